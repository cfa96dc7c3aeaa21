#include <shade/brdf/blinn_phong.hpp>
