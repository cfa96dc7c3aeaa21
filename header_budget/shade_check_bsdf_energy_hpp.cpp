#include <shade/check/bsdf_energy.hpp>
