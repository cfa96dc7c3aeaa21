#pragma once
// shade: header-only C++20 shading, BRDF and ray-intersection library on GLM.
// This umbrella header includes every public header. Conventions: shade/core/frame.hpp.

#include <shade/version.hpp>

#include <shade/core/config.hpp>
#include <shade/core/error.hpp>
#include <shade/core/frame.hpp>
#include <shade/core/math.hpp>
#include <shade/core/surface_point.hpp>
#include <shade/core/types.hpp>

#include <shade/brdf/brdf.hpp>
#include <shade/light/light_sample.hpp>
#include <shade/shading/shader.hpp>
