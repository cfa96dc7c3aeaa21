#pragma once
// shade::sphere and ray/sphere intersection, numerically stable for far-away and
// off-centre spheres.

#include <algorithm>
#include <cmath>
#include <concepts>
#include <optional>

#include <glm/geometric.hpp>

#include <shade/core/error.hpp>
#include <shade/core/math.hpp>
#include <shade/core/types.hpp>
#include <shade/geometry/hit.hpp>
#include <shade/geometry/ray.hpp>

namespace shade {

/// A sphere with centre `center` and radius `radius` > 0; its front side is the outside.
template <std::floating_point T>
class sphere {
public:
    using scalar_type = T;

    /// Throws shade::invalid_parameter naming "center" if center is not finite, or
    /// "radius" unless radius is finite and > 0.
    sphere(const vec3<T>& center, T radius)
        : center_(require_finite("center", center)), radius_(require_positive("radius", radius)) {}

    /// The centre.
    [[nodiscard]] const vec3<T>& center() const noexcept { return center_; }
    /// The radius (> 0).
    [[nodiscard]] T radius() const noexcept { return radius_; }

private:
    vec3<T> center_;
    T radius_;
};

namespace detail {

/// -e for the e with max|v_i| = m * 2^e, m in [0.5, 1): std::ldexp(v_i, -e) rescales v so
/// its largest component lies in [0.5, 1) without any rounding (a power of two), so that
/// v·v can neither overflow nor underflow. Returned as an exponent, not as the factor
/// 2^-e, because that factor overflows to infinity when m is subnormal (float: m < 2^-126
/// has e down to -148, and 2^148 is not a float). Precondition: v finite and non-zero.
template <std::floating_point T>
[[nodiscard]] inline int power_of_two_rescale_exponent(const vec3<T>& v) noexcept {
    const T m = std::max(std::abs(v.x), std::max(std::abs(v.y), std::abs(v.z)));
    int e = 0;
    (void)std::frexp(m, &e);
    return -e;
}

} // namespace detail

/// The first hit of ray r with sphere s inside [t_min, t_max], or nothing.
///
/// With f = o - c, substituting o + t d into |x - c|^2 = R^2 gives
///     a t^2 - 2 b t + c_0 = 0,   a = d·d,  b = -f·d,  c_0 = f·f - R^2,
/// whose roots are (b ± sqrt(b^2 - a c_0)) / a. Two precision fixes, from
/// Haines, Günther, Akenine-Möller 2019, "Precision Improvements for Ray/Sphere
/// Intersection", Ray Tracing Gems ch. 7, §7.2:
///   * the discriminant is evaluated as b^2 - a c_0 = a (R^2 - |l|^2) with
///     l = f + (b/a) d, the part of f perpendicular to the ray (Hearn and Baker's form).
///     The textbook b^2 - a c_0 subtracts two numbers of size |f|^2 and loses everything
///     when the sphere is far away (|f| = 1e6, R = 1: all digits in float);
///   * the two roots are t_1 = q / a and t_0 = c_0 / q with q = b + sign(b) sqrt(a Δ),
///     so no root is computed as a difference of nearly equal numbers (Press, Teukolsky,
///     Vetterling, Flannery, Numerical Recipes, §5.6, eqs. 5.6.4-5.6.5).
/// The direction is first rescaled by a power of two (exact) so that a = d·d cannot
/// overflow or underflow for huge or tiny directions; t is scaled back.
///
/// Returns the nearer root in [t_min, t_max] (front_face = true: the ray enters), else the
/// farther one (front_face = false: the ray leaves, e.g. when the origin is inside).
/// A tangent ray (discriminant exactly 0) returns its single touching point as an
/// entering hit. The normal is the outward unit normal (p - c) / R, normalised again.
/// No hit for an invalid ray, a negative discriminant or roots outside [t_min, t_max].
template <std::floating_point T>
[[nodiscard]] std::optional<hit<T>> intersect(const ray<T>& r, const sphere<T>& s) noexcept {
    if (!r.valid()) return std::nullopt;
    const int scale = detail::power_of_two_rescale_exponent(r.direction);
    // d = direction * 2^scale, exact (a component more than the exponent range below the
    // largest may underflow, far below rounding); t for d is t_user / 2^scale.
    const vec3<T> d(std::ldexp(r.direction.x, scale), std::ldexp(r.direction.y, scale),
                    std::ldexp(r.direction.z, scale));
    const vec3<T> f = r.origin - s.center();
    const T radius = s.radius();

    const T a = glm::dot(d, d);
    const T b = -glm::dot(f, d);
    const vec3<T> l = f + (b / a) * d;
    const T delta = sqr(radius) - glm::dot(l, l); // = (b^2 - a c_0) / a
    if (!(delta >= T(0))) return std::nullopt;      // also rejects NaN

    const T c0 = glm::dot(f, f) - sqr(radius);
    const T q = b + std::copysign(std::sqrt(a * delta), b);
    // q == 0 only when b == 0 and delta == 0: then c_0 = |l|^2 - R^2 = 0 and both roots
    // are 0; c_0 / q would be 0/0.
    const T root_a = q / a;
    const T root_b = q != T(0) ? c0 / q : T(0);
    const T t_near = std::ldexp(std::min(root_a, root_b), scale);
    const T t_far = std::ldexp(std::max(root_a, root_b), scale);

    T t;
    bool entering;
    if (detail::in_interval(t_near, r.t_min, r.t_max)) {
        t = t_near;
        entering = true;
    } else if (detail::in_interval(t_far, r.t_min, r.t_max)) {
        t = t_far;
        entering = false;
    } else {
        return std::nullopt;
    }
    const vec3<T> p = r.at(t);
    const vec3<T> n = detail::normalize_or_zero((p - s.center()) / radius);
    if (!is_finite(p) || !detail::is_unit_normal(n)) return std::nullopt;
    return hit<T>{t, p, n, entering};
}

} // namespace shade
