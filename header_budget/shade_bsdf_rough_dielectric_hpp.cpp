#include <shade/bsdf/rough_dielectric.hpp>
