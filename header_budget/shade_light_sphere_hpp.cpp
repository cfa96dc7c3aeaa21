#include <shade/light/sphere.hpp>
