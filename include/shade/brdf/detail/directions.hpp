#pragma once
// Internal helpers shared by the reflection models in shade/brdf: the robust half vector,
// the floor applied to cosines in denominators, and the constructor check that a model's
// peak value fits in the scalar type.

#include <cmath>
#include <concepts>
#include <limits>
#include <string_view>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <shade/core/error.hpp>
#include <shade/core/math.hpp>
#include <shade/core/types.hpp>

namespace shade::detail {

/// Smallest cosine a model divides by: machine epsilon of T (1.2e-7 float, 2.2e-16
/// double). A unit vector whose cosine with n is below this lies on the horizon to within
/// its own rounding error, so flooring there changes f only for directions that are
/// grazing anyway; without the floor 1/(n·l) overflows to Inf for n·l below ~3e-39 (float).
template <std::floating_point T>
inline constexpr T cos_floor = std::numeric_limits<T>::epsilon();

/// max(c, cos_floor<T>): a cosine that is safe to divide by (see cos_floor).
template <std::floating_point T>
[[nodiscard]] constexpr T floored_cos(T c) noexcept {
    return c > cos_floor<T> ? c : cos_floor<T>;
}

/// The smallest s·s from which half_vector_and_cos normalises s = l + v directly (one
/// square root, one division): 2^(min_exponent / 2) (2^-62 in float, 2^-510 in double).
/// From there on, a component whose square underflows (below numeric_limits<T>::min()) has
/// a square below 2^(min_exponent / 2) times s·s, far under an ulp of it, so whether that
/// square keeps its bits does not matter. Below it, s is rescaled first
/// (rescaled_unit_and_length).
template <std::floating_point T>
inline constexpr T direct_normalization_floor = [] {
    T x = T(1);
    for (int e = std::numeric_limits<T>::min_exponent / 2; e < 0; ++e) x *= T(0.5);
    return x;
}();

/// A unit vector and the length it was scaled from.
template <std::floating_point T>
struct unit_and_length {
    vec3<T> unit;  ///< s / |s|
    T length = 0;  ///< |s|
};

/// s / |s| and |s| for any finite s != 0, however small: s is first multiplied by the
/// power of two that brings its largest component into [0.5, 1) (exact:
/// power_of_two_rescale_exponent, times_power_of_two), so s·s can neither underflow nor
/// overflow, and |s| is scaled back at the end. s = 0 (or NaN) gives (0, 0).
template <std::floating_point T>
[[nodiscard]] inline unit_and_length<T> rescaled_unit_and_length(const vec3<T>& s) noexcept {
    const int k = power_of_two_rescale_exponent(s);
    const vec3<T> w(times_power_of_two(s.x, k), times_power_of_two(s.y, k), times_power_of_two(s.z, k));
    const T length_w = glm::length(w);
    if (!(length_w > T(0))) return {vec3<T>(0, 0, 0), T(0)};
    return {w / length_w, times_power_of_two(length_w, -k)};
}

/// The half vector with its cosine to l and v: h = normalize(l + v) and
/// cos_theta_d = l·h = v·h.
template <std::floating_point T>
struct half_angle {
    vec3<T> h;         ///< unit half vector
    T cos_theta_d = 0; ///< l·h = v·h, in [0, 1]
};

/// h = normalize(l + v) together with cos_theta_d = |l + v| / 2, which is (l·h + v·h)/2
/// for any l, v (because (l + v)·h = |l + v|) and so l·h = v·h for exactly unit l, v.
/// Computing the cosine from |l + v| instead of dot(v, h) makes it exactly symmetric in l
/// and v (models using it are reciprocal to the last bit) and accurate when l and v are
/// nearly opposite: there rounded unit vectors make l·h and v·h differ by
/// (|v|^2 - |l|^2) / (2 |l + v|), which is large when |l + v| is small; their mean does not
/// suffer from this. Precondition as for half_vector (below).
template <std::floating_point T>
[[nodiscard]] inline half_angle<T> half_vector_and_cos(const vec3<T>& l, const vec3<T>& v) noexcept {
    const vec3<T> s = l + v;
    const T length2 = glm::dot(s, s);
    if (length2 >= direct_normalization_floor<T>) {
        const T length = std::sqrt(length2);
        return {s * (T(1) / length), glm::min(T(0.5) * length, T(1))};
    }
    const unit_and_length<T> small = rescaled_unit_and_length(s);
    return {small.unit, glm::min(T(0.5) * small.length, T(1))};
}

/// The half vector h = normalize(l + v) for unit l and v.
/// Precondition: n·l > 0 and n·v > 0 for some unit n (both above the surface), which
/// makes l + v non-zero: |l + v| >= n·(l + v) > 0. |l + v| as small as 1e-30 (both
/// directions grazing and nearly opposite) is normalised without underflow
/// (rescaled_unit_and_length); l = -v gives 0.
template <std::floating_point T>
[[nodiscard]] inline vec3<T> half_vector(const vec3<T>& l, const vec3<T>& v) noexcept {
    return half_vector_and_cos(l, v).h;
}

/// The largest channel of an RGB value.
template <std::floating_point T>
[[nodiscard]] constexpr T max_channel(const vec3<T>& c) noexcept {
    return glm::max(c.x, glm::max(c.y, c.z));
}

/// Throws invalid_parameter naming `parameter` unless `peak` (the largest value the model
/// can return with the parameters given, or a bound on it) is finite. Validating
/// constructors call this so that parameters which are each valid, but together make f
/// overflow T, are rejected up front instead of returning Inf later.
template <std::floating_point T>
void require_finite_peak(std::string_view parameter, T peak) {
    if (!std::isfinite(peak))
        throw invalid_parameter(parameter,
                                "is too large: the BRDF's peak value would overflow the scalar type",
                                to_text(peak));
}

} // namespace shade::detail
