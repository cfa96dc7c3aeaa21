#include <shade/light/light.hpp>
