#include <shade/geometry/ray.hpp>
