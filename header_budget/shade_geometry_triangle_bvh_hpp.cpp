#include <shade/geometry/triangle_bvh.hpp>
