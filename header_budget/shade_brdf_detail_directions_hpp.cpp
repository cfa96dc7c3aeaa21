#include <shade/brdf/detail/directions.hpp>
