#include <shade/brdf/fresnel.hpp>
