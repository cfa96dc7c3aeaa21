#include <shade/brdf/lambert.hpp>
