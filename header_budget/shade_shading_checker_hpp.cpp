#include <shade/shading/checker.hpp>
