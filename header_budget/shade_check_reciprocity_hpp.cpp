#include <shade/check/reciprocity.hpp>
