#include <shade/geometry/hit.hpp>
