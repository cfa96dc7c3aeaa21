#include <shade/brdf/ggx_dielectric_coating.hpp>
