#include <shade/brdf/microfacet/detail/anisotropic_strong_albedo_data.hpp>
