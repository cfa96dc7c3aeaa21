#include <shade/geometry/triangle_batch.hpp>
