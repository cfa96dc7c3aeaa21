#include <shade/bsdf/detail/dielectric_albedo_data.hpp>
