#include <shade/core/scalar.hpp>
