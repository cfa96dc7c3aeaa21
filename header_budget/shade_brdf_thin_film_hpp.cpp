#include <shade/brdf/thin_film.hpp>
