#pragma once
// Hit records returned (inside std::optional) by the intersection routines of
// shade/geometry, and the face-culling switch they accept.
//
// Normal convention: a hit's normal n is the surface's own geometric, outward unit normal,
// independent of the ray. front_face says which side the ray struck: true when the ray
// arrived from the side n points into (dot(direction, n) < 0 for plane and triangle; the
// entering root for a sphere). facing_normal() gives n flipped toward the ray's origin,
// which is what shading with the "away from the surface" convention of
// shade/core/frame.hpp wants.
//
// Rounding: p_error bounds, per coordinate, how far the computed p can be from the exact
// point of the surface that the record describes (|p - p_exact| <= p_error in each
// coordinate), with Higham's gamma_n = n u / (1 - n u) bounds (Higham 2002, "Accuracy and
// Stability of Numerical Algorithms", 2nd ed., sec. 3.1; their use for ray origins: Pharr,
// Jakob, Humphreys 2023, "Physically Based Rendering", 4th ed., sec. 6.8).
// shade::spawn_ray (shade/geometry/spawn.hpp) moves a new ray's origin off the surface by
// it, so that the ray cannot hit the surface it starts on.
//
// Parameterisation: uv are the surface parameters of p and dpdu the tangent dp/du (not
// unit length). Every shape's (u, v) is right-handed about the outward normal:
// cross(dp/du, dp/dv) points along n (for a triangle, with its default barycentric uv or
// per-vertex uv that are not mirrored). surface_at(h) builds the shading frame from them.

#include <cmath>
#include <concepts>
#include <cstdint>
#include <limits>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <shade/core/config.hpp>
#include <shade/core/math.hpp>
#include <shade/core/surface_point.hpp>
#include <shade/core/types.hpp>

namespace shade {

/// Which faces an intersection routine may report.
///   none:       double-sided (the default): front and back faces are hit.
///   back_faces: back-face culling: only hits with front_face == true are reported.
enum class culling { none, back_faces };

/// Where a ray met a surface.
template <std::floating_point T>
struct hit {
    using scalar_type = T;

    T t = T(0);            ///< ray parameter of the hit, in units of the ray's direction
    vec3<T> p{0, 0, 0};    ///< world-space hit point
    vec3<T> n{0, 0, 1};    ///< geometric outward unit normal of the surface at p
    bool front_face = true; ///< true when the ray struck the side n points into
    vec2<T> uv{0, 0};      ///< surface parameters (u, v) of p; the shape says how they map
    vec3<T> dpdu{0, 0, 0}; ///< tangent dp/du at p, perpendicular to n, zero where undefined
    vec3<T> p_error{0, 0, 0}; ///< bound on |p - exact point| per coordinate (see "Rounding" above)

    /// n if the ray struck the front face, -n otherwise: the unit normal on the side of
    /// the ray's origin.
    [[nodiscard]] constexpr vec3<T> facing_normal() const noexcept {
        return front_face ? n : -n;
    }
};

/// A hit on a triangle (v0, v1, v2): a hit plus barycentric coordinates.
///
/// barycentric = (b0, b1, b2) are the weights of v0, v1, v2: b0 + b1 + b2 = 1, all >= 0,
/// and p = b0 v0 + b1 v1 + b2 v2. The common (u, v) pair is u = b1, v = b2, so that
/// p = v0 + u (v1 - v0) + v (v2 - v0).
template <std::floating_point T>
struct triangle_hit : hit<T> {
    vec3<T> barycentric{1, 0, 0}; ///< (b0, b1, b2): weights of v0, v1, v2

    /// Weight of v1 (b1).
    [[nodiscard]] constexpr T u() const noexcept { return barycentric.y; }
    /// Weight of v2 (b2).
    [[nodiscard]] constexpr T v() const noexcept { return barycentric.z; }
};

/// The shading point of hit h: position h.p, uv h.uv, and the frame whose normal is
/// h.facing_normal() (the side the ray came from) and whose tangent t is dp/du made unit
/// (shade::surface_point::at with a tangent; where dp/du is zero, as at a sphere's poles,
/// an arbitrary tangent). On a back-face hit the normal is -n, so the bitangent
/// b = cross(-n, t) points against dp/dv: the frame stays right-handed.
template <std::floating_point T>
[[nodiscard]] surface_point<T> surface_at(const hit<T>& h) noexcept {
    return surface_point<T>::at(h.p, h.facing_normal(), h.dpdu, h.uv);
}

/// The nearest hit found by a hierarchy (shade::bvh, primitive_bvh, triangle_bvh): the
/// primitive's index (its position in the span the hierarchy was built from) and the
/// primitive test's record.
template <class H>
struct primitive_hit {
    std::uint32_t primitive = 0; ///< index of the primitive hit
    H hit{};                     ///< what the primitive test returned (t, and so on)
};

namespace detail {

/// Higham's gamma_n = n u / (1 - n u), with u = epsilon / 2 the unit roundoff of T: a
/// computation of n roundings has relative error at most gamma_n (Higham 2002, lemma 3.1).
template <std::floating_point T>
[[nodiscard]] constexpr T gamma(int n) noexcept {
    constexpr T u = std::numeric_limits<T>::epsilon() / 2;
    return (T(n) * u) / (T(1) - T(n) * u);
}

/// v / |v| without underflow or overflow: v is first divided by its largest absolute
/// component (so the squares below lie in [0, 3]), then normalised. Returns the zero
/// vector when v is zero or not finite; callers treat that as "no valid normal".
template <std::floating_point T>
[[nodiscard]] inline vec3<T> normalize_or_zero(const vec3<T>& v) noexcept {
    const T m = glm::max(std::abs(v.x), glm::max(std::abs(v.y), std::abs(v.z)));
    if (!(m > T(0)) || !std::isfinite(m)) return vec3<T>(0, 0, 0);
    const vec3<T> w = v / m;
    return w / glm::length(w);
}

/// v / |v| for a v whose length is known in advance up to a small factor: scale = 2^k
/// with that length times 2^k in [0.5, 1) (times_power_of_two(T(1), k), +infinity when
/// 2^k is not a T). Then w = v scale is exact and w·w cannot overflow or underflow, so
/// w / |w| is the answer, each component correctly rounded, and the scale can be
/// computed before v is known (ray/sphere takes it from the radius, off the dependency
/// chain that ends in v). Where |w| is outside [1/4, 4] (v far from its expected
/// length) or scale is infinite, normalize_or_zero decides instead.
template <std::floating_point T>
[[nodiscard]] inline vec3<T> normalize_expected_length(const vec3<T>& v, T scale) noexcept {
    const vec3<T> w = v * scale;
    const T w2 = glm::dot(w, w);
    if (w2 >= T(0.0625) && w2 <= T(16)) return w / std::sqrt(w2);
    return normalize_or_zero(v);
}

/// True when the zero-or-unit vector from normalize_or_zero is a usable unit normal.
template <std::floating_point T>
[[nodiscard]] inline bool is_unit_normal(const vec3<T>& n) noexcept {
    return is_finite(n) && (n.x != T(0) || n.y != T(0) || n.z != T(0));
}

/// True when t is finite and in the ray's closed interval [t_min, t_max]. NaN fails, and
/// so does an infinite t even when t_max is +infinity (a hit must be a point).
template <std::floating_point T>
[[nodiscard]] inline bool in_interval(T t, T t_min, T t_max) noexcept {
    return std::isfinite(t) && t >= t_min && t <= t_max;
}

} // namespace detail

} // namespace shade
