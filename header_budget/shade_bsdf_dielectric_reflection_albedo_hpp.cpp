#include <shade/bsdf/dielectric_reflection_albedo.hpp>
