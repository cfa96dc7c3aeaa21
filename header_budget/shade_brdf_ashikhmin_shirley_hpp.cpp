#include <shade/brdf/ashikhmin_shirley.hpp>
