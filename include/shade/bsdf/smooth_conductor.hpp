#pragma once
// shade::smooth_conductor: a perfect metal mirror, the limit of a microfacet conductor as
// its roughness goes to 0.

#include <concepts>
#include <optional>

#include <glm/geometric.hpp>

#include <shade/bsdf/bsdf.hpp>
#include <shade/bsdf/detail/delta.hpp>
#include <shade/brdf/brdf.hpp>
#include <shade/brdf/detail/sampling.hpp>
#include <shade/brdf/fresnel.hpp>
#include <shade/core/surface_point.hpp>
#include <shade/core/types.hpp>

namespace shade {

/// A smooth conductor: the delta mirror reflection l = 2 (n·v) n - v with the exact
/// conductor Fresnel reflectance F(n·v) per channel (shade::conductor_fresnel, Born, Wolf
/// 1999, "Principles of Optics", 7th ed., sec. 14.2; e.g. shade::metals::gold<T>()).
/// Pharr, Jakob, Humphreys 2023, "Physically Based Rendering", 4th ed., sec. 9.4 (the
/// smooth case of ConductorBxDF).
///
/// A delta lobe (shade/bsdf/bsdf.hpp): f and pdf are 0 for any given pair of directions;
/// sample() returns the mirror direction with probability 1 and weight F(n·v), in either
/// transport mode (a reflection crosses no interface). Opaque and one-sided, as the BRDFs
/// are: nothing is drawn for v below the surface.
template <std::floating_point T>
class smooth_conductor : public detail::delta_lobes<T> {
public:
    using scalar_type = T;

    /// A conductor of complex index eta + i kappa per channel, relative to the outside
    /// medium. Throws shade::invalid_parameter naming "eta" unless every channel of eta
    /// lies in [1e-4, 1e4], or "kappa" unless every channel of kappa lies in [0, 1e4]
    /// (as shade::conductor_fresnel).
    smooth_conductor(const rgb<T>& eta, const rgb<T>& kappa) : fresnel_(eta, kappa) {}

    /// A conductor with the given Fresnel term (validated when it was built), e.g.
    /// shade::metals::gold<T>().
    explicit constexpr smooth_conductor(const conductor_fresnel<T>& fresnel) noexcept : fresnel_(fresnel) {}

    /// The conductor's Fresnel term.
    [[nodiscard]] constexpr const conductor_fresnel<T>& fresnel() const noexcept { return fresnel_; }

    /// The mirror direction of v with probability 1 and weight F(n·v), eta 1, in either
    /// transport mode; uc and u are not used. nullopt unless v is above the surface.
    [[nodiscard]] std::optional<bsdf_sample<T>> sample(const vec3<T>& v, T /*uc*/, const vec2<T>& /*u*/,
                                                       const surface_point<T>& at,
                                                       transport_mode /*mode*/ = transport_mode::radiance) const noexcept {
        const T n_dot_v = glm::dot(at.n(), v);
        if (!(n_dot_v > T(0))) return std::nullopt;
        return detail::make_specular_sample(detail::reflect_about(v, at.n()), fresnel_.F(n_dot_v), T(1), at,
                                            bsdf_flags::reflection, T(1));
    }

private:
    conductor_fresnel<T> fresnel_;
};

} // namespace shade
