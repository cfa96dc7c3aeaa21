#pragma once
// The surface point the model tests of tests/check evaluate every shipped BRDF at.

#include <glm/geometric.hpp>

#include <shade/core/frame.hpp>
#include <shade/core/surface_point.hpp>

namespace check_test {

/// A point off the origin with a tilted normal and a tangent from +x, so the checks are
/// seen to use the frame of `at` and anisotropic models are tested off-axis.
template <class T>
shade::surface_point<T> model_point() {
    const auto n = glm::normalize(shade::vec3<T>(T(0.2), T(0.3), T(1)));
    shade::surface_point<T> at;
    at.p = {T(0.25), T(-1.5), T(2)};
    at.shading = shade::frame<T>::from_normal_tangent(n, {1, 0, 0});
    return at;
}

} // namespace check_test
