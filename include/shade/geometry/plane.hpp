#pragma once
// shade::plane and ray/plane intersection.

#include <cmath>
#include <concepts>
#include <limits>
#include <optional>

#include <glm/geometric.hpp>

#include <shade/core/error.hpp>
#include <shade/core/frame.hpp>
#include <shade/core/types.hpp>
#include <shade/geometry/hit.hpp>
#include <shade/geometry/ray.hpp>

namespace shade {

/// An infinite plane through `point` with unit normal `normal`; its front side is the one
/// the normal points into. Its parameterisation is Cartesian, in world units, in the
/// orthonormal frame (tangent, bitangent, normal): the point point + u tangent +
/// v bitangent has uv = (u, v), so dp/du = tangent, dp/dv = bitangent and
/// cross(tangent, bitangent) = normal.
template <std::floating_point T>
class plane {
public:
    using scalar_type = T;

    /// Throws shade::invalid_parameter naming "point" if point is not finite, or "normal"
    /// if normal is zero or not finite. normal may have any length; it is normalised. The
    /// tangent is that of shade::frame::from_normal (an arbitrary, fixed direction).
    plane(const vec3<T>& point, const vec3<T>& normal)
        : point_(require_finite("point", point)),
          axes_(frame<T>::from_normal(require_direction("normal", normal))) {}

    /// As plane(point, normal), with the u axis along `tangent` made perpendicular to the
    /// normal (shade::frame::from_normal_tangent, which throws naming "tangent" if it is
    /// zero, not finite or parallel to the normal).
    plane(const vec3<T>& point, const vec3<T>& normal, const vec3<T>& tangent)
        : point_(require_finite("point", point)),
          axes_(frame<T>::from_normal_tangent(normal, tangent)) {}

    /// A point on the plane: uv = (0, 0).
    [[nodiscard]] const vec3<T>& point() const noexcept { return point_; }
    /// The plane's unit normal (front side).
    [[nodiscard]] const vec3<T>& normal() const noexcept { return axes_.n; }
    /// The unit u axis dp/du, perpendicular to the normal.
    [[nodiscard]] const vec3<T>& tangent() const noexcept { return axes_.t; }
    /// The unit v axis dp/dv = cross(normal, tangent).
    [[nodiscard]] const vec3<T>& bitangent() const noexcept { return axes_.b; }

private:
    vec3<T> point_;
    frame<T> axes_;
};

namespace detail {

/// The rounding bound, in every coordinate, of the point p = o + t d where t = n·(q - o) / n·d
/// is a ray's parameter at a plane with unit normal n through q (shade::intersect with a
/// plane, and the rectangle and disk lights). The distance of p from the plane,
/// n·(p - q) = n·(o - q) + t (n·d) + the rounding of o + t d, is the error of n·(q - o)
/// (gamma_4), of the division (u), of n·d times t (gamma_3) and of the sum (gamma_2),
/// together below gamma_8 (|o|_1 + |q|_1 + |t d|_1), bounding each |x|_2 by |x|_1 (Higham's
/// gamma_n = n u / (1 - n u); Pharr, Jakob, Humphreys 2023, "Physically Based Rendering",
/// 4th ed., sec. 6.8). It is given in every coordinate, so that spawn_ray's offset,
/// dot(|n|, p_error) = p_error |n|_1 >= p_error, clears it whatever n is. Coordinates near
/// overflow make the sum infinite: the largest finite bound instead.
template <std::floating_point T>
[[nodiscard]] inline vec3<T> plane_hit_error(const vec3<T>& o, const vec3<T>& q, T t, const vec3<T>& d) noexcept {
    const auto l1 = [](const vec3<T>& v) { return std::abs(v.x) + std::abs(v.y) + std::abs(v.z); };
    const T e = gamma<T>(8) * (l1(o) + l1(q) + l1(t * d));
    return vec3<T>(std::isfinite(e) ? e : std::numeric_limits<T>::max());
}

} // namespace detail

/// The hit of ray r with plane pl, or nothing.
///
/// Ray/plane intersection (Haines 1989, "Essential Ray Tracing Algorithms", in Glassner
/// (ed.), An Introduction to Ray Tracing, section on ray/plane intersection): with n the
/// unit normal and q a point of the plane, n·(o + t d - q) = 0 gives
///     t = n·(q - o) / n·d.
/// Returns the hit with that t, p = o + t d (p_error bounding its distance from the plane),
/// the plane's normal, front_face = (n·d < 0),
/// uv = the coordinates of p - point() along tangent() and bitangent(), dpdu = tangent().
/// No hit when r is not valid(), when n·d == 0 exactly (ray parallel to the plane, also
/// when it lies in it; no epsilon, so nearly parallel rays hit far away as they should),
/// when t is outside [t_min, t_max] or not finite, or, with culling::back_faces, when the
/// ray arrives from the back (n·d > 0).
///
/// Declared inline (a hint a template does not otherwise carry) so that g++ inlines it
/// into loops of shadow rays, where most tests stop early at t outside [t_min, t_max].
template <std::floating_point T>
[[nodiscard]] inline std::optional<hit<T>> intersect(const ray<T>& r, const plane<T>& pl,
                                              culling cull = culling::none) noexcept {
    // The one test of the ray itself: valid() would also check that origin and direction
    // are finite and the direction non-zero, but those need no test of their own here. A
    // zero direction makes n·d zero; a non-finite origin makes t infinite or NaN; a
    // non-finite direction makes n·d infinite or NaN, so t is NaN or ±0, and at t = ±0 the
    // point o + t d is NaN. Each case is rejected below. t_max < t_min or a NaN bound
    // leaves no t in [t_min, t_max].
    //
    // Every return below returns `out`, filled field by field, so that it is built in the
    // caller's storage (named return value optimisation). A returned temporary
    // hit<T>{t, p, n, ...} is assembled by g++ 12 -O3 on the stack with 4- and 8-byte
    // stores and copied with 16-byte loads, which the CPU cannot forward from those stores.
    std::optional<hit<T>> out;
    if (!(r.t_min >= T(0))) return out;
    const vec3<T>& n = pl.normal();
    const T n_dot_d = glm::dot(n, r.direction);
    if (n_dot_d == T(0)) return out;
    if (cull == culling::back_faces && !(n_dot_d < T(0))) return out;
    const T t = glm::dot(n, pl.point() - r.origin) / n_dot_d;
    if (!detail::in_interval(t, r.t_min, r.t_max)) return out;
    const vec3<T> p = r.at(t);
    if (!is_finite(p)) return out;
    out.emplace();
    out->t = t;
    out->p = p;
    out->n = n;
    out->front_face = n_dot_d < T(0);
    out->p_error = detail::plane_hit_error(r.origin, pl.point(), t, r.direction);
    const vec3<T> offset = p - pl.point();
    out->uv = vec2<T>(glm::dot(offset, pl.tangent()), glm::dot(offset, pl.bitangent()));
    out->dpdu = pl.tangent();
    return out;
}

} // namespace shade
