#include <shade/light/bvh_light_sampler.hpp>
