#include <shade/light/emission.hpp>
