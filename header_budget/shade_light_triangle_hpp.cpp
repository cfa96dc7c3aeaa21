#include <shade/light/triangle.hpp>
