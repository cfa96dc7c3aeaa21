#include <shade/brdf/microfacet.hpp>
