#include <shade/color/lab.hpp>
