#include <shade/geometry/camera.hpp>
