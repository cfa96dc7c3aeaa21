#include <shade/light/environment.hpp>
