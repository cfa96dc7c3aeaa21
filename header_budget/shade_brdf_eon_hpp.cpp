#include <shade/brdf/eon.hpp>
