#include <shade/bsdf/refract.hpp>
