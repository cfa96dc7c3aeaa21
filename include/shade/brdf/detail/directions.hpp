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

/// s / m for a scalar m > 0, as s times 1/m (one division instead of three) when 1/m is
/// finite, that is when m is a normal number; a subnormal m divides each component.
template <std::floating_point T>
[[nodiscard]] inline vec3<T> scaled_by_inverse(const vec3<T>& s, T m) noexcept {
    if (m >= std::numeric_limits<T>::min()) return s * (T(1) / m);
    return s / m;
}

/// The half vector h = normalize(l + v) for unit l and v.
/// Precondition: n·l > 0 and n·v > 0 for some unit n (both above the surface), which
/// makes l + v non-zero: |l + v| >= n·(l + v) > 0.
/// l + v is scaled by the inverse of its largest component before normalising, so that |l + v| as small
/// as 1e-30 (both directions grazing and nearly opposite) does not underflow to 0 when
/// squared inside glm::normalize (which would give NaN).
template <std::floating_point T>
[[nodiscard]] inline vec3<T> half_vector(const vec3<T>& l, const vec3<T>& v) noexcept {
    const vec3<T> s = l + v;
    const T m = glm::max(std::abs(s.x), glm::max(std::abs(s.y), std::abs(s.z)));
    if (!(m > T(0))) return vec3<T>(0, 0, 0); // l = -v: excluded by the precondition
    const vec3<T> w = scaled_by_inverse(s, m);
    return w * (T(1) / glm::length(w));
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
/// suffer from this. Precondition as for half_vector.
template <std::floating_point T>
[[nodiscard]] inline half_angle<T> half_vector_and_cos(const vec3<T>& l, const vec3<T>& v) noexcept {
    const vec3<T> s = l + v;
    const T m = glm::max(std::abs(s.x), glm::max(std::abs(s.y), std::abs(s.z)));
    if (!(m > T(0))) return {vec3<T>(0, 0, 0), T(0)}; // l = -v: excluded by the precondition
    const vec3<T> w = scaled_by_inverse(s, m);
    const T len_w = glm::length(w);
    return {w * (T(1) / len_w), glm::min(T(0.5) * m * len_w, T(1))};
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
