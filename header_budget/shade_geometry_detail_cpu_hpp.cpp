#include <shade/geometry/detail/cpu.hpp>
