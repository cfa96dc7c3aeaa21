#include <shade/geometry/detail/triangle_batch_kernel.hpp>
