#pragma once
// shade::thin_dielectric: a thin slab of dielectric with parallel smooth faces (a window
// pane, a soap film without interference): delta reflection and straight transmission.

#include <cmath>
#include <concepts>
#include <optional>

#include <glm/geometric.hpp>

#include <shade/bsdf/bsdf.hpp>
#include <shade/bsdf/detail/delta.hpp>
#include <shade/brdf/brdf.hpp>
#include <shade/brdf/detail/sampling.hpp>
#include <shade/brdf/fresnel.hpp>
#include <shade/core/error.hpp>
#include <shade/core/surface_point.hpp>
#include <shade/core/types.hpp>

namespace shade {

/// A thin dielectric slab in a uniform medium, the same on both sides: light is reflected
/// about the normal or passes straight through (l = -v, the slab too thin to displace it),
/// from either side alike.
///
/// Pharr, Jakob, Humphreys 2023, "Physically Based Rendering", 4th ed., sec. 9.5.1
/// (ThinDielectricBxDF). With R = F_dielectric(|n·v|, eta) the reflectance of one face
/// and T = 1 - R its transmittance (the same at the second face: the faces are parallel,
/// so light meets it at the refraction angle, and the Fresnel reflectance seen from inside
/// at that angle equals R), the light that leaves the slab on v's side sums the series of
/// internal reflections:
///
///     R' = R + T R T + T R^3 T + ... = R + T^2 R / (1 - R^2) = 2 R / (1 + R)
///     T' = T T + T R^2 T + ...       = T^2 / (1 - R^2)       = (1 - R) / (1 + R) = 1 - R'
///
/// (1 - R^2 = T (1 + R); the closed forms need no guard at R = 1, and R' + T' = 1: the
/// slab absorbs nothing). Both are delta lobes (shade/bsdf/bsdf.hpp): f and pdf are 0 for
/// any given pair of directions; sample() chooses the reflection when uc < R', with
/// probability R', the transmission with probability T' = 1 - R', so every weight is 1.
/// The medium is the same on both sides, so the transmission crosses no relative index
/// (the sample's eta is 1) and the two transport modes agree.
///
/// eta = n_slab / n_medium, 1.5 for a glass pane in air.
template <std::floating_point T>
class thin_dielectric : public detail::delta_lobes<T> {
public:
    using scalar_type = T;

    /// A slab of relative index eta = n_slab / n_medium. Throws shade::invalid_parameter
    /// naming "eta" unless eta lies in [1e-4, 1e4] (dielectric_eta_min, dielectric_eta_max).
    explicit thin_dielectric(T eta)
        : eta_(require_in_range("eta", eta, dielectric_eta_min<T>, dielectric_eta_max<T>)) {}

    /// Unchecked: the caller guarantees eta in [1e-4, 1e4].
    constexpr thin_dielectric(unchecked_t, T eta) noexcept : eta_(eta) {}

    /// The relative index of refraction n_slab / n_medium.
    [[nodiscard]] constexpr T eta() const noexcept { return eta_; }

    /// The slab's reflectance R' = 2R / (1 + R) for light arriving at cosine |n·v| (any
    /// sign), R = F_dielectric(|n·v|, eta); its transmittance is 1 - R'.
    [[nodiscard]] T reflectance(T n_dot_v) const noexcept {
        const T R = F_dielectric(std::abs(n_dot_v), eta_);
        return T(2) * R / (T(1) + R);
    }

    /// The mirror reflection of v when uc < R' (probability R'), otherwise l = -v
    /// (probability 1 - R'), each with weight 1 in either transport mode and eta 1; v on
    /// either side; u is not used. nullopt only when v lies on the surface (n·v = 0, or NaN).
    [[nodiscard]] std::optional<bsdf_sample<T>> sample(const vec3<T>& v, T uc, const vec2<T>& /*u*/,
                                                       const surface_point<T>& at,
                                                       transport_mode /*mode*/ = transport_mode::radiance) const noexcept {
        const T n_dot_v = glm::dot(at.n(), v);
        if (n_dot_v == T(0) || !std::isfinite(n_dot_v)) return std::nullopt;
        const T R = reflectance(n_dot_v);
        if (uc < R) {
            return detail::make_specular_sample(detail::reflect_about(v, at.n()), rgb<T>(R), R, at,
                                                bsdf_flags::reflection, T(1));
        }
        const T transmittance = T(1) - R;
        return detail::make_specular_sample(-v, rgb<T>(transmittance), transmittance, at,
                                            bsdf_flags::transmission, T(1));
    }

private:
    T eta_;
};

} // namespace shade
