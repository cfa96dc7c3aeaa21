#include <shade/core/sobol.hpp>
