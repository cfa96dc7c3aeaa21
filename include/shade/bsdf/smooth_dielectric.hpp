#pragma once
// shade::smooth_dielectric: a perfectly smooth interface between two dielectrics (glass,
// water): delta reflection and delta refraction.

#include <cmath>
#include <concepts>
#include <optional>

#include <glm/geometric.hpp>

#include <shade/bsdf/bsdf.hpp>
#include <shade/bsdf/detail/delta.hpp>
#include <shade/bsdf/refract.hpp>
#include <shade/brdf/brdf.hpp>
#include <shade/brdf/detail/sampling.hpp>
#include <shade/brdf/fresnel.hpp>
#include <shade/core/error.hpp>
#include <shade/core/math.hpp>
#include <shade/core/surface_point.hpp>
#include <shade/core/types.hpp>

namespace shade {

/// A smooth dielectric interface: the mirror reflection with the exact Fresnel
/// reflectance R and the refraction (Snell's law, shade::refract) with 1 - R, from either
/// side; total internal reflection (R = 1) beyond the critical angle on the denser side.
///
/// Fresnel reflectance: F_dielectric_two_sided (Walter, Marschner, Li, Torrance 2007,
/// "Microfacet Models for Refraction through Rough Surfaces", EGSR, eq. 22). The model
/// and its sampling are those of Pharr, Jakob, Humphreys 2023, "Physically Based
/// Rendering", 4th ed., sec. 9.5 (the smooth case of DielectricBxDF): with v given and
/// eta' = eta_l / eta_v (eta when v is outside, 1/eta when inside),
///
///     reflection  l = 2 (n·v) n - v,         throughput R = F(|n·v|, eta')
///     refraction  l = refract(v, ±n, eta'),  throughput (1 - R) / eta'^2 in radiance mode,
///                                            1 - R in importance mode
///
/// the factor 1/eta'^2 being the change of radiance across the interface (Veach 1997,
/// "Robust Monte Carlo Methods for Light Transport Simulation", sec. 5.2). Both lobes are
/// delta lobes (see shade/bsdf/bsdf.hpp): f and pdf are 0 for any given pair of
/// directions; sample() chooses the reflection when uc < R, with probability R, the
/// refraction with probability 1 - R, so a reflection's weight is 1 and a refraction's
/// 1/eta'^2 (radiance) or 1 (importance). Reflected plus transmitted energy is exactly 1:
/// the interface absorbs nothing.
///
/// eta = n_inside / n_outside, inside being the side opposite at.n(): 1.5 for glass in
/// air, 1/1.33 for an air bubble in water. eta = 1 is an index-matched interface, which
/// transmits everything straight through.
template <std::floating_point T>
class smooth_dielectric : public detail::delta_lobes<T> {
public:
    using scalar_type = T;

    /// An interface of relative index eta = n_inside / n_outside. Throws
    /// shade::invalid_parameter naming "eta" unless eta lies in [1e-4, 1e4]
    /// (dielectric_eta_min, dielectric_eta_max).
    explicit smooth_dielectric(T eta)
        : eta_(require_in_range("eta", eta, dielectric_eta_min<T>, dielectric_eta_max<T>)) {}

    /// Unchecked: the caller guarantees eta in [1e-4, 1e4].
    constexpr smooth_dielectric(unchecked_t, T eta) noexcept : eta_(eta) {}

    /// The relative index of refraction n_inside / n_outside.
    [[nodiscard]] constexpr T eta() const noexcept { return eta_; }

    /// The mirror reflection of v when uc < R (probability R, weight 1), otherwise the
    /// refraction of v (probability 1 - R, weight 1/eta'^2 in radiance mode, 1 in
    /// importance mode), v on either side; u is not used. The sample's eta is eta' for a
    /// refraction, 1 for a reflection. nullopt only when v lies on the surface (n·v = 0,
    /// or NaN).
    [[nodiscard]] std::optional<bsdf_sample<T>> sample(const vec3<T>& v, T uc, const vec2<T>& /*u*/,
                                                       const surface_point<T>& at,
                                                       transport_mode mode = transport_mode::radiance) const noexcept {
        const T n_dot_v = glm::dot(at.n(), v);
        if (n_dot_v == T(0) || !std::isfinite(n_dot_v)) return std::nullopt;
        const bool outside = n_dot_v > T(0);
        const vec3<T> n_v = outside ? at.n() : -at.n(); // the normal on v's side
        const T eta_prime = outside ? eta_ : T(1) / eta_;
        const std::optional<vec3<T>> refracted = refract(v, n_v, eta_prime);
        // refract and F_dielectric decide total internal reflection each from its own
        // rounding; where refract finds no direction, R = 1 keeps the choice consistent.
        const T R = refracted ? F_dielectric_two_sided(n_dot_v, eta_) : T(1);
        if (uc < R || !refracted) {
            return detail::make_specular_sample(detail::reflect_about(v, n_v), rgb<T>(R), R, at,
                                                bsdf_flags::reflection, T(1));
        }
        const T transmittance = T(1) - R;
        const T throughput =
            mode == transport_mode::radiance ? transmittance / (eta_prime * eta_prime) : transmittance;
        return detail::make_specular_sample(*refracted, rgb<T>(throughput), transmittance, at,
                                            bsdf_flags::transmission, eta_prime);
    }

private:
    T eta_;
};

} // namespace shade
