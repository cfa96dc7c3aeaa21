#include <shade/core/random.hpp>
