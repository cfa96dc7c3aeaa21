#include <shade/core/alias_table.hpp>
