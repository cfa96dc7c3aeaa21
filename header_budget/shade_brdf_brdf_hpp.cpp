#include <shade/brdf/brdf.hpp>
