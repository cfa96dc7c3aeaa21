#include <shade/geometry/detail/bvh_build.hpp>
