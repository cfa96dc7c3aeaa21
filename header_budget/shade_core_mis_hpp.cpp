#include <shade/core/mis.hpp>
