#include <shade/bsdf/dielectric_albedo_table.hpp>
