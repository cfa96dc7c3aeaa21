#include <shade/bsdf/detail/dielectric_anisotropic_reflection_albedo_data.hpp>
