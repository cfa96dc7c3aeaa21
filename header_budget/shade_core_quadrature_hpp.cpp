#include <shade/core/quadrature.hpp>
