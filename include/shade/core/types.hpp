#pragma once
// Vector and colour types: shade uses GLM's vectors directly, generic on the scalar.

#include <concepts>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace shade {

/// A 3-vector (point or direction) of scalar T, T float or double.
template <std::floating_point T>
using vec3 = glm::vec<3, T>;

/// A 2-vector of scalar T (pixel coordinates, sample pairs, texture coordinates).
template <std::floating_point T>
using vec2 = glm::vec<2, T>;

/// Linear RGB colour (not sRGB-encoded). Same type as vec3; the name documents intent.
template <std::floating_point T>
using rgb = glm::vec<3, T>;

} // namespace shade
