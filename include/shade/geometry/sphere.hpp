#pragma once
// shade::sphere and ray/sphere intersection, numerically stable for far-away and
// off-centre spheres.

#include <cmath>
#include <concepts>
#include <optional>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <shade/core/error.hpp>
#include <shade/core/math.hpp>
#include <shade/core/types.hpp>
#include <shade/geometry/aabb.hpp>
#include <shade/geometry/hit.hpp>
#include <shade/geometry/ray.hpp>

namespace shade {

/// A sphere with centre `center` and radius `radius` > 0; its front side is the outside.
///
/// Parameterisation (latitude-longitude, right-handed about the outward normal): the point
/// c + R (sin θ cos φ, sin θ sin φ, cos θ) has uv = (φ / 2π, 1 - θ / π), φ in [0, 2π), so
/// u runs once around the z axis from +x toward +y and v from 0 at the south pole (-z) to
/// 1 at the north pole (+z). Differentiating,
///     dp/du = 2π R sin θ (-sin φ, cos φ, 0) = 2π R (-n_y, n_x, 0),
///     dp/dv = π R (-cos θ cos φ, -cos θ sin φ, sin θ),
/// and cross(dp/du, dp/dv) points along the outward normal n. dp/du is zero at the poles,
/// where the parameterisation is singular.
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

/// The uv of the point with outward unit normal n on a sphere (see shade::sphere):
/// u = φ / 2π with φ = atan2(n_y, n_x) moved into [0, 2π), and v = 1 - θ / π computed as
/// atan2(sqrt(n_x² + n_y²), -n_z) / π, which is accurate near the poles where acos(n_z)
/// loses digits.
template <std::floating_point T>
[[nodiscard]] inline vec2<T> sphere_uv(const vec3<T>& n) noexcept {
    T phi = std::atan2(n.y, n.x);
    if (phi < T(0)) phi += T(2) * pi<T>;
    const T u = phi / (T(2) * pi<T>);
    const T v = std::atan2(std::sqrt(n.x * n.x + n.y * n.y), -n.z) / pi<T>;
    // φ just below 0 can round up to 2π when moved; u stays in [0, 1).
    return vec2<T>(u < T(1) ? u : T(0), v);
}

} // namespace detail

