#include <shade/light/delta_light.hpp>
