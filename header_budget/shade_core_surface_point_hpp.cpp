#include <shade/core/surface_point.hpp>
