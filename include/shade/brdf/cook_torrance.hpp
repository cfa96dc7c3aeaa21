#pragma once
// shade::cook_torrance: the microfacet specular BRDF F D G / (c (n·l)(n·v))
// (shade::microfacet_reflection, shade/brdf/microfacet_reflection.hpp) over a Lambertian
// base, composed at compile time from a distribution D, a Fresnel term F, a masking term G
// (shade/brdf/microfacet.hpp, shade/brdf/fresnel.hpp) and a normalization form:
//
//   cook_torrance<beckmann<T>, schlick<T>, v_groove<T>>                  default: Walter et al.
//   cook_torrance<ggx<T>, dielectric_fresnel<T>, smith_ggx<T>, cook_torrance_form::course>
//
// and a Scattering policy (shade/brdf/multiple_scattering.hpp): single_scattering, the
// default, or kulla_conty, which adds the energy of multiple scattering back:
//
//   cook_torrance<ggx<T>, schlick<T>, smith_height_correlated<T>, cook_torrance_form::walter, kulla_conty>
//
// Example:
//   const shade::cook_torrance<shade::ggx<float>, shade::schlick<float>, shade::smith_ggx<float>>
//       metal(shade::ggx<float>(0.3f), shade::schlick<float>({0.95f, 0.64f, 0.54f}));

#include <concepts>
#include <optional>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <shade/brdf/brdf.hpp>
#include <shade/brdf/detail/directions.hpp>
#include <shade/brdf/fresnel.hpp>
#include <shade/brdf/microfacet.hpp>
#include <shade/brdf/microfacet/albedo_table.hpp>
#include <shade/brdf/microfacet_reflection.hpp>
#include <shade/brdf/multiple_scattering.hpp>
#include <shade/core/error.hpp>
#include <shade/core/math.hpp>
#include <shade/core/sampling.hpp>
#include <shade/core/surface_point.hpp>
#include <shade/core/types.hpp>

