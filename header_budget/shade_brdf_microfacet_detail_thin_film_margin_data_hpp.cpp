#include <shade/brdf/microfacet/detail/thin_film_margin_data.hpp>
