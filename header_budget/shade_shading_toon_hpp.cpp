#include <shade/shading/toon.hpp>
