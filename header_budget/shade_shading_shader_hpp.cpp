#include <shade/shading/shader.hpp>
