#include <shade/light/classic_light.hpp>
