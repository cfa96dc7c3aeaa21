#include <shade/light/environment_map.hpp>
