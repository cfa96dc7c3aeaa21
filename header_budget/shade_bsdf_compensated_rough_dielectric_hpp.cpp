#include <shade/bsdf/compensated_rough_dielectric.hpp>
