#include <shade/core/math.hpp>
