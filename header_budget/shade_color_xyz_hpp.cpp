#include <shade/color/xyz.hpp>
