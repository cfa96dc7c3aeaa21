#include <shade/brdf/metals.hpp>
