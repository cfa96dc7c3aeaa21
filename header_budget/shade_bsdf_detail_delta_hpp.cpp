#include <shade/bsdf/detail/delta.hpp>
