#include <shade/color/srgb.hpp>
