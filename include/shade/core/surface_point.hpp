#pragma once
// shade::surface_point: what a reflection model may know about the point it shades.

#include <cmath>
#include <concepts>

#include <glm/geometric.hpp>

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

    /// A point at p with unit normal n, surface parameters uv and the tangent frame of
    /// `tangent` (e.g. dp/du, any length): t is tangent's part perpendicular to n, made
    /// unit, and b = cross(n, t). Where that part is zero or not finite (no tangent known),
    /// the arbitrary frame of at(p, n) instead; never throws.
    [[nodiscard]] static surface_point at(const vec3<T>& p, const vec3<T>& n, const vec3<T>& tangent,
                                          const vec2<T>& uv) noexcept {
        surface_point s = at(p, n);
        s.uv = uv;
        const vec3<T> ortho = tangent - n * glm::dot(n, tangent);
        // Divided by its largest component first, so that squaring a tiny or huge tangent
        // neither underflows nor overflows.
        const T m = std::fmax(std::fabs(ortho.x), std::fmax(std::fabs(ortho.y), std::fabs(ortho.z)));
        if (!(m > T(0)) || !std::isfinite(m)) return s;
        const vec3<T> w = ortho / m;
        s.shading.t = w / glm::length(w);
        s.shading.b = glm::cross(n, s.shading.t);
        return s;
    }
};

} // namespace shade
