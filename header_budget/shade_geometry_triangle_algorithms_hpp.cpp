#include <shade/geometry/triangle_algorithms.hpp>
