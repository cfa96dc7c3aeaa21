#include <shade/geometry/detail/triangle_batch_vector.hpp>
