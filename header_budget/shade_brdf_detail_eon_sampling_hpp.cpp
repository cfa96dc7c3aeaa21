#include <shade/brdf/detail/eon_sampling.hpp>
