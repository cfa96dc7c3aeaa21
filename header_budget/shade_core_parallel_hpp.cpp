#include <shade/core/parallel.hpp>
