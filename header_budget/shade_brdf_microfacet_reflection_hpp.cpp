#include <shade/brdf/microfacet_reflection.hpp>
