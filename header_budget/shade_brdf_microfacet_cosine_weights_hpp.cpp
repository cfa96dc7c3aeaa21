#include <shade/brdf/microfacet/cosine_weights.hpp>
