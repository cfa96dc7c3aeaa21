#include <shade/material/openpbr_presets.hpp>
