#include <shade/brdf/microfacet/anisotropic_albedo_table.hpp>
