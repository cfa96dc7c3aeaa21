#include <shade/geometry/bvh.hpp>
