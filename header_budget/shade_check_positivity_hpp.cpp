#include <shade/check/positivity.hpp>
