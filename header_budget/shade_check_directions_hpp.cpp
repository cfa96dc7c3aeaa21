#include <shade/check/directions.hpp>
