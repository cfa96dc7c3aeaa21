#include <shade/light/point.hpp>
