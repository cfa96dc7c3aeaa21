#include <shade/bsdf/detail/dielectric_reflection_albedo_data.hpp>
