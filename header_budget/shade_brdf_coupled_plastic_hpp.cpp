#include <shade/brdf/coupled_plastic.hpp>
