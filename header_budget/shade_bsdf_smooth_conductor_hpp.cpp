#include <shade/bsdf/smooth_conductor.hpp>
