#include <shade/bsdf/detail/beckmann_dielectric_albedo_beyond_data.hpp>
