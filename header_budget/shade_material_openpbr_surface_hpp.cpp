#include <shade/material/openpbr_surface.hpp>
