#include <shade/brdf/microfacet/beckmann.hpp>
