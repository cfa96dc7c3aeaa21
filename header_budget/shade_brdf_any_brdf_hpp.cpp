#include <shade/brdf/any_brdf.hpp>
