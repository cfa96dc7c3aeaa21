#include <shade/light/area_emitter.hpp>
