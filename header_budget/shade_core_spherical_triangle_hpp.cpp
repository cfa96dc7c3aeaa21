#include <shade/core/spherical_triangle.hpp>
