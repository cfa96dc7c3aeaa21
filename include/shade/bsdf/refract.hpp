#pragma once
// shade::refract: the direction of a ray refracted at a smooth interface (Snell's law).
// The matching reflectance is shade::F_dielectric (shade/brdf/fresnel.hpp).

#include <cmath>
#include <concepts>
#include <optional>

#include <glm/geometric.hpp>

#include <shade/core/math.hpp>
#include <shade/core/types.hpp>

namespace shade {

/// The refraction of w through an interface of normal n: the unit direction, pointing away
/// from the surface on the side opposite w, along which light arriving from w's side
/// continues, or nullopt under total internal reflection (no refracted ray).
///
/// w is a unit direction away from the surface (e.g. v toward the viewer), n the unit
/// normal on w's side (n·w > 0; a slightly negative n·w by rounding is taken as 0), and
/// eta = eta_t / eta_i the index of refraction on the far side over that on w's side (> 0).
///
/// Snell's law (Pharr, Jakob, Humphreys 2023, "Physically Based Rendering", 4th ed.,
/// sec. 9.3, eq. 9.2): eta_i sin(theta_i) = eta_t sin(theta_t), the refracted ray in the
/// plane of w and n on the other side of n. So the component of the result perpendicular to
/// n is that of w, w - cos_i n, reversed and scaled by 1/eta, and its component along n is
/// -cos_t:
///
///     t = -(w - cos_i n) / eta - cos_t n,   cos_i = n·w,
///     sin^2(theta_t) = (1 - cos_i^2) / eta^2,   cos_t = sqrt(1 - sin^2(theta_t))
///
/// with total internal reflection when sin^2(theta_t) >= 1 (only possible for eta < 1).
/// 1 - cos_i^2 is computed as (1 - cos_i)(1 + cos_i), which does not cancel near grazing
/// incidence. |t| = 1 in exact arithmetic; t is normalised all the same, because for a
/// small eta the rounding error of w - cos_i n is magnified 1/eta times in the first term
/// (the direction itself is that sensitive to w, its length need not be).
template <std::floating_point T>
[[nodiscard]] inline std::optional<vec3<T>> refract(const vec3<T>& w, const vec3<T>& n, T eta) noexcept {
    const T cos_i = glm::min(glm::max(glm::dot(n, w), T(0)), T(1));
    const T sin2_i = (T(1) - cos_i) * (T(1) + cos_i);
    const T sin2_t = sin2_i / (eta * eta);
    if (!(sin2_t < T(1))) return std::nullopt; // total internal reflection (or a NaN eta)
    const T cos_t = std::sqrt(T(1) - sin2_t);
    return glm::normalize(-(w - cos_i * n) / eta - cos_t * n);
}

} // namespace shade
