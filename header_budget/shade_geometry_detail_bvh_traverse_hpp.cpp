#include <shade/geometry/detail/bvh_traverse.hpp>
