#include <shade/brdf/anisotropic_multiple_scattering.hpp>
