#include <shade/shading/gooch.hpp>
