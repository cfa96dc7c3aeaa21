#include <shade/shade.hpp>
