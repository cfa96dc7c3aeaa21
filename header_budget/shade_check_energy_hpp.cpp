#include <shade/check/energy.hpp>
