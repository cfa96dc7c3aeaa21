#include <shade/shading/sum_over_lights.hpp>
