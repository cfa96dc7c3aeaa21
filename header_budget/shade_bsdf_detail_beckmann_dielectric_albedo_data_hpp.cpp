#include <shade/bsdf/detail/beckmann_dielectric_albedo_data.hpp>
