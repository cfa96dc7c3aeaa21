#include <shade/geometry/triangle.hpp>
