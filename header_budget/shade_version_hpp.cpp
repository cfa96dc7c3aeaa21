#include <shade/version.hpp>
