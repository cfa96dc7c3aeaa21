#include <shade/check/doctest.hpp>
