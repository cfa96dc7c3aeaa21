#include <shade/brdf/microfacet/detail/anisotropic_albedo_data.hpp>
