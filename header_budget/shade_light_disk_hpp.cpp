#include <shade/light/disk.hpp>