namespace shade {

/// Cook-Torrance reflection: a Lambertian base plus a microfacet specular lobe.
///
///     f = k_d / pi + k_s * scale * F(v·h) D(h) G(l, v, h) / ((n·l)(n·v))
///
/// Cook, Torrance 1982, "A Reflectance Model for Computer Graphics", ACM ToG 1(1): the
/// paper mixes a diffuse and a specular bidirectional reflectance as R = d R_d + s R_s with
/// s + d = 1; here the two weights are the per-channel colours k_d (Lambert albedo, f_d =
/// k_d / pi) and k_s (multiplies the specular term), which reproduce the paper's mixing
/// with k_d = d * (diffuse reflectance) and k_s = s. Neither is coupled to F, so
/// energy conservation needs k_d + k_s * (specular albedo) <= 1 (e.g. k_d + k_s <= 1 with
/// the walter form and a Smith G); the form constants are in shade::cook_torrance_form.
///
/// The specular part is shade::microfacet_reflection (lobe(), the same f and sampler)
/// weighted by k_s. The model keeps a lobe choice of its own because it depends on the view
/// (through F(n·v), below); a shade::mix of the lobe and shade::lambert chooses with a
/// constant probability, which would change the pdf and the samples.
///
/// The terms are evaluated in the local frame of at.shading (t, b, n): l, v and
/// h = normalize(l + v) become vectors with n = +z and t = +x, so an anisotropic
/// distribution's alpha_x (m_x) runs along the frame's tangent. Returns 0 unless n·l > 0
/// and n·v > 0. n·l and n·v are floored at machine epsilon in the denominator
/// (detail::cos_floor) so f stays finite at grazing. Reciprocal: yes. Satisfies
/// shade::split_brdf (f_diffuse = k_d / pi, f_specular = lobe), and shade::sampled_brdf
/// when the distribution is a shade::sampled_microfacet_distribution (ggx, beckmann).
///
/// Sampling (sample, pdf): the specular lobe by the distribution's visible normals (the
/// normal m drawn from D_v(m) = G1(v) max(0, v·m) D(m)/(n·v), l the mirror of v about m),
/// whose density in l is
///
///     pdf_s(l) = D_v(h) / (4 v·h) = G1(v) D(h) / (4 n·v)
///
/// (Heitz 2018, "Sampling the GGX Distribution of Visible Normals", JCGT 7(4), the
/// density of the reflected direction; 1/(4 v·h) is the Jacobian of the reflection,
/// Walter et al. 2007, eq. 14), with the
/// distribution's own Smith G1 whatever masking term G the model uses; the diffuse lobe by
/// the cosine, pdf_d(l) = (n·l)/pi. The lobe is chosen with uc: specular with probability
/// P_s = w_s / (w_s + w_d), an estimate of the lobes' albedos from v alone:
/// w_s = max channel of k_s F(n·v) times 4 * scale (1 for the walter form, whose specular
/// albedo with a Smith G is at most F-weighted k_s), w_d = max channel of k_d; P_s is 1
/// when k_d = 0, 0 when k_s = 0, and otherwise kept in [0.1, 0.9] so that neither lobe is
/// starved where the estimate is poor (F(n·v) can be 0 where F(v·h) is not). pdf and the
/// pdf a sample carries are the mixture P_s pdf_s + (1 - P_s) pdf_d.
///
/// With Scattering = kulla_conty (shade/brdf/multiple_scattering.hpp) the specular lobe
/// is f_ss + f_ms, where f_ss is the lobe above and f_ms Kulla and Conty's
/// multiple-scattering lobe, both times k_s:
///
///     f = k_d / pi + k_s (f_ss + F_ms (1 - E(n·l)) (1 - E(n·v)) / (pi (1 - E_avg)))
///
/// With F = 1 (and k_d = 0, k_s = 1) its albedo is 1 at every view to the accuracy of the
/// albedo tables. k_d stays an independent Lambertian term (the coupled diffuse base is
/// shade::coupled_plastic). Its sampler draws the specular lobe as a mixture: the cosine
/// with probability q(v) = w_ms / (w_ss + w_ms), w_ms = max channel of F_ms times
/// 1 - E(n·v) (f_ms's albedo), w_ss = max channel of F_avg times E(n·v) (an estimate of
/// f_ss's), otherwise the visible normals; pdf_s becomes (1 - q) G1(v) D(h) / (4 n·v) +
/// q (n·l) / pi. With F = 1, q = 1 - E(n·v).
///
/// Distribution: beckmann<T> or ggx<T> (or any shade::microfacet_distribution).
/// Fresnel: schlick<T>, dielectric_fresnel<T> or conductor_fresnel<T> (or any
///          shade::fresnel_term).
/// Masking: v_groove<T>, smith_beckmann<T> (with beckmann), smith_ggx<T> (with ggx),
///          smith_separable<T>, smith_height_correlated<T> (with either);
///          default-constructed (the masking terms are stateless).
/// Scattering: single_scattering (default), kulla_conty or kulla_conty_anisotropic (with ggx or beckmann,
///          smith_height_correlated and the walter form).
template <class Distribution, class Fresnel, class Masking,
          class Form = cook_torrance_form::walter, class Scattering = single_scattering>
    requires microfacet_distribution<Distribution> &&
             fresnel_term<Fresnel, scalar_of<Distribution>> &&
             masking_for<Masking, Distribution> && std::default_initializable<Masking> &&
             cook_torrance_normalization<Form, scalar_of<Distribution>> &&
             scattering_policy_for<Scattering, Distribution, Masking, Form>
class cook_torrance {
public:
    using scalar_type = scalar_of<Distribution>;
    using distribution_type = Distribution;
    using fresnel_type = Fresnel;
    using masking_type = Masking;
    using form_type = Form;
    using scattering_type = Scattering;
    /// The specular lobe this model weighs by k_s.
    using lobe_type = microfacet_reflection<Distribution, Fresnel, Masking, Form, Scattering>;

private:
    using T = scalar_type;
    static constexpr bool compensated = std::derived_from<Scattering, kulla_conty>;

public:
    /// Validating constructor (the distribution and Fresnel term validated their own
    /// parameters when they were built). Throws shade::invalid_parameter if the peak value
    /// of f would overflow T: naming the distribution's parameter ("alpha", "m", or the
    /// anisotropic one that sets the peak) when the specular lobe overflows with k_s = 1,
    /// else "k_s" or "k_d"; and naming "k_s" or "k_d" unless every channel is finite and
    /// >= 0.
    cook_torrance(const Distribution& distribution, const Fresnel& fresnel,
                  const rgb<T>& k_s = rgb<T>(1), const rgb<T>& k_d = rgb<T>(0))
        : k_s_(require_non_negative("k_s", k_s)), k_d_(require_non_negative("k_d", k_d)),
          lobe_(distribution, fresnel) {
        const T peak = detail::max_channel(k_s_) * lobe_.peak();
        detail::require_finite_peak("k_s", peak);
        detail::require_finite_peak("k_d", detail::max_channel(k_d_) * inv_pi<T> + peak);
    }

