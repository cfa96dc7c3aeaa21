#include <shade/check/chi2.hpp>
