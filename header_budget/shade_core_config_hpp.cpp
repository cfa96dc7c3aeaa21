#include <shade/core/config.hpp>
