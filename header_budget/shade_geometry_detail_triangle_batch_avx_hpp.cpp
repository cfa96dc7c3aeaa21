#include <shade/geometry/detail/triangle_batch_avx.hpp>
