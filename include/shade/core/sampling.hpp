#pragma once
// Sample points of the unit square [0,1)^2: stratified grids (shade::stratified_u), and
// warps from the square to the disk and the hemisphere in the local frame (n = +z), each
// returning a unit direction (or disk point) and documenting its pdf.

#include <cmath>
#include <concepts>
#include <string>

#include <glm/common.hpp>

#include <shade/core/config.hpp>
#include <shade/core/error.hpp>
#include <shade/core/math.hpp>
#include <shade/core/types.hpp>

namespace shade {

/// The jitter of a deterministic grid: every stratum is sampled at its centre (0.5, 0.5).
/// Noise-free but can band; pass a random jitter in [0,1)^2 for jittered stratification.
template <std::floating_point T>
struct cell_centre {
    [[nodiscard]] constexpr vec2<T> operator()(int i, int j) const noexcept {
        (void)i;
        (void)j;
        return vec2<T>(T(0.5), T(0.5));
    }
};

/// The sample pair of stratum (i, j) of an n x n grid over [0,1)^2, placed at `jitter`
/// (in [0,1)^2) inside the stratum: ((i + jitter.x) / n, (j + jitter.y) / n). Averaging
/// an integrand over the n^2 pairs of a jittered grid is stratified sampling (one sample
/// per stratum), which never has more variance than n^2 independent uniform samples.
/// Preconditions: 0 <= i, j < n and jitter in [0,1)^2 (SHADE_ASSERT in debug builds).
template <std::floating_point T>
[[nodiscard]] constexpr vec2<T> stratified_u(int i, int j, int n, const vec2<T>& jitter) noexcept {
    SHADE_ASSERT(0 <= i && i < n && 0 <= j && j < n && is_in_unit_square(jitter));
    return vec2<T>((T(i) + jitter.x) / T(n), (T(j) + jitter.y) / T(n));
}

namespace detail {

/// Returns n, the side of a stratified grid; throws invalid_parameter naming
/// "samples_per_side" unless n >= 1.
inline int require_samples_per_side(int n) {
    if (n < 1)
        throw invalid_parameter("samples_per_side", "must be >= 1", std::to_string(n));
    return n;
}

} // namespace detail

namespace detail {

/// A sine and a cosine.
template <std::floating_point T>
struct sin_cos {
    T sin;
    T cos;
};

/// sin(x) and cos(x) for |x| <= pi/4, from their Taylor series cut where the remainder is
/// below half an ulp of the result (Lagrange bound |x|^(k+1)/(k+1)! at |x| = pi/4): through
/// x^9 and x^10 in float (remainders 1.7e-9 and 1.1e-10), x^15 and x^16 in double (4.6e-17
/// and 2.0e-18), evaluated by Horner's rule in x^2. Replaces a call of std::sin and
/// std::cos where the argument is known to be this small.
template <std::floating_point T>
[[nodiscard]] constexpr sin_cos<T> sin_cos_quarter_pi(T x) noexcept {
    // sin x = x (1 - x^2/(2*3) (1 - x^2/(4*5) (1 - ...))), cos x = 1 - x^2/(1*2) (1 - ...):
    // each factor is a term's ratio to the previous one, multiplied by its reciprocal.
    constexpr int last = sizeof(T) <= 4 ? 9 : 15; // the last odd power of the sine
    const T x2 = x * x;
    T s = T(1);
    for (int k = last - 1; k >= 2; k -= 2) s = T(1) - x2 * (T(1) / T(k * (k + 1))) * s;
    T c = T(1);
    for (int k = last; k >= 1; k -= 2) c = T(1) - x2 * (T(1) / T(k * (k + 1))) * c;
    return {x * s, c};
}

/// sin(pi/2 t) and cos(pi/2 t) for t in [0, 1], from sin_cos_quarter_pi: for t > 1/2 the
/// angle is taken as pi/2 - pi/2 (1 - t) (1 - t is exact there). Written with selects
/// rather than branches: t is random in the samplers, so a branch would be mispredicted
/// half of the time.
template <std::floating_point T>
[[nodiscard]] inline sin_cos<T> sin_cos_half_pi(T t) noexcept {
    const bool upper = t > T(0.5);
    const sin_cos<T> b = sin_cos_quarter_pi((pi<T> / T(2)) * (upper ? T(1) - t : t));
    return {upper ? b.cos : b.sin, upper ? b.sin : b.cos};
}

/// sin(2 pi u) and cos(2 pi u) for u in [0, 1): 4u = q + t with the quadrant q and t in
/// [0, 1) (both exact), sin_cos_half_pi(t) turned by q quarter turns (q odd swaps sine and
/// cosine; the sine is negative in quadrants 2 and 3, the cosine in 1 and 2), with selects.
template <std::floating_point T>
[[nodiscard]] inline sin_cos<T> sin_cos_two_pi(T u) noexcept {
    const T u4 = T(4) * u;
    const T q = glm::min(std::floor(u4), T(3));
    const sin_cos<T> a = sin_cos_half_pi(u4 - q);
    const bool odd = q == T(1) || q == T(3);
    const T s = odd ? a.cos : a.sin;
    const T c = odd ? a.sin : a.cos;
    return {q >= T(2) ? -s : s, (q == T(1) || q == T(2)) ? -c : c};
}

} // namespace detail

/// Maps u in [0,1)^2 to the unit disk with the concentric map of Shirley & Chiu 1997,
/// "A Low Distortion Map Between Disk and Square", JGT 2(3). It keeps strata compact, so
/// stratified square samples stay stratified on the disk. Uniform: pdf = 1/pi per area.
/// The angle is pi/4 (b/a) or pi/2 - pi/4 (a/b), so its sine and cosine come from
/// detail::sin_cos_quarter_pi of pi/4 times the smaller ratio.
/// Precondition: u in [0,1)^2 (SHADE_ASSERT in debug builds; outside it the point leaves
/// the disk).
template <std::floating_point T>
[[nodiscard]] inline vec2<T> square_to_concentric_disk(const vec2<T>& u) noexcept {
    SHADE_ASSERT(is_in_unit_square(u));
    const T a = T(2) * u.x - T(1);
    const T b = T(2) * u.y - T(1);
    // r = the larger of a, b in magnitude; phi = pi/4 (b/a) when it is a, else
    // pi/2 - pi/4 (a/b), whose cosine and sine are the sine and cosine of pi/4 (a/b).
    // Selects rather than branches: which case applies is random.
    const bool a_larger = std::abs(a) > std::abs(b);
    const T r = a_larger ? a : b;
    if (r == T(0)) return {T(0), T(0)};
    const detail::sin_cos<T> sc = detail::sin_cos_quarter_pi((pi<T> / T(4)) * ((a_larger ? b : a) / r));
    return {r * (a_larger ? sc.cos : sc.sin), r * (a_larger ? sc.sin : sc.cos)};
}

/// Cosine-weighted direction on the upper hemisphere (Malley's method: a uniform disk
/// point lifted to the hemisphere). pdf(w) = cos(theta) / pi per steradian.
/// Precondition: u in [0,1)^2 (SHADE_ASSERT in debug builds; outside it the result is not
/// a unit vector).
template <std::floating_point T>
[[nodiscard]] inline vec3<T> square_to_cosine_hemisphere(const vec2<T>& u) noexcept {
    SHADE_ASSERT(is_in_unit_square(u));
    const vec2<T> d = square_to_concentric_disk(u);
    const T z = safe_sqrt(T(1) - d.x * d.x - d.y * d.y);
    return {d.x, d.y, z};
}

/// cos(theta) and sin(theta) of a polar angle drawn with density (e + 1) cos^e(theta) in
/// cos(theta) on [0, 1], from u in [0,1): cos(theta) = u^(1/(e+1)), the inversion used by
/// Lafortune, Willems 1994, "Using the Modified Phong Reflectance Model for Physically
/// Based Rendering", Tech. Rep. CW 197, K.U. Leuven, and by Ashikhmin, Shirley 2000,
/// "An Anisotropic Phong BRDF Model", JGT 5(2), sec. 4 (u and 1 - u are equally
/// distributed). 1 - cos(theta) = -expm1(log(u)/(e+1)) is formed without cancellation, so
/// sin(theta) = sqrt((1 - cos)(1 + cos)) stays accurate for the narrow lobes of large e,
/// where cos(theta) rounds to 1. u = 0 gives cos = 0 (log(0) = -inf).
template <std::floating_point T>
struct polar_cosines {
    T cos_theta; ///< in [0, 1]
    T sin_theta; ///< in [0, 1]
};

template <std::floating_point T>
[[nodiscard]] inline polar_cosines<T> power_cosine_polar(T u, T exponent) noexcept {
    const T one_minus_cos = -std::expm1(std::log(u) / (exponent + T(1)));
    const T cos_theta = T(1) - one_minus_cos;
    return {cos_theta, safe_sqrt(one_minus_cos * (T(1) + cos_theta))};
}

/// Direction on the upper hemisphere (n = +z) with the power-cosine density
/// pdf(w) = (e + 1)/(2 pi) cos^e(theta) per steradian (e >= 0; e = 1 is the cosine
/// density, e = 0 the uniform one): the polar angle from power_cosine_polar(u.x, e), the
/// azimuth 2 pi u.y (its sine and cosine from detail::sin_cos_two_pi). The lobe of the modified Phong BRDF (Lafortune, Willems 1994) about
/// its axis.
template <std::floating_point T>
[[nodiscard]] inline vec3<T> square_to_power_cosine_hemisphere(const vec2<T>& u, T exponent) noexcept {
    const polar_cosines<T> c = power_cosine_polar(u.x, exponent);
    const detail::sin_cos<T> phi = detail::sin_cos_two_pi(u.y);
    return {c.sin_theta * phi.cos, c.sin_theta * phi.sin, c.cos_theta};
}

/// Uniform direction on the upper hemisphere (Archimedes: z uniform in [0,1)).
/// pdf(w) = 1 / (2 pi) per steradian. Precondition: u in [0,1)^2 (SHADE_ASSERT in debug
/// builds; outside it the result is not a unit vector).
template <std::floating_point T>
[[nodiscard]] inline vec3<T> square_to_uniform_hemisphere(const vec2<T>& u) noexcept {
    SHADE_ASSERT(is_in_unit_square(u));
    const T z = u.x;
    const T r = safe_sqrt(T(1) - z * z);
    const T phi = T(2) * pi<T> * u.y;
    return {r * std::cos(phi), r * std::sin(phi), z};
}

/// Uniform direction on the whole unit sphere (Archimedes: z uniform in [-1, 1)).
/// pdf(w) = 1 / (4 pi) per steradian.
template <std::floating_point T>
[[nodiscard]] inline vec3<T> square_to_uniform_sphere(const vec2<T>& u) noexcept {
    const T z = T(1) - T(2) * u.x;
    const T r = safe_sqrt((T(1) - z) * (T(1) + z));
    const T phi = T(2) * pi<T> * u.y;
    return {r * std::cos(phi), r * std::sin(phi), z};
}

/// Uniform direction inside the cone of half-angle theta_max about +z, given
/// one_minus_cos_max = 1 - cos(theta_max) in (0, 2] (passed in this form so that narrow
/// cones, where cos(theta_max) rounds to 1, keep their width): 1 - cos(theta) is uniform
/// in [0, one_minus_cos_max), so pdf(w) = 1 / (2 pi one_minus_cos_max) per steradian
/// inside the cone (Archimedes' hat-box theorem, as in Shirley, Wang, Zimmerman 1996,
/// "Monte Carlo Techniques for Direct Lighting Calculations", ACM TOG 15(1), §4.2).
template <std::floating_point T>
[[nodiscard]] inline vec3<T> square_to_uniform_cone(const vec2<T>& u, T one_minus_cos_max) noexcept {
    const T one_minus_cos = u.x * one_minus_cos_max;
    const T z = T(1) - one_minus_cos;
    const T r = safe_sqrt(one_minus_cos * (T(2) - one_minus_cos)); // sin = sqrt((1-c)(1+c))
    const T phi = T(2) * pi<T> * u.y;
    return {r * std::cos(phi), r * std::sin(phi), z};
}

/// Local direction with polar angle theta and azimuth phi (n = +z, t = +x).
template <std::floating_point T>
[[nodiscard]] inline vec3<T> spherical_direction(T theta, T phi) noexcept {
    const T s = std::sin(theta);
    return {s * std::cos(phi), s * std::sin(phi), std::cos(theta)};
}

} // namespace shade
