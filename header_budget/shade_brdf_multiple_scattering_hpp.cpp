#include <shade/brdf/multiple_scattering.hpp>
