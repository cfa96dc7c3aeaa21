#include <shade/bsdf/dielectric_anisotropic_reflection_table.hpp>
