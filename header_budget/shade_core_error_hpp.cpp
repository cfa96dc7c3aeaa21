#include <shade/core/error.hpp>
