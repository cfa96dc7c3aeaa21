#pragma once
// What shade::cook_torrance does with the energy its single-scattering lobe loses: the
// Scattering policy, its last template parameter.
//
//   single_scattering   (default) f_s = F D G2 / (4 (n·l)(n·v)) only: light that scatters
//                       more than once between microfacets is lost, so rough surfaces are
//                       too dark (with F = 1, GGX alpha = 1 reflects 0.31 at normal incidence)
//   kulla_conty         adds Kulla and Conty's multiple-scattering lobe, which returns that
//                       energy: with F = 1 the albedo is 1 at every view, to the accuracy of
//                       the albedo tables (shade/brdf/microfacet/albedo_table.hpp)
//
//   cook_torrance<ggx<T>, schlick<T>, smith_height_correlated<T>, cook_torrance_form::walter, kulla_conty>
//
// Why Kulla-Conty and not Turquin. Turquin 2019 ("A Practical Energy Compensation for
// Multiple Scattering in Microfacet Models", Ubisoft tech report, eq. 2) scales the
// single-scattering lobe by 1 + F0 (1 - E(mu_v)) / E(mu_v): one lookup and the lobe's
// shape kept, but the factor depends on the view only, so f(l, v) != f(v, l) and the
// property kit's reciprocity check would fail it. Kulla and Conty's lobe is a product of
// one factor per direction, (1 - E(mu_l))(1 - E(mu_v)), so the model stays reciprocal; its
// albedo is exactly 1 - E(mu_v) with F = 1 (below), and it is diffuse-like, so it is
// sampled by the cosine.

#include <cmath>
#include <concepts>

#include <glm/common.hpp>

#include <shade/brdf/microfacet/albedo_table.hpp>
#include <shade/brdf/microfacet/beckmann.hpp>
#include <shade/brdf/microfacet/detail/albedo_data.hpp>
#include <shade/brdf/microfacet/ggx.hpp>
#include <shade/brdf/microfacet/masking.hpp>
#include <shade/core/math.hpp>
#include <shade/core/quadrature.hpp>
#include <shade/core/types.hpp>

