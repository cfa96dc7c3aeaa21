#include <shade/brdf/microfacet/masking.hpp>
