#include <shade/brdf/aliases.hpp>
