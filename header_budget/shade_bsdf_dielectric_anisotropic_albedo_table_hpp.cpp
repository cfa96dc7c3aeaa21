#include <shade/bsdf/dielectric_anisotropic_albedo_table.hpp>
