#include <shade/bsdf/mix.hpp>
