#include <shade/light/spot.hpp>
