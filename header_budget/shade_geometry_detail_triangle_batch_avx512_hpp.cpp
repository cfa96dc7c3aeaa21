#include <shade/geometry/detail/triangle_batch_avx512.hpp>
