#include <shade/brdf/detail/sampling.hpp>
