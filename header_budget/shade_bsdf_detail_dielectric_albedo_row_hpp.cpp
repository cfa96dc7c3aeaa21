#include <shade/bsdf/detail/dielectric_albedo_row.hpp>
