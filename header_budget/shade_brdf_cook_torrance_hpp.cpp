#include <shade/brdf/cook_torrance.hpp>
