#include <shade/brdf/microfacet/albedo_table.hpp>
