#include <shade/light/any_light.hpp>
