#pragma once
// shade::surface_point: what a reflection model may know about the point it shades.

#include <cmath>
#include <concepts>

#include <glm/geometric.hpp>

#include <shade/core/config.hpp>
#include <shade/core/error.hpp>
#include <shade/core/frame.hpp>
#include <shade/core/math.hpp>
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

    /// A point at p with normal n and an arbitrary tangent frame. Unchecked: the caller
    /// promises a finite p and a unit-length n (checked only by SHADE_ASSERT in debug
    /// builds); a longer or shorter n gives a frame that is not orthonormal and wrong
    /// shading. Use checked() for untrusted input.
    [[nodiscard]] static surface_point at(const vec3<T>& p, const vec3<T>& n) noexcept {
        SHADE_ASSERT(is_unit_length(n));
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

    /// As at(), validated: throws shade::invalid_parameter naming "p" unless p is finite
    /// and naming "n" unless n is a finite unit vector (|n|^2 within 1e-3 of 1,
    /// shade::is_unit_length). n is used as given, not renormalised.
    [[nodiscard]] static surface_point checked(const vec3<T>& p, const vec3<T>& n) {
        (void)require_finite("p", p);
        (void)require_unit_length("n", n);
        return at(p, n);
    }
};

} // namespace shade
