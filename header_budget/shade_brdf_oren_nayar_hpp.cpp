#include <shade/brdf/oren_nayar.hpp>
