#include <shade/bsdf/detail/lobe_pair.hpp>
