#include <shade/core/distribution.hpp>
