#include <shade/brdf/microfacet/detail/cosine_weight_data.hpp>
