#include <shade/bsdf/rough_dielectric_albedo_grid.hpp>
