#include <shade/check/detail/model_ref.hpp>
