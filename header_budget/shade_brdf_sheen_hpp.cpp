#include <shade/brdf/sheen.hpp>
