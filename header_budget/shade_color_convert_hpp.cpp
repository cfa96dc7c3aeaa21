#include <shade/color/convert.hpp>
