#pragma once
// shade::surface_point: what a reflection model may know about the point it shades.

#include <concepts>

#include <shade/core/frame.hpp>
#include <shade/core/types.hpp>

namespace shade {

/// A point on a surface together with its shading frame. Reflection models receive it as
/// `at` so that anisotropic models can use the tangents and spatially varying combinators
/// (checker, gradient) can use the position.
template <std::floating_point T>
struct surface_point {
    using scalar_type = T;

    vec3<T> p{0, 0, 0}; ///< world-space position
    frame<T> shading{}; ///< orthonormal shading frame; shading.n is the shading normal
    vec2<T> uv{0, 0};   ///< surface parameterisation, for 2D patterns (0 when unknown)

    /// The shading normal.
    [[nodiscard]] constexpr const vec3<T>& n() const noexcept { return shading.n; }

    /// A point at p with normal n (unit length) and an arbitrary tangent frame.
    [[nodiscard]] static surface_point at(const vec3<T>& p, const vec3<T>& n) noexcept {
        surface_point s;
        s.p = p;
        s.shading = frame<T>::from_normal(n);
        return s;
    }
};

} // namespace shade
