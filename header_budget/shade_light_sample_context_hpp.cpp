#include <shade/light/sample_context.hpp>
