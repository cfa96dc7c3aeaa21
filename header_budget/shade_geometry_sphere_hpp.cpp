#include <shade/geometry/sphere.hpp>
