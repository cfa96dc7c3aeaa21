#include <shade/bsdf/detail/dielectric_anisotropic_albedo_data.hpp>
