#include <shade/check/bsdf_reciprocity.hpp>
