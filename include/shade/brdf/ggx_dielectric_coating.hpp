#pragma once
// shade::ggx_dielectric_coating: a rough dielectric coating of index 1.5 (GGX, exact
// dielectric Fresnel, compensated for multiple scattering) that reports its own directional
// albedo from precomputed tables, so that shade::layer weighs a base under it by the
// tabulated albedo instead of estimating it. The coat of shade::coupled_plastic.
//
//   const shade::layer varnished(shade::ggx_dielectric_coating<float>(shade::ggx<float>(0.2f)),
//                                shade::lambert<float>({0.8f, 0.1f, 0.1f}));

#include <concepts>
#include <optional>

#include <shade/brdf/brdf.hpp>
#include <shade/brdf/cook_torrance.hpp>
#include <shade/brdf/fresnel.hpp>
#include <shade/brdf/microfacet.hpp>
#include <shade/brdf/microfacet/albedo_table.hpp>
#include <shade/brdf/microfacet/detail/albedo_data.hpp>
#include <shade/brdf/multiple_scattering.hpp>
#include <shade/core/surface_point.hpp>
#include <shade/core/types.hpp>

namespace shade {

/// A GGX dielectric coating of relative index eta = 1.5: shade::cook_torrance with the
/// exact dielectric Fresnel, height-correlated Smith, the walter form and Kulla and Conty's
/// multiple-scattering compensation (shade::kulla_conty), k_s = 1, k_d = 0. f, pdf and
/// sample are that model's (1/sr without the cosine; the density in 1/sr; a
/// shade::sampled_brdf), f_specular too.
///
/// Its directional albedo, the fraction of the energy arriving at cosine mu that it
/// reflects (dimensionless), is read from tables:
///
///     E_s(mu) = E_F(mu) + F_ms (1 - E(mu)),   E_s,avg = E_F,avg + F_ms (1 - E_avg)
///
/// with E_F the single-scattering albedo with the dielectric Fresnel of eta = 1.5 (the table
/// ggx_dielectric_albedo and its average), E and E_avg those with F = 1 (ggx_albedo), and
/// F_ms = F_avg^2 E_avg / (1 - F_avg (1 - E_avg)) the multiple-scattering Fresnel factor
/// (Kulla, Conty 2017, "Revisiting Physically Based Shading at Imageworks", SIGGRAPH course,
/// the Fresnel slide; shade/brdf/multiple_scattering.hpp). The multiple-scattering lobe
/// F_ms (1 - E(mu_l)) (1 - E(mu_v)) / (pi (1 - E_avg)) reflects F_ms (1 - E(mu)) from a
/// view of cosine mu (it integrates against the cosine to that), hence the second term.
/// albedo(mu) and average_albedo() are what shade::layer reads (detail::has_directional_albedo).
/// eta is fixed because the dielectric table is computed for 1.5 (plastics, varnish). An
/// anisotropic GGX reads the tables at sqrt(alpha_x alpha_y), as kulla_conty does.
template <std::floating_point T>
class ggx_dielectric_coating {
public:
    using scalar_type = T;
    /// The coating's model: compensated GGX with the dielectric Fresnel, k_s = 1, k_d = 0.
    using lobe_type =
        cook_torrance<ggx<T>, dielectric_fresnel<T>, smith_height_correlated<T>, cook_torrance_form::walter, kulla_conty>;

    /// The coating's relative index of refraction.
    static constexpr T eta = T(1.5);

    /// A coating of GGX roughness `distribution` (validated when it was built). Throws what
    /// lobe_type's constructor throws (shade::invalid_parameter when its peak overflows T).
    explicit ggx_dielectric_coating(const ggx<T>& distribution)
        : lobe_(distribution, dielectric_fresnel<T>(eta)),
          alpha_(detail::albedo_tables_of<ggx<T>>::roughness(distribution)) {
        const T e_avg = lobe_.average_single_scattering_albedo();
        f_ms_ = detail::multiple_scattering_fresnel(detail::fresnel_average<T>(dielectric_fresnel<T>(eta)), e_avg).x;
        average_ = detail::albedo_average_lookup(detail::ggx_dielectric_albedo_average, detail::albedo_grid_nodes, alpha_) +
                   f_ms_ * (T(1) - e_avg);
    }

    [[nodiscard]] constexpr const lobe_type& lobe() const noexcept { return lobe_; } ///< the coating's model

    /// E_s(mu), the directional albedo at view cosine mu in [0, 1] (dimensionless; class
    /// comment).
    [[nodiscard]] T albedo(T mu) const noexcept {
        const T e_f = detail::albedo_lookup(detail::ggx_dielectric_albedo, detail::albedo_grid_nodes, mu, alpha_);
        return e_f + f_ms_ * (T(1) - lobe_.single_scattering_albedo(mu));
    }

    /// E_s,avg = 2 ∫ E_s(mu) mu dmu, the cosine-weighted average albedo, from the tables.
    [[nodiscard]] constexpr T average_albedo() const noexcept { return average_; }

    /// BRDF value in 1/sr without the cosine (lobe_type's f); 0 unless n·l > 0 and n·v > 0.
    [[nodiscard]] rgb<T> f(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const noexcept {
        return lobe_.f(l, v, at);
    }

    /// The specular part in 1/sr: all of f (k_d = 0).
    [[nodiscard]] rgb<T> f_specular(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const noexcept {
        return lobe_.f_specular(l, v, at);
    }

    /// The solid-angle density (1/sr) with which sample() draws l (lobe_type's pdf).
    [[nodiscard]] T pdf(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const noexcept {
        return lobe_.pdf(l, v, at);
    }

    /// Draws l for the view v as lobe_type's sample does (visible normals, and the cosine
    /// for the multiple-scattering lobe); nullopt when v or the drawn l is not above the
    /// surface.
    [[nodiscard]] std::optional<brdf_sample<T>> sample(const vec3<T>& v, T uc, const vec2<T>& u,
                                                       const surface_point<T>& at) const noexcept {
        return lobe_.sample(v, uc, u, at);
    }

private:
    lobe_type lobe_;
    T alpha_;          // roughness the tables are read at
    T f_ms_ = 0;       // F_ms (grey: the dielectric Fresnel is)
    T average_ = 0;    // E_s,avg
};

} // namespace shade
