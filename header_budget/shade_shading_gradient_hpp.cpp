#include <shade/shading/gradient.hpp>
