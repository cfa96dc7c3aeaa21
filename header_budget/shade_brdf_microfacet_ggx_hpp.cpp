#include <shade/brdf/microfacet/ggx.hpp>
