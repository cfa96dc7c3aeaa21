#include <shade/bsdf/thin_dielectric.hpp>
