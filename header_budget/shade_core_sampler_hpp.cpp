#include <shade/core/sampler.hpp>
