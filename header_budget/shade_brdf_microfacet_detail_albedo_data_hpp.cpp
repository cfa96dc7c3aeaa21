#include <shade/brdf/microfacet/detail/albedo_data.hpp>
