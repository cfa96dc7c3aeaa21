#include <shade/light/light_bounds_of.hpp>
