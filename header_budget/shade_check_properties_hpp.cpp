#include <shade/check/properties.hpp>
