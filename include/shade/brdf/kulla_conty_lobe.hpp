#pragma once
// shade::kulla_conty_lobe: Kulla and Conty's multiple-scattering compensation as a lobe of
// its own, fed by the albedo tables of its distribution and the Fresnel average of its
// Fresnel term (and so of eta for a dielectric), so that it composes with the
// single-scattering lobe through shade::mix (or sits in a shade::layer) instead of being
// built into the microfacet model. Not in the umbrella header: include it directly.
//
//   using D = shade::ggx<float>;
//   using F = shade::schlick<float>;
//   const shade::mix gold(shade::microfacet_reflection<D, F, shade::smith_height_correlated<float>>(D(0.5f), F(f0)),
//                         shade::rgb<float>(1), shade::kulla_conty_lobe<D, F>(D(0.5f), F(f0)), shade::rgb<float>(1));

#include <concepts>
#include <optional>

#include <glm/geometric.hpp>

#include <shade/brdf/brdf.hpp>
#include <shade/brdf/detail/directions.hpp>
#include <shade/brdf/detail/sampling.hpp>
#include <shade/brdf/fresnel.hpp>
#include <shade/brdf/microfacet.hpp>
#include <shade/brdf/microfacet/albedo_table.hpp>
#include <shade/brdf/multiple_scattering.hpp>
#include <shade/core/surface_point.hpp>
#include <shade/core/types.hpp>

namespace shade {

/// The multiple-scattering lobe of Kulla, Conty 2017, "Revisiting Physically Based Shading
/// at Imageworks", SIGGRAPH course "Physically Based Shading in Theory and Practice" (the
/// energy-compensation lobe and its Fresnel term; the slides number no equations), alone:
///
///     f_ms(l, v) = F_ms (1 - E(n·l)) (1 - E(n·v)) / (pi (1 - E_avg))      (1/sr, per channel)
///     F_ms       = F_avg^2 E_avg / (1 - F_avg (1 - E_avg)),   F_avg = 2 ∫ F(mu) mu dmu
///
/// E(mu) and E_avg the directional and average albedo of the single-scattering microfacet
/// lobe of the same distribution with F = 1, height-correlated Smith masking and the walter
/// form, read from the tables of the distribution (ggx or beckmann, at the roughness
/// sqrt(alpha_x alpha_y), shade/brdf/microfacet/albedo_table.hpp); F_avg the Fresnel term's
/// cosine-weighted average (detail::fresnel_average; for dielectric_fresnel it depends on
/// eta). These are exactly the values of the f_ms that shade::kulla_conty adds inside
/// shade::microfacet_reflection, so
///
///     mix(microfacet_reflection<D, F, smith_height_correlated<T>>(d, F), 1, kulla_conty_lobe<D, F>(d, F), 1)
///
/// has the f of microfacet_reflection<D, F, smith_height_correlated<T>, walter, kulla_conty>
/// (its sampler differs: mix's constant lobe choice). Symmetric in l and v (reciprocal);
/// 0 unless n·l > 0 and n·v > 0 (a BRDF). Its albedo from a view of cosine mu is
/// F_ms (1 - E(mu)) (the factor (1 - E(n·l)) integrates against the cosine to 1 - E_avg),
/// reported per the largest channel by albedo(mu) and average_albedo() so that shade::layer
/// reads them. Where 1 - E_avg < detail::kulla_conty_min_loss (a near-mirror) it is 0, as
/// in kulla_conty. Sampling: the cosine density n·l / pi (the lobe is diffuse-like).
template <class Distribution, class Fresnel>
    requires microfacet_distribution<Distribution> && fresnel_term<Fresnel, scalar_of<Distribution>> &&
             requires { detail::albedo_tables_of<Distribution>::e; }
class kulla_conty_lobe {
public:
    using scalar_type = scalar_of<Distribution>;
    using distribution_type = Distribution;
    using fresnel_type = Fresnel;

private:
    using T = scalar_type;

public:
    /// The compensation of the single-scattering lobe of `distribution` with `fresnel`
    /// (each validated its own parameters when it was built).
    kulla_conty_lobe(const Distribution& distribution, const Fresnel& fresnel) noexcept
        : state_(detail::make_kulla_conty_state(distribution, fresnel)) {}

    /// E(mu): the single-scattering albedo with F = 1 at view cosine mu, from the table
    /// (dimensionless, in [0, 1]).
    [[nodiscard]] T single_scattering_albedo(T mu) const noexcept {
        return detail::albedo_lookup(detail::albedo_tables_of<Distribution>::e, detail::albedo_grid_nodes, mu,
                                     state_.alpha);
    }

    /// E_avg, the cosine-weighted average of single_scattering_albedo.
    [[nodiscard]] constexpr T average_single_scattering_albedo() const noexcept { return state_.e_avg; }

    /// F_ms / (pi (1 - E_avg)) per channel (1/sr): f_ms at a pair where E(n·l) = E(n·v) = 0.
    [[nodiscard]] constexpr const rgb<T>& scale() const noexcept { return state_.scale; }

    /// The lobe's directional albedo at view cosine mu, largest channel: max(F_ms) (1 - E(mu)).
    [[nodiscard]] T albedo(T mu) const noexcept { return state_.f_ms_max * (T(1) - single_scattering_albedo(mu)); }

    /// Its cosine-weighted average, largest channel: max(F_ms) (1 - E_avg).
    [[nodiscard]] constexpr T average_albedo() const noexcept { return state_.f_ms_max * (T(1) - state_.e_avg); }

    /// BRDF value f_ms in 1/sr without the cosine (class comment); 0 unless n·l > 0 and n·v > 0.
    [[nodiscard]] rgb<T> f(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const noexcept {
        detail::assert_unit_directions(l, v, at);
        const vec3<T> l_local = at.shading.to_local(l);
        const vec3<T> v_local = at.shading.to_local(v);
        if (!(l_local.z > T(0)) || !(v_local.z > T(0))) return rgb<T>(0);
        // Each factor is computed the same way for l and v, so the product is the same
        // number with l and v exchanged.
        const T loss_l = T(1) - single_scattering_albedo(l_local.z);
        const T loss_v = T(1) - single_scattering_albedo(v_local.z);
        return state_.scale * (loss_l * loss_v);
    }

    /// The density (1/sr) with which sample() draws l: n·l / pi, 0 unless n·l > 0 and n·v > 0.
    [[nodiscard]] T pdf(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const noexcept {
        return detail::cosine_brdf_pdf(l, v, at);
    }

    /// Draws l from the cosine density for the view v (u in [0,1)^2; uc unused). Returns l
    /// with f, pdf and the weight f (n·l) / pdf; nullopt when v or l is not above the surface.
    [[nodiscard]] std::optional<brdf_sample<T>> sample(const vec3<T>& v, T /*uc*/, const vec2<T>& u,
                                                       const surface_point<T>& at) const noexcept {
        return detail::sample_cosine_brdf(v, u, at, [&](const vec3<T>& l) { return f(l, v, at); });
    }

private:
    detail::kulla_conty_state<T> state_;
};

} // namespace shade
