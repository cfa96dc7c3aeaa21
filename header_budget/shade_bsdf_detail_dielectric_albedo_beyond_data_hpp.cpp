#include <shade/bsdf/detail/dielectric_albedo_beyond_data.hpp>
