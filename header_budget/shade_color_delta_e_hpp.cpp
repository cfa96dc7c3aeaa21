#include <shade/color/delta_e.hpp>
