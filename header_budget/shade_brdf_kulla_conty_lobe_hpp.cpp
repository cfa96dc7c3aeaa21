#include <shade/brdf/kulla_conty_lobe.hpp>
