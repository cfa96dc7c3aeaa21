#include <shade/bsdf/smooth_dielectric.hpp>
