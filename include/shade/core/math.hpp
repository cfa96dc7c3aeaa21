#pragma once
// Scalar constants and small numeric helpers shared by all of shade.

#include <cmath>
#include <concepts>
#include <limits>
#include <numbers>

#include <glm/geometric.hpp>

#include <shade/core/types.hpp>

namespace shade {

/// pi in the scalar type T.
template <std::floating_point T>
inline constexpr T pi = std::numbers::pi_v<T>;

/// 1/pi in the scalar type T.
template <std::floating_point T>
inline constexpr T inv_pi = std::numbers::inv_pi_v<T>;

/// +infinity in the scalar type T (the t_max of an unbounded ray).
template <std::floating_point T>
inline constexpr T infinity = std::numeric_limits<T>::infinity();

/// x squared.
template <std::floating_point T>
[[nodiscard]] constexpr T sqr(T x) noexcept {
    return x * x;
}

/// sqrt(max(x, 0)): for quantities that are non-negative in exact arithmetic but may round
/// to a tiny negative (1 - cos^2, discriminants). Without the clamp sqrt would return NaN.
template <std::floating_point T>
[[nodiscard]] inline T safe_sqrt(T x) noexcept {
    return std::sqrt(x > T(0) ? x : T(0));
}

/// True when every component of v is finite (no NaN, no infinity).
template <std::floating_point T>
[[nodiscard]] inline bool is_finite(const vec3<T>& v) noexcept {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

/// True when every component of v is finite (no NaN, no infinity).
template <std::floating_point T>
[[nodiscard]] inline bool is_finite(const vec2<T>& v) noexcept {
    return std::isfinite(v.x) && std::isfinite(v.y);
}

/// max(a·b, 0): the clamped cosine used by every reflection model.
template <std::floating_point T>
[[nodiscard]] inline T clamped_dot(const vec3<T>& a, const vec3<T>& b) noexcept {
    const T d = glm::dot(a, b);
    return d > T(0) ? d : T(0);
}

} // namespace shade
