#include <shade/geometry/spawn.hpp>
