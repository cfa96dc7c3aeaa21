#include <shade/light/light_sample.hpp>
