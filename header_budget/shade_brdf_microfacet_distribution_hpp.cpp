#include <shade/brdf/microfacet/distribution.hpp>
