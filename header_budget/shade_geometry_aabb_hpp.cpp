#include <shade/geometry/aabb.hpp>
