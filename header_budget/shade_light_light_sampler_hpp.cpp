#include <shade/light/light_sampler.hpp>