/// The first hit of ray r with sphere s inside [t_min, t_max], or nothing: t, p, n and
/// front_face, without the parameterisation (uv and dpdu stay zero). This is the lean test
/// for loops over many spheres that keep the closest hit; make_hit(s, h) then adds uv and
/// dpdu to that one, and intersect(r, s) does both.
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
/// overflow or underflow for huge or tiny directions, and positions relative to the centre
/// are scaled by a power of two that brings a radius above 1 into [0.5, 1), so that R^2
/// cannot overflow: every finite radius works (R = 1e20 in float, whose square is not a
/// float, is hit like R = 1); t is scaled back.
///
/// Returns the nearer root in [t_min, t_max] (front_face = true: the ray enters), else the
/// farther one (front_face = false: the ray leaves, e.g. when the origin is inside).
/// A tangent ray (discriminant exactly 0) returns its single touching point as an
/// entering hit. The normal is the outward unit normal: o + t d - c normalised (its length
/// is R up to rounding), and the point is on the sphere along it, p = c + R n, with p_error
/// = gamma_6 (|c| + R) per coordinate.
/// No hit for an invalid ray, a negative discriminant or roots outside [t_min, t_max].
///
/// Declared inline (a hint a template does not otherwise carry) so that g++ 12 -O3 inlines
/// it into callers: called out of line, its optional<hit> comes back through memory that
/// the caller rereads with wider loads than the stores.
template <std::floating_point T>
[[nodiscard]] inline std::optional<hit<T>> find_intersection(const ray<T>& r,
                                                             const sphere<T>& s) noexcept {
    // Every return below returns `out`, so that it is built in the caller's storage (named
    // return value optimisation). A hit<double> returned as a temporary is copied with
    // `rep movs` by g++ -O3, which costs more than the whole intersection test.
    std::optional<hit<T>> out;
    // The one test of the ray itself. valid() would also check that origin and direction
    // are finite and the direction non-zero; the arithmetic below rejects those rays on
    // its own. A zero direction gives a = 0, so b / a is NaN. A non-finite direction gives
    // a = inf (or NaN), and b is then infinite or NaN too (a product inf * f_i or
    // inf * 0), so b / a is NaN. A non-finite origin gives an infinite or NaN f, and l
    // with it. Each way delta is NaN or -inf and fails the test delta >= 0. A NaN bound or
    // t_max < t_min leaves no root in [t_min, t_max].
    if (!(r.t_min >= T(0))) return out;
    const int scale = detail::power_of_two_rescale_exponent(r.direction);
    // d = direction * 2^scale, exact (a component more than the exponent range below the
    // largest may underflow, far below rounding); t for d is t_user / 2^scale.
    const vec3<T> d(detail::times_power_of_two(r.direction.x, scale),
                    detail::times_power_of_two(r.direction.y, scale),
                    detail::times_power_of_two(r.direction.z, scale));
    // 2^k with R 2^k in [0.5, 1) (+infinity for a subnormal R), for the normal below
    // (|p - c| is R up to the rounding of p); computed here, where it waits for nothing.
    const int radius_exponent = detail::power_of_two_rescale_exponent(s.radius());
    const T normal_scale = detail::times_power_of_two(T(1), radius_exponent);
    // Positions (f and R) scaled by 2^k, k = min(radius_exponent, 0): a radius above 1 is
    // brought into [0.5, 1), so R^2, |l|^2 and |f|^2 near R^2 cannot overflow (R = 1e20 in
    // float has R^2 = 1e40). Every quantity below then scales by a power of two (a, b / a
    // and the roots' ratios not at all), so the results are those of the unscaled
    // arithmetic wherever that does not overflow, up to components of f more than 2^-149
    // (float) times R, which underflow. Never scaled up: that could overflow f.
    const int position_exponent = radius_exponent < 0 ? radius_exponent : 0;
    const vec3<T> f_unscaled = r.origin - s.center();
    const vec3<T> f(detail::times_power_of_two(f_unscaled.x, position_exponent),
                    detail::times_power_of_two(f_unscaled.y, position_exponent),
                    detail::times_power_of_two(f_unscaled.z, position_exponent));
    const T radius = detail::times_power_of_two(s.radius(), position_exponent);

    const T a = glm::dot(d, d);
    const T b = -glm::dot(f, d);
    const vec3<T> l = f + (b / a) * d;
    const T delta = sqr(radius) - glm::dot(l, l); // = (b^2 - a c_0) / a
    if (!(delta >= T(0))) return out; // also rejects NaN

    const T c0 = glm::dot(f, f) - sqr(radius);
    const T q = b + std::copysign(std::sqrt(a * delta), b);
    // q == 0 only when b == 0 and delta == 0: then c_0 = |l|^2 - R^2 = 0 and both roots
    // are 0; c_0 / q would be 0/0.
    const T root_a = q / a;
    const T root_b = q != T(0) ? c0 / q : T(0);
    // t for the user's direction and unscaled positions: root 2^(scale - position_exponent).
    const T t_near = detail::times_power_of_two(glm::min(root_a, root_b), scale - position_exponent);
    const T t_far = detail::times_power_of_two(glm::max(root_a, root_b), scale - position_exponent);

    T t;
    bool entering;
    if (detail::in_interval(t_near, r.t_min, r.t_max)) {
        t = t_near;
        entering = true;
    } else if (detail::in_interval(t_far, r.t_min, r.t_max)) {
        t = t_far;
        entering = false;
    } else {
        return out;
    }
    const vec3<T> on_ray = r.at(t);
    const vec3<T> n = detail::normalize_expected_length(on_ray - s.center(), normal_scale);
    if (!is_finite(on_ray) || !detail::is_unit_normal(n)) return out;
    // The point is reprojected onto the sphere, c + R n (Pharr, Jakob, Humphreys 2023,
    // sec. 6.8.5): o + t d can lie off the surface by t's error times |d|, which grows for
    // rays that graze the sphere; c + R n is on it up to the rounding of n (gamma_4
    // relative), of R n (u) and of the sum with c (u), below gamma_6 (|c| + R) in each
    // coordinate.
    const vec3<T> p = s.center() + s.radius() * n;
    if (!is_finite(p)) return out;
    out.emplace();
    out->t = t;
    out->p = p;
    out->p_error = detail::gamma<T>(6) * (glm::abs(s.center()) + vec3<T>(s.radius()));
    out->n = n;
    out->front_face = entering;
    return out;
}

/// Hit h of find_intersection(r, s) with its uv and dpdu set from the sphere's
/// parameterisation (see shade::sphere): uv from the unit normal, dp/du = 2π R (-n_y, n_x, 0).
template <std::floating_point T>
[[nodiscard]] inline hit<T> make_hit(const sphere<T>& s, hit<T> h) noexcept {
    h.uv = detail::sphere_uv(h.n);
    h.dpdu = (T(2) * pi<T> * s.radius()) * vec3<T>(-h.n.y, h.n.x, T(0));
    return h;
}

/// The first hit of ray r with sphere s, with its parameterisation:
/// find_intersection(r, s) completed by make_hit.
template <std::floating_point T>
[[nodiscard]] inline std::optional<hit<T>> intersect(const ray<T>& r, const sphere<T>& s) noexcept {
    std::optional<hit<T>> out = find_intersection(r, s);
    if (out) *out = make_hit(s, *out);
    return out;
}

/// The bounds of a sphere: center ± radius on every axis, each rounded outward (one step
/// toward infinity), so the box holds the exact sphere although c ± r is rounded.
template <std::floating_point T>
[[nodiscard]] aabb<T> bounds(const sphere<T>& s) noexcept {
    const vec3<T> r(s.radius());
    const vec3<T> lo = s.center() - r;
    const vec3<T> hi = s.center() + r;
    aabb<T> box;
    for (int k = 0; k < 3; ++k) {
        box.lo[k] = std::nextafter(lo[k], -infinity<T>);
        box.hi[k] = std::nextafter(hi[k], infinity<T>);
    }
    return box;
}

} // namespace shade