namespace shade {

/// Scattering policy of shade::cook_torrance: single scattering only (the default; the
/// model is exactly the microfacet BRDF of its header).
struct single_scattering {};

/// Scattering policy of shade::cook_torrance: Kulla and Conty's multiple-scattering
/// compensation. The specular part becomes f_ss + f_ms with
///
///     f_ms(l, v) = F_ms (1 - E(mu_l)) (1 - E(mu_v)) / (pi (1 - E_avg))
///     F_ms       = F_avg^2 E_avg / (1 - F_avg (1 - E_avg)),   F_avg = 2 integral_0^1 F(mu) mu dmu
///
/// Kulla, Conty 2017, "Revisiting Physically Based Shading at Imageworks", SIGGRAPH 2017
/// course "Physically Based Shading in Theory and Practice" (the slides on multiple
/// scattering: the energy-compensation lobe, the product form of Kelemen, Szirmay-Kalos
/// 2001, "A Microfacet Based Coupled Specular-Matte BRDF Model with Importance Sampling",
/// Eurographics short presentation; and the Fresnel term, the sum over k >= 2 bounces of
/// F_avg^k E_avg (1 - E_avg)^(k-1) divided by its F = 1 value 1 - E_avg; the slides number
/// no equations). mu = n·w; E(mu) and E_avg are the albedo and the average albedo of
/// the single-scattering lobe with F = 1 (shade/brdf/microfacet/albedo_table.hpp).
/// With F = 1, integral of f_ms (n·l) dl = (1 - E(mu_v)) (1 - E_avg) / (1 - E_avg), so the
/// total albedo E(mu_v) + 1 - E(mu_v) is 1. f_ms is symmetric in l and v (reciprocal).
///
/// Applies to ggx and beckmann with smith_height_correlated masking and the walter form
/// (the masking and form the tables were computed with). Anisotropic distributions read
/// the tables at the geometric mean roughness sqrt(alpha_x alpha_y) (for beckmann
/// sqrt(m_x m_y)), whatever the azimuth: an anisotropic lobe's albedo depends on the
/// azimuth, so with F = 1 the albedo then departs from 1 both ways, already at 2:1
/// (docs/properties.md measures it); kulla_conty_anisotropic
/// (shade/brdf/anisotropic_multiple_scattering.hpp) reads it at each direction's azimuth.
/// Roughness above 1 reads the alpha = 1 row, so there the compensation is partial and the
/// albedo stays below 1.
struct kulla_conty {};

namespace detail {

/// The albedo tables of a distribution type with F = 1 and height-correlated Smith, and
/// the roughness its table is read at; defined for ggx and beckmann.
template <class Distribution>
struct albedo_tables_of;

template <std::floating_point T>
struct albedo_tables_of<ggx<T>> {
    static constexpr const float* e = ggx_albedo;
    static constexpr const float* e_avg = ggx_albedo_average;
    /// sqrt(alpha_x alpha_y).
    [[nodiscard]] static T roughness(const ggx<T>& d) noexcept { return std::sqrt(d.alpha_x() * d.alpha_y()); }
};

template <std::floating_point T>
struct albedo_tables_of<beckmann<T>> {
    static constexpr const float* e = beckmann_albedo;
    static constexpr const float* e_avg = beckmann_albedo_average;
    /// sqrt(m_x m_y).
    [[nodiscard]] static T roughness(const beckmann<T>& d) noexcept { return std::sqrt(d.m_x() * d.m_y()); }
};

/// The cosine-weighted average of a Fresnel term, per channel:
///
///     F_avg = 2 integral_0^1 F(mu) mu dmu
///
/// (Kulla, Conty 2017, the F_avg of the Fresnel slide), by 5-point Gauss-Legendre
/// quadrature on 8 equal intervals (Abramowitz, Stegun 1964, "Handbook of Mathematical
/// Functions", 25.4.29): exact for Schlick's polynomial of degree 6 (f0 + (1 - f0) / 21), and
/// accurate for the smooth exact Fresnel curves of dielectrics (eta > 1) and conductors.
/// Returns values in [0, 1].
template <std::floating_point T, class Fresnel>
[[nodiscard]] rgb<T> fresnel_average(const Fresnel& fresnel) noexcept {
    const glm::dvec3 average = gauss_legendre_integral(
        [&fresnel](double mu) { return glm::dvec3(fresnel.F(T(mu))) * (2 * mu); }, 0, 1, 8);
    return rgb<T>(glm::clamp(average, glm::dvec3(0), glm::dvec3(1)));
}

/// F_ms = F_avg^2 E_avg / (1 - F_avg (1 - E_avg)) per channel (Kulla, Conty 2017, the
/// Fresnel slide): the share of the multiply scattered energy (1 - E_avg with F = 1)
/// that leaves after the Fresnel factor of every bounce. In [0, 1]; 1 for F_avg = 1.
template <std::floating_point T>
[[nodiscard]] rgb<T> multiple_scattering_fresnel(const rgb<T>& f_avg, T e_avg) noexcept {
    return f_avg * f_avg * e_avg / (rgb<T>(1) - f_avg * (T(1) - e_avg));
}

/// Below this 1 - E_avg, f_ms is taken as 0: the lobe is then a near-mirror that loses
/// almost nothing, and the normalization 1 / (1 - E_avg) would only amplify the float
/// rounding of the table.
inline constexpr double kulla_conty_min_loss = 1e-6;

/// What a Kulla-Conty compensated model keeps: the table roughness, E_avg, and the
/// constant factor F_ms / (pi (1 - E_avg)) of f_ms, per channel.
template <std::floating_point T>
struct kulla_conty_state {
    T alpha = 0;         ///< roughness at which the tables are read
    T e_avg = 1;         ///< E_avg(alpha)
    rgb<T> scale{0};     ///< F_ms / (pi (1 - E_avg)), 1/sr
    T f_avg_max = 0;     ///< largest channel of F_avg (for the sampler's lobe choice)
    T f_ms_max = 0;      ///< largest channel of F_ms
};

/// The state for the table roughness alpha and the average albedo e_avg in [0, 1].
template <std::floating_point T, class Fresnel>
[[nodiscard]] kulla_conty_state<T> make_kulla_conty_state(T alpha, T e_avg, const Fresnel& fresnel) noexcept {
    kulla_conty_state<T> s;
    s.alpha = alpha;
    s.e_avg = e_avg;
    const rgb<T> f_avg = fresnel_average<T>(fresnel);
    const rgb<T> f_ms = multiple_scattering_fresnel(f_avg, s.e_avg);
    const T loss = T(1) - s.e_avg;
    s.scale = loss > T(kulla_conty_min_loss) ? f_ms * (inv_pi<T> / loss) : rgb<T>(0);
    s.f_avg_max = glm::max(glm::max(f_avg.x, f_avg.y), f_avg.z);
    s.f_ms_max = loss > T(kulla_conty_min_loss) ? glm::max(glm::max(f_ms.x, f_ms.y), f_ms.z) : T(0);
    return s;
}

/// The state of the compensation for a distribution and a Fresnel term.
template <class Distribution, class Fresnel, std::floating_point T = scalar_of<Distribution>>
[[nodiscard]] kulla_conty_state<T> make_kulla_conty_state(const Distribution& distribution,
                                                          const Fresnel& fresnel) noexcept {
    using tables = albedo_tables_of<Distribution>;
    const T alpha = tables::roughness(distribution);
    return make_kulla_conty_state(alpha, albedo_average_lookup(tables::e_avg, albedo_grid_nodes, alpha), fresnel);
}

/// The per-model state of a Scattering policy: kulla_conty_state for kulla_conty, empty for
/// single_scattering; albedo<Distribution>(w) is the E(w) of f_ms for a local direction w.
template <class Scattering, std::floating_point T>
struct scattering_state {};

template <std::floating_point T>
struct scattering_state<kulla_conty, T> : kulla_conty_state<T> {
    scattering_state() = default;
    template <class Distribution, class Fresnel>
    scattering_state(const Distribution& distribution, const Fresnel& fresnel) noexcept
        : kulla_conty_state<T>(make_kulla_conty_state(distribution, fresnel)) {}
    template <class Distribution>
    [[nodiscard]] T albedo(const vec3<T>& w) const noexcept {
        return albedo_lookup(albedo_tables_of<Distribution>::e, albedo_grid_nodes, w.z, this->alpha);
    }
};

} // namespace detail

} // namespace shade
