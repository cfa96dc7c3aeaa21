#include <shade/core/sampling.hpp>
