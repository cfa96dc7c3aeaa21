#include <shade/check/sampling.hpp>
