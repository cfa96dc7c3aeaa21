#include <shade/brdf/phong.hpp>
