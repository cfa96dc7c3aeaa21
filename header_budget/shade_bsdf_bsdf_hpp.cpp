#include <shade/bsdf/bsdf.hpp>
