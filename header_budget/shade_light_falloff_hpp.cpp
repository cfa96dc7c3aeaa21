#include <shade/light/falloff.hpp>
