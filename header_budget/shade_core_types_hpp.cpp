#include <shade/core/types.hpp>
