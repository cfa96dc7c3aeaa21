#pragma once
// shade::coupled_plastic: a rough plastic whose Lambertian base receives only the light its
// specular coating does not reflect, so that with a white base (k_d = 1) it reflects all
// the light it receives, at every roughness and view, and with k_d = 0 it is the coating
// alone.
//
//   const shade::coupled_plastic<float> red(shade::ggx<float>(0.3f), {0.8f, 0.1f, 0.1f});

#include <concepts>
#include <optional>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <shade/brdf/brdf.hpp>
#include <shade/brdf/cook_torrance.hpp>
#include <shade/brdf/detail/directions.hpp>
#include <shade/brdf/fresnel.hpp>
#include <shade/brdf/microfacet.hpp>
#include <shade/brdf/microfacet/albedo_table.hpp>
#include <shade/brdf/microfacet/detail/albedo_data.hpp>
#include <shade/brdf/multiple_scattering.hpp>
#include <shade/core/error.hpp>
#include <shade/core/math.hpp>
#include <shade/core/sampling.hpp>
#include <shade/core/surface_point.hpp>
#include <shade/core/types.hpp>

namespace shade {

/// A rough plastic: a GGX dielectric coating of relative index eta = 1.5 (exact dielectric
/// Fresnel, height-correlated Smith, compensated for multiple scattering with
/// shade::kulla_conty) over a Lambertian base of albedo k_d, coupled to the coating:
///
///     f = f_s(l, v) + k_d (1 - E_s(n·l)) (1 - E_s(n·v)) / (pi (1 - E_s,avg))
///
/// Kulla, Conty 2017, "Revisiting Physically Based Shading at Imageworks", SIGGRAPH course
/// "Physically Based Shading in Theory and Practice" (the layering of a diffuse base under
/// a specular layer by the layer's albedo; the slides number no equations), in the
/// product form of Kelemen, Szirmay-Kalos 2001, "A Microfacet Based Coupled Specular-Matte
/// BRDF Model with Importance Sampling", Eurographics short presentation. f_s is the
/// compensated coating (k_s = 1), E_s(mu) its directional albedo and E_s,avg the
/// cosine-weighted average:
///
///     E_s(mu) = E_F(mu) + F_ms (1 - E(mu)),   E_s,avg = E_F,avg + F_ms (1 - E_avg)
///
/// with E_F the single-scattering albedo with the dielectric Fresnel (the table
/// ggx_dielectric_albedo), E and E_avg those with F = 1 and F_ms the coating's
/// multiple-scattering Fresnel factor (shade/brdf/multiple_scattering.hpp). The base term
/// is symmetric in l and v (reciprocal); its albedo is k_d (1 - E_s(n·v)), so with k_d = 1
/// the total is E_s(n·v) + 1 - E_s(n·v) = 1 to the accuracy of the tables, and with
/// k_d = 0 f is the coating's f exactly. eta is fixed at 1.5 (common plastics, varnish) because
/// the dielectric table is computed for it. Anisotropic GGX reads the tables at
/// sqrt(alpha_x alpha_y), as kulla_conty does. Returns 0 unless n·l > 0 and n·v > 0.
///
/// Sampling: the coating's sampler (visible normals and its cosine share, see
/// shade::cook_torrance) with probability P_s = E_s(n·v) / (E_s(n·v) + max(k_d) (1 -
/// E_s(n·v))) kept in [0.1, 0.9] (1 when k_d = 0), else the cosine; pdf is the mixture
/// P_s pdf_s + (1 - P_s) (n·l) / pi.
template <std::floating_point T>
class coupled_plastic {
public:
    using scalar_type = T;
    /// The coating: compensated GGX with the dielectric Fresnel, k_s = 1, k_d = 0.
    using coating_type =
        cook_torrance<ggx<T>, dielectric_fresnel<T>, smith_height_correlated<T>, cook_torrance_form::walter, kulla_conty>;

    /// The coating's relative index of refraction.
    static constexpr T eta = T(1.5);

    /// A plastic with GGX roughness `distribution` and base albedo k_d (per channel >= 0 and
    /// finite; <= 1 for a physical base). Throws shade::invalid_parameter naming "k_d".
    coupled_plastic(const ggx<T>& distribution, const rgb<T>& k_d)
        : coating_(distribution, dielectric_fresnel<T>(eta)), k_d_(require_non_negative("k_d", k_d)) {
        const T alpha = detail::albedo_tables_of<ggx<T>>::roughness(distribution);
        const T e_avg = coating_.average_single_scattering_albedo();
        f_ms_ = detail::multiple_scattering_fresnel(detail::fresnel_average<T>(dielectric_fresnel<T>(eta)), e_avg).x;
        alpha_ = alpha;
        const T e_s_avg = detail::albedo_average_lookup(detail::ggx_dielectric_albedo_average, detail::albedo_grid_nodes, alpha) +
                          f_ms_ * (T(1) - e_avg);
        // E_s,avg is about 0.1 or less for eta = 1.5 (the coating reflects little), so the
        // denominator is far from 0.
        base_scale_ = inv_pi<T> / (T(1) - e_s_avg);
        detail::require_finite_peak("k_d", detail::max_channel(k_d_) * base_scale_);
    }

