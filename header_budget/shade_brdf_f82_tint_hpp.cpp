#include <shade/brdf/f82_tint.hpp>
