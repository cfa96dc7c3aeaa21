#pragma once
// Warps from the unit square [0,1)^2 to the disk and the hemisphere, in the local frame
// (n = +z). Each returns a unit direction (or disk point) and documents its pdf.

#include <cmath>
#include <concepts>

#include <shade/core/math.hpp>
#include <shade/core/types.hpp>

namespace shade {

/// Maps u in [0,1)^2 to the unit disk with the concentric map of Shirley & Chiu 1997,
/// "A Low Distortion Map Between Disk and Square", JGT 2(3). It keeps strata compact, so
/// stratified square samples stay stratified on the disk. Uniform: pdf = 1/pi per area.
template <std::floating_point T>
[[nodiscard]] inline vec2<T> square_to_concentric_disk(const vec2<T>& u) noexcept {
    const T a = T(2) * u.x - T(1);
    const T b = T(2) * u.y - T(1);
    if (a == T(0) && b == T(0)) return {T(0), T(0)};
    T r;
    T phi;
    if (std::abs(a) > std::abs(b)) {
        r = a;
        phi = (pi<T> / T(4)) * (b / a);
    } else {
        r = b;
        phi = pi<T> / T(2) - (pi<T> / T(4)) * (a / b);
    }
    return {r * std::cos(phi), r * std::sin(phi)};
}

/// Cosine-weighted direction on the upper hemisphere (Malley's method: a uniform disk
/// point lifted to the hemisphere). pdf(w) = cos(theta) / pi per steradian.
template <std::floating_point T>
[[nodiscard]] inline vec3<T> square_to_cosine_hemisphere(const vec2<T>& u) noexcept {
    const vec2<T> d = square_to_concentric_disk(u);
    const T z = safe_sqrt(T(1) - d.x * d.x - d.y * d.y);
    return {d.x, d.y, z};
}

/// Uniform direction on the upper hemisphere (Archimedes: z uniform in [0,1)).
/// pdf(w) = 1 / (2 pi) per steradian.
template <std::floating_point T>
[[nodiscard]] inline vec3<T> square_to_uniform_hemisphere(const vec2<T>& u) noexcept {
    const T z = u.x;
    const T r = safe_sqrt(T(1) - z * z);
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
