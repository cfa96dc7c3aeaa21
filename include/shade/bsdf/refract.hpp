#pragma once
// shade::refract: the direction of a ray refracted at a smooth interface (Snell's law), and
// its inverse for microfacets, shade::generalized_half_vector: the normal that reflects or
// refracts one given direction into another. The matching reflectance is
// shade::F_dielectric (shade/brdf/fresnel.hpp).

#include <cmath>
#include <concepts>
#include <limits>
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

/// The microfacet normal that scatters light between the unit directions l and v: the
/// generalized half vector
///
///     m = normalize(v + eta l),   turned to n's side (m·n >= 0)
///
/// Walter, Marschner, Li, Torrance 2007, "Microfacet Models for Refraction through Rough
/// Surfaces", EGSR, eq. 16 (h_t = -(eta_i i + eta_o o) / |...|, written with both directions
/// pointing away from the surface and divided by the index on v's side). eta = eta_l / eta_v
/// is the index of refraction on l's side over that on v's side:
///   * reflection (l and v on the same side): eta = 1, and m is the half vector
///     normalize(l + v) (Walter et al. eq. 13);
///   * refraction (opposite sides): m is the only normal through which refract(v, m, eta)
///     (or refract(l, m, 1 / eta)) gives the other direction: v + eta l parallel to m is
///     Snell's law eta_v (v x m) = -eta_l (l x m) with the two directions on opposite sides
///     of m.
/// n is the unit normal whose side m is turned to (the local frame's +z by default). Returns
/// nullopt when v + eta l is 0 or not finite (l = -v with eta = 1; a refraction pair
/// with eta = 1 has no such normal). For a pair that no normal can refract (both on one
/// side of the computed m, e.g. eta on the wrong side), m is still returned: the caller
/// tests the signs of l·m and v·m (G1(w, m), shade/brdf/microfacet/distribution.hpp).
template <std::floating_point T>
[[nodiscard]] inline std::optional<vec3<T>> generalized_half_vector(const vec3<T>& l, const vec3<T>& v, T eta,
                                                                    const vec3<T>& n = vec3<T>(0, 0, 1)) noexcept {
    vec3<T> m = v + eta * l;
    const T length2 = glm::dot(m, m);
    if (!(length2 > T(0)) || !(length2 <= std::numeric_limits<T>::max())) return std::nullopt;
    m /= std::sqrt(length2);
    if (glm::dot(m, n) < T(0)) m = -m;
    return m;
}

} // namespace shade
