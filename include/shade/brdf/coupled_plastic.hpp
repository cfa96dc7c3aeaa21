#pragma once
// shade::coupled_plastic: a rough plastic whose Lambertian base receives only the light its
// specular coating does not reflect, so that with a white base (k_d = 1) it reflects all
// the light it receives, at every roughness and view, and with k_d = 0 it is the coating
// alone.
//
//   const shade::coupled_plastic<float> red(shade::ggx<float>(0.3f), {0.8f, 0.1f, 0.1f});

#include <concepts>
#include <optional>

#include <glm/geometric.hpp>

#include <shade/brdf/brdf.hpp>
#include <shade/brdf/detail/directions.hpp>
#include <shade/brdf/ggx_dielectric_coating.hpp>
#include <shade/brdf/lambert.hpp>
#include <shade/brdf/microfacet.hpp>
#include <shade/bsdf/bsdf.hpp>
#include <shade/bsdf/layer.hpp>
#include <shade/core/error.hpp>
#include <shade/core/math.hpp>
#include <shade/core/surface_point.hpp>
#include <shade/core/types.hpp>

namespace shade {

/// A rough plastic: a GGX dielectric coating of relative index eta = 1.5 (exact dielectric
/// Fresnel, height-correlated Smith, compensated for multiple scattering with
/// shade::kulla_conty: shade::ggx_dielectric_coating) over a Lambertian base of albedo k_d,
/// coupled to the coating:
///
///     f = f_s(l, v) + k_d (1 - E_s(n·l)) (1 - E_s(n·v)) / (pi (1 - E_s,avg))
///
/// Kulla, Conty 2017, "Revisiting Physically Based Shading at Imageworks", SIGGRAPH course
/// "Physically Based Shading in Theory and Practice" (the layering of a diffuse base under
/// a specular layer by the layer's albedo; the slides number no equations), in the
/// product form of Kelemen, Szirmay-Kalos 2001, "A Microfacet Based Coupled Specular-Matte
/// BRDF Model with Importance Sampling", Eurographics short presentation. f_s is the
/// compensated coating (k_s = 1), E_s(mu) its directional albedo and E_s,avg the
/// cosine-weighted average, both read from tables (ggx_dielectric_coating's albedo and
/// average_albedo).
///
/// It is the layer of those two lobes: a shade::layer<ggx_dielectric_coating<T>,
/// lambert<T>, base_albedo_choice<T>> of coat weight 1 with layering::reciprocal (its public
/// base class: coat(), base(), base_factor, coat_probability and the sample with a
/// transport mode are the layer's), with the names of a BRDF.
/// The base term is symmetric in l and v (reciprocal); its albedo is k_d (1 - E_s(n·v)), so
/// with k_d = 1 the total is E_s(n·v) + 1 - E_s(n·v) = 1 to the accuracy of the tables, and
/// with k_d = 0 f is the coating's f exactly. eta is fixed at 1.5 (common plastics, varnish)
/// because the dielectric table is computed for it. Anisotropic GGX reads the tables at
/// sqrt(alpha_x alpha_y), as kulla_conty does. Returns 0 unless n·l > 0 and n·v > 0.
///
/// Sampling: the coating's sampler (visible normals and its cosine share, see
/// shade::cook_torrance) with probability P_s = E_s(n·v) / (E_s(n·v) + max(k_d) (1 -
/// E_s(n·v))) kept in [0.1, 0.9] (1 when k_d = 0: base_albedo_choice with b = max(k_d)),
/// else the cosine (the Lambertian base's sampler); pdf is the mixture
/// P_s pdf_s + (1 - P_s) (n·l) / pi.
template <std::floating_point T>
class coupled_plastic : public layer<ggx_dielectric_coating<T>, lambert<T>, base_albedo_choice<T>> {
public:
    using scalar_type = T;
    /// The layer this model is.
    using layer_type = layer<ggx_dielectric_coating<T>, lambert<T>, base_albedo_choice<T>>;
    /// The coating's model: compensated GGX with the dielectric Fresnel, k_s = 1, k_d = 0.
    using coating_type = typename ggx_dielectric_coating<T>::lobe_type;

    /// The coating's relative index of refraction.
    static constexpr T eta = ggx_dielectric_coating<T>::eta;

