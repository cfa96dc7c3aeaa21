#include <shade/material/openpbr_parameters.hpp>
