#include <shade/geometry/plane.hpp>
