#include <shade/light/directional.hpp>