    /// Unchecked: the caller guarantees k_s, k_d finite and >= 0 (and not so large that f
    /// overflows).
    cook_torrance(unchecked_t, const Distribution& distribution, const Fresnel& fresnel,
                  const rgb<T>& k_s = rgb<T>(1), const rgb<T>& k_d = rgb<T>(0)) noexcept
        : k_s_(k_s), k_d_(k_d), lobe_(unchecked, distribution, fresnel) {}

    [[nodiscard]] constexpr const Distribution& distribution() const noexcept { return lobe_.distribution(); } ///< D term
    [[nodiscard]] constexpr const Fresnel& fresnel() const noexcept { return lobe_.fresnel(); } ///< F term
    [[nodiscard]] constexpr const rgb<T>& k_s() const noexcept { return k_s_; } ///< specular weight
    [[nodiscard]] constexpr const rgb<T>& k_d() const noexcept { return k_d_; } ///< Lambert albedo
    [[nodiscard]] constexpr const lobe_type& lobe() const noexcept { return lobe_; } ///< the specular lobe (k_s = 1)

    /// Diffuse part k_d / pi (1/sr), 0 unless n·l > 0 and n·v > 0.
    [[nodiscard]] rgb<T> f_diffuse(const vec3<T>& l, const vec3<T>& v,
                                   const surface_point<T>& at) const noexcept {
        if (!(glm::dot(at.n(), l) > T(0)) || !(glm::dot(at.n(), v) > T(0))) return rgb<T>(0);
        return k_d_ * inv_pi<T>;
    }

    /// Specular part k_s scale F D G / ((n·l)(n·v)) (1/sr), plus k_s f_ms with
    /// kulla_conty: k_s times the lobe's f; 0 unless n·l > 0 and n·v > 0.
    [[nodiscard]] rgb<T> f_specular(const vec3<T>& l, const vec3<T>& v,
                                    const surface_point<T>& at) const noexcept {
        const auto value =
            lobe_.template evaluate_local<true, false>(at.shading.to_local(l), at.shading.to_local(v), k_s_, T(0));
        if constexpr (compensated)
            return value.single + value.multiple;
        else
            return value.single;
    }

    /// With kulla_conty: the albedo E(mu) of the single-scattering lobe with F = 1 at
    /// the view cosine mu (microfacet_reflection::single_scattering_albedo).
    [[nodiscard]] T single_scattering_albedo(T mu) const noexcept
        requires compensated
    {
        return lobe_.single_scattering_albedo(mu);
    }

    /// With kulla_conty: the E(w) f_ms uses for the unit local direction w (n = +z)
    /// (microfacet_reflection::single_scattering_albedo).
    [[nodiscard]] T single_scattering_albedo(const vec3<T>& w_local) const noexcept
        requires compensated
    {
        return lobe_.single_scattering_albedo(w_local);
    }

    /// With kulla_conty: E_avg, the cosine-weighted average of single_scattering_albedo.
    [[nodiscard]] T average_single_scattering_albedo() const noexcept
        requires compensated
    {
        return lobe_.average_single_scattering_albedo();
    }

    /// With kulla_conty: the probability q that sample(), having chosen the specular lobe,
    /// draws from the cosine (f_ms) rather than the visible normals, for a view of cosine
    /// n_dot_v (see the class comment).
    [[nodiscard]] T multiple_scattering_probability(T n_dot_v) const noexcept
        requires compensated
    {
        return lobe_.multiple_scattering_probability(n_dot_v);
    }

    /// BRDF value in 1/sr without the cosine: f_diffuse + f_specular.
    [[nodiscard]] rgb<T> f(const vec3<T>& l, const vec3<T>& v,
                           const surface_point<T>& at) const noexcept {
        return evaluate<true, false>(at.shading.to_local(l), at.shading.to_local(v), lobe_choice{}).f;
    }

