#include <shade/light/light_bounds.hpp>