    [[nodiscard]] constexpr const coating_type& coating() const noexcept { return coating_; } ///< the specular layer
    [[nodiscard]] constexpr const rgb<T>& k_d() const noexcept { return k_d_; } ///< base albedo

    /// E_s(mu): the directional albedo of the coating at view cosine mu (dimensionless).
    [[nodiscard]] T coating_albedo(T mu) const noexcept {
        const T e_f = detail::albedo_lookup(detail::ggx_dielectric_albedo, detail::albedo_grid_nodes, mu, alpha_);
        return e_f + f_ms_ * (T(1) - coating_.single_scattering_albedo(mu));
    }

    /// The base term k_d (1 - E_s(n·l)) (1 - E_s(n·v)) / (pi (1 - E_s,avg)) in 1/sr; 0 unless
    /// n·l > 0 and n·v > 0.
    [[nodiscard]] rgb<T> f_diffuse(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const noexcept {
        const T n_dot_l = glm::dot(at.n(), l);
        const T n_dot_v = glm::dot(at.n(), v);
        if (!(n_dot_l > T(0)) || !(n_dot_v > T(0))) return rgb<T>(0);
        return base(n_dot_l, n_dot_v);
    }

    /// The coating f_s in 1/sr (shade::cook_torrance with kulla_conty).
    [[nodiscard]] rgb<T> f_specular(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const noexcept {
        return coating_.f_specular(l, v, at);
    }

    /// BRDF value in 1/sr without the cosine: f_specular + f_diffuse.
    [[nodiscard]] rgb<T> f(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const noexcept {
        detail::assert_unit_directions(l, v, at);
        return coating_.f(l, v, at) + f_diffuse(l, v, at);
    }

    /// The solid-angle density (1/sr) with which sample() draws l: P_s pdf_s + (1 - P_s)
    /// (n·l) / pi; 0 unless n·l > 0 and n·v > 0.
    [[nodiscard]] T pdf(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const noexcept {
        const T n_dot_l = glm::dot(at.n(), l);
        const T n_dot_v = glm::dot(at.n(), v);
        if (!(n_dot_l > T(0)) || !(n_dot_v > T(0))) return T(0);
        const T p_s = specular_probability(n_dot_v);
        return p_s * coating_.pdf(l, v, at) + (T(1) - p_s) * n_dot_l * inv_pi<T>;
    }

    /// Draws l for the view v: the coating's sampler when uc < P_s (with uc / P_s as its
    /// own lobe choice), else the cosine. Returns l with f, pdf and the weight f (n·l) / pdf;
    /// nullopt when v or the drawn l is not above the surface.
    [[nodiscard]] std::optional<brdf_sample<T>> sample(const vec3<T>& v, T uc, const vec2<T>& u,
                                                       const surface_point<T>& at) const noexcept {
        const T n_dot_v = glm::dot(at.n(), v);
        if (!(n_dot_v > T(0))) return std::nullopt;
        const T p_s = specular_probability(n_dot_v);
        vec3<T> l;
        if (uc < p_s) {
            const auto s = coating_.sample(v, uc / p_s, u, at);
            if (!s) return std::nullopt;
            l = s->l;
        } else {
            l = at.shading.to_world(square_to_cosine_hemisphere(u));
        }
        const T n_dot_l = glm::dot(at.n(), l);
        if (!(n_dot_l > T(0))) return std::nullopt;
        return detail::make_brdf_sample(l, f(l, v, at), pdf(l, v, at), n_dot_l);
    }

    /// P_s, the probability that sample() uses the coating's sampler, for a view of cosine
    /// n_dot_v > 0 (see the class comment).
    [[nodiscard]] T specular_probability(T n_dot_v) const noexcept {
        const T w_d = detail::max_channel(k_d_);
        if (!(w_d > T(0))) return T(1);
        const T e_s = coating_albedo(n_dot_v);
        const T p = e_s / (e_s + w_d * (T(1) - e_s));
        return glm::clamp(p, T(0.1), T(0.9));
    }

private:
    // k_d (1 - E_s(n·l)) (1 - E_s(n·v)) / (pi (1 - E_s,avg)) for cosines > 0; the product
    // of the two factors is the same number with l and v exchanged.
    [[nodiscard]] rgb<T> base(T n_dot_l, T n_dot_v) const noexcept {
        const T loss_l = T(1) - coating_albedo(n_dot_l);
        const T loss_v = T(1) - coating_albedo(n_dot_v);
        return k_d_ * (base_scale_ * (loss_l * loss_v));
    }

    coating_type coating_;
    rgb<T> k_d_;
    T alpha_ = 0;       // roughness the tables are read at
    T f_ms_ = 0;        // the coating's F_ms (grey)
    T base_scale_ = 0;  // 1 / (pi (1 - E_s,avg)), 1/sr
};

} // namespace shade