    /// The solid-angle density (1/sr) with which sample() draws l for the view v: the
    /// mixture P_s pdf_s(l) + (1 - P_s) pdf_d(l) of the class comment. 0 unless n·l > 0 and
    /// n·v > 0.
    [[nodiscard]] T pdf(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const noexcept
        requires sampled_microfacet_distribution<Distribution>
    {
        const vec3<T> v_local = at.shading.to_local(v);
        if (!(v_local.z > T(0))) return T(0);
        return evaluate<false, true>(at.shading.to_local(l), v_local, lobe_choice_for(v_local.z)).pdf;
    }

    /// Draws a direction l toward the light for the view v: the lobe chosen with uc in
    /// [0,1) (specular when uc < P_s), the direction within it from u in [0,1)^2 (see the
    /// class comment). Returns l with f(l, v, at), pdf(l, v, at) and the weight
    /// f (n·l) / pdf; nullopt when v is not above the surface or the drawn l is not.
    [[nodiscard]] std::optional<brdf_sample<T>> sample(const vec3<T>& v, T uc, const vec2<T>& u,
                                                       const surface_point<T>& at) const noexcept
        requires sampled_microfacet_distribution<Distribution>
    {
        const vec3<T> v_local = at.shading.to_local(v);
        if (!(v_local.z > T(0))) return std::nullopt;
        vec3<T> l_local;
        const lobe_choice choice = lobe_choice_for(v_local.z);
        if (uc < choice.p_s) {
            bool cosine = false;
            // Of the specular draws (uc < p_s), the share q goes to the cosine.
            if constexpr (compensated) cosine = uc < choice.p_s * choice.q;
            l_local = lobe_.draw_local(v_local, cosine, u);
        } else {
            l_local = square_to_cosine_hemisphere(u);
        }
        const vec3<T> l = at.shading.to_world(l_local);
        // f and pdf from l as f() and pdf() would take it (its local form recomputed from
        // the world direction returned), so the sample carries exactly their values; v's
        // local form and the lobe choice are the ones they compute too.
        const vec3<T> l_back = at.shading.to_local(l);
        if (!(l_back.z > T(0))) return std::nullopt;
        const auto value = evaluate<true, true>(l_back, v_local, choice);
        return detail::make_brdf_sample(l, value.f, value.pdf, l_back.z);
    }

    /// The probability P_s that sample() picks the specular lobe for a view with
    /// cosine n_dot_v > 0 (see the class comment).
    [[nodiscard]] T specular_probability(T n_dot_v) const noexcept {
        const T w_d = detail::max_channel(k_d_);
        if (!(w_d > T(0))) return T(1);
        if (!(detail::max_channel(k_s_) > T(0))) return T(0);
        const T w_s = detail::max_channel(k_s_ * lobe_.fresnel().F(n_dot_v)) *
                      (T(4) * Form::template scale<T>());
        // Divided by the larger weight first, so that huge (valid) weights cannot overflow
        // the sum.
        const T larger = glm::max(w_s, w_d);
        const T p = (w_s / larger) / (w_s / larger + w_d / larger);
        return glm::clamp(p, T(0.1), T(0.9));
    }

private:
    struct value_and_pdf {
        rgb<T> f{0};
        T pdf{0};
    };

    // The lobe probabilities of a view: P_s, and with kulla_conty the share q of the
    // specular draws that go to the cosine (0 otherwise).
    struct lobe_choice {
        T p_s{0};
        T q{0};
    };

    // For a view of cosine n_dot_v > 0.
    [[nodiscard]] lobe_choice lobe_choice_for(T n_dot_v) const noexcept {
        lobe_choice out{specular_probability(n_dot_v), T(0)};
        if constexpr (compensated) out.q = multiple_scattering_probability(n_dot_v);
        return out;
    }

    // f and/or pdf of local l and v (choice: the lobe probabilities of v, read only for
    // the pdf), one routine for f(), pdf() and sample(), so that sample() returns exactly
    // what f() and pdf() return at its direction. The specular lobe's parts come from
    // lobe_type::evaluate_local with weight k_s.
    template <bool with_f, bool with_pdf>
    [[nodiscard]] value_and_pdf evaluate(const vec3<T>& l_local, const vec3<T>& v_local,
                                         const lobe_choice& choice) const noexcept {
        value_and_pdf out;
        if (!(l_local.z > T(0)) || !(v_local.z > T(0))) return out;
        const auto lobe = lobe_.template evaluate_local<with_f, with_pdf>(l_local, v_local, k_s_, choice.q);
        if constexpr (with_f) {
            out.f = k_d_ * inv_pi<T> + lobe.single;
            if constexpr (compensated) out.f += lobe.multiple;
        }
        if constexpr (with_pdf) {
            const T p_s = choice.p_s;
            // The specular density is not read where the lobe is never chosen.
            const T pdf_s = p_s > T(0) ? lobe.pdf : T(0);
            out.pdf = p_s * pdf_s + (T(1) - p_s) * l_local.z * inv_pi<T>;
        }
        return out;
    }

    rgb<T> k_s_;
    rgb<T> k_d_;
    lobe_type lobe_;
};

} // namespace shade
