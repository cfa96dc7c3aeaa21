#include <shade/brdf/detail/power_lobe.hpp>
