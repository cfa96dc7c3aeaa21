#include <shade/core/frame.hpp>