    /// A plastic with GGX roughness `distribution` and base albedo k_d (per channel >= 0 and
    /// finite; <= 1 for a physical base). Throws shade::invalid_parameter naming "k_d".
    coupled_plastic(const ggx<T>& distribution, const rgb<T>& k_d) : layer_type(make_layer(distribution, k_d)) {
        // E_s,avg is about 0.1 or less for eta = 1.5 (the coating reflects little), so the
        // denominator is far from 0.
        detail::require_finite_peak("k_d", detail::max_channel(k_d) * inv_pi<T> / (T(1) - this->coat().average_albedo()));
    }

    /// The specular layer (coat().lobe()).
    [[nodiscard]] constexpr const coating_type& coating() const noexcept { return this->coat().lobe(); }
    [[nodiscard]] constexpr const rgb<T>& k_d() const noexcept { return this->base().k_d(); } ///< base albedo

    /// E_s(mu): the directional albedo of the coating at view cosine mu (dimensionless).
    [[nodiscard]] T coating_albedo(T mu) const noexcept { return this->coat().albedo(mu); }

    /// The base term k_d (1 - E_s(n·l)) (1 - E_s(n·v)) / (pi (1 - E_s,avg)) in 1/sr; 0 unless
    /// n·l > 0 and n·v > 0.
    [[nodiscard]] rgb<T> f_diffuse(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const noexcept {
        const T n_dot_l = glm::dot(at.n(), l);
        const T n_dot_v = glm::dot(at.n(), v);
        if (!(n_dot_l > T(0)) || !(n_dot_v > T(0))) return rgb<T>(0);
        return this->base_factor(n_dot_l, n_dot_v) * this->base().f(l, v, at);
    }

    /// The coating f_s in 1/sr (shade::cook_torrance with kulla_conty).
    [[nodiscard]] rgb<T> f_specular(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const noexcept {
        return this->coat().f_specular(l, v, at);
    }

    /// BRDF value in 1/sr without the cosine: f_specular + f_diffuse (the layer's f).
    [[nodiscard]] rgb<T> f(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const noexcept {
        detail::assert_unit_directions(l, v, at);
        return layer_type::f(l, v, at);
    }

    /// The solid-angle density (1/sr) with which sample() draws l: P_s pdf_s + (1 - P_s)
    /// (n·l) / pi; 0 unless n·l > 0 and n·v > 0.
    [[nodiscard]] T pdf(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const noexcept {
        return layer_type::pdf(l, v, at);
    }

    /// The layer's sample in the given transport mode (a bsdf_sample; its lobes are BRDFs,
    /// so its flags are glossy_reflection, as shade::sample_bsdf gives a BRDF's); in
    /// radiance mode the same l, f, pdf and weight as the BRDF sample below.
    [[nodiscard]] std::optional<bsdf_sample<T>> sample(const vec3<T>& v, T uc, const vec2<T>& u,
                                                       const surface_point<T>& at, transport_mode mode) const {
        return layer_type::sample(v, uc, u, at, mode);
    }

    /// Draws l for the view v: the coating's sampler when uc < P_s (with uc / P_s as its
    /// own lobe choice), else the cosine. Returns l with f, pdf and the weight f (n·l) / pdf
    /// (the layer's radiance-mode sample); nullopt when v or the drawn l is not above the
    /// surface.
    [[nodiscard]] std::optional<brdf_sample<T>> sample(const vec3<T>& v, T uc, const vec2<T>& u,
                                                       const surface_point<T>& at) const noexcept {
        const std::optional<bsdf_sample<T>> s = layer_type::sample(v, uc, u, at, transport_mode::radiance);
        if (!s) return std::nullopt;
        return brdf_sample<T>{s->l, s->f, s->pdf, s->weight};
    }

    /// P_s, the probability that sample() uses the coating's sampler, for a view of cosine
    /// n_dot_v > 0 (see the class comment).
    [[nodiscard]] T specular_probability(T n_dot_v) const noexcept { return this->coat_probability(n_dot_v); }

private:
    // The layer, k_d validated by name before its bound max(k_d) is formed.
    [[nodiscard]] static layer_type make_layer(const ggx<T>& distribution, const rgb<T>& k_d) {
        const lambert<T> base(k_d);
        return layer_type(ggx_dielectric_coating<T>(distribution), base, T(1), layering::reciprocal,
                          base_albedo_choice<T>(detail::max_channel(k_d)));
    }
};

} // namespace shade
