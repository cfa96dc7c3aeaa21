#include <shade/check/result.hpp>
