#include <shade/bsdf/layer.hpp>
