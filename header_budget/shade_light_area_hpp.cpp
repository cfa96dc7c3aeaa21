#include <shade/light/area.hpp>
