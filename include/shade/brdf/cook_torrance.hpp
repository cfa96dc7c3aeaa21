#pragma once
// shade::cook_torrance: the microfacet specular BRDF F D G / (c (n·l)(n·v)) over a
// Lambertian base, composed at compile time from a distribution D, a Fresnel term F, a
// masking term G (shade/brdf/microfacet.hpp, shade/brdf/fresnel.hpp) and a normalization
// form:
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
#include <shade/brdf/multiple_scattering.hpp>
#include <shade/core/error.hpp>
#include <shade/core/math.hpp>
#include <shade/core/sampling.hpp>
#include <shade/core/surface_point.hpp>
#include <shade/core/types.hpp>

namespace shade {

/// The normalizations of the Cook-Torrance specular term, used as the Form parameter of
/// shade::cook_torrance. Each form is f_s = scale * F D G / ((n·l)(n·v)) with D the
/// normalized distribution (integral of D (n·h) dh = 1, as in shade/brdf/microfacet.hpp);
/// `scale<T>()` returns that constant and `factor_vs_walter` its ratio to the default.
/// All three forms are reciprocal (every factor is symmetric in l and v).
namespace cook_torrance_form {

/// The microfacet-consistent form (default):  f_s = F D G / (4 (n·l)(n·v)).
///
/// Walter, Marschner, Li, Torrance 2007, "Microfacet Models for Refraction through Rough
/// Surfaces", EGSR, eq. 20. The 4 is the Jacobian |dh/dl| = 1/(4 (h·l)) of the half-vector
/// map. With a Smith G (and F <= 1) the directional albedo is <= 1: energy conserving
/// (single scattering only, so rough surfaces lose some energy). With the V-groove G the
/// albedo is also below 1 in our numerical checks, but no general bound is claimed.
struct walter {
    static constexpr double factor_vs_walter = 1.0;
    template <std::floating_point T>
    [[nodiscard]] static constexpr T scale() noexcept {
        return T(0.25);
    }
};

/// The form common in course slides and textbooks:  f_s = F D G / (pi (n·l)(n·v)).
///
/// This is the 1982 paper's expression (see paper_1982) with a NORMALIZED D plugged in.
/// It is 4/pi ~ 1.27 times the default, so it reflects more energy than it receives:
/// with F = 1 and a narrow lobe the albedo at normal incidence is ~1.27. Not energy
/// conserving.
struct course {
    static constexpr double factor_vs_walter = 4.0 / 3.14159265358979323846;
    template <std::floating_point T>
    [[nodiscard]] static constexpr T scale() noexcept {
        return inv_pi<T>;
    }
};

/// The expression of the 1982 paper, with the paper's own (unnormalized) distribution.
///
/// Cook, Torrance 1982, "A Reflectance Model for Computer Graphics", ACM ToG 1(1): 7-24:
///   R_s = (F / pi) D G / ((N·L)(N·V)),   with Beckmann   D = exp(-(tan(alpha)/m)^2) / (m^2 cos^4(alpha)).
/// The paper's D has no 1/pi, i.e. it is pi times the normalized D_beckmann, so in terms
/// of the normalized D used here
///   R_s = (F / pi) (pi D) G / ((n·l)(n·v)) = F D G / ((n·l)(n·v)),
/// which is 4 times the default. (For GGX the same convention, pi times the normalized D,
/// is applied.) Not energy conserving: with F = 1 and a narrow lobe the albedo at normal
/// incidence is ~4. Provided to reproduce the paper's images and numbers. (The paper's
/// expression was checked against secondary sources quoting it, not the original scan.)
struct paper_1982 {
    static constexpr double factor_vs_walter = 4.0;
    template <std::floating_point T>
    [[nodiscard]] static constexpr T scale() noexcept {
        return T(1);
    }
};

} // namespace cook_torrance_form

/// X is one of the shade::cook_torrance_form types (or a user type with the same members).
template <class X, class T>
concept cook_torrance_normalization = std::floating_point<T> && requires {
    { X::template scale<T>() } -> std::same_as<T>;
};

/// The distribution, masking and form are those the Kulla-Conty tables were computed for:
/// ggx or beckmann, smith_height_correlated, cook_torrance_form::walter.
template <class Distribution, class Masking, class Form>
concept kulla_conty_compensable =
    requires { detail::albedo_tables_of<Distribution>::e; } &&
    std::same_as<Masking, smith_height_correlated<scalar_of<Distribution>>> &&
    std::same_as<Form, cook_torrance_form::walter>;

/// S is a Scattering policy of shade::cook_torrance for this distribution, masking and
/// form: single_scattering always, kulla_conty (or kulla_conty_anisotropic, derived from
/// it) when kulla_conty_compensable.
template <class S, class Distribution, class Masking, class Form>
concept scattering_policy_for =
    std::same_as<S, single_scattering> ||
    (std::derived_from<S, kulla_conty> && kulla_conty_compensable<Distribution, Masking, Form>);

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
        : distribution_(distribution), fresnel_(fresnel),
          k_s_(require_non_negative("k_s", k_s)), k_d_(require_non_negative("k_d", k_d)) {
        if constexpr (compensated) ms_ = detail::scattering_state<Scattering, T>(distribution_, fresnel_);
        // D <= peak, F <= 1, G <= 1, 1/((n·l)(n·v)) <= 1/cos_floor^2; with kulla_conty,
        // f_ms <= its scale (each 1 - E factor is <= 1).
        const T floor2 = detail::cos_floor<T> * detail::cos_floor<T>;
        T lobe_peak = Form::template scale<T>() * (distribution_.peak() / floor2);
        if constexpr (compensated) lobe_peak += detail::max_channel(ms_.scale);
        detail::require_finite_peak(detail::peak_parameter_of(distribution_), lobe_peak);
        const T peak = detail::max_channel(k_s_) * lobe_peak;
        detail::require_finite_peak("k_s", peak);
        detail::require_finite_peak("k_d", detail::max_channel(k_d_) * inv_pi<T> + peak);
    }

    /// Unchecked: the caller guarantees k_s, k_d finite and >= 0 (and not so large that f
    /// overflows).
    cook_torrance(unchecked_t, const Distribution& distribution, const Fresnel& fresnel,
                  const rgb<T>& k_s = rgb<T>(1), const rgb<T>& k_d = rgb<T>(0)) noexcept
        : distribution_(distribution), fresnel_(fresnel), k_s_(k_s), k_d_(k_d) {
        if constexpr (compensated) ms_ = detail::scattering_state<Scattering, T>(distribution_, fresnel_);
    }

    [[nodiscard]] constexpr const Distribution& distribution() const noexcept { return distribution_; } ///< D term
    [[nodiscard]] constexpr const Fresnel& fresnel() const noexcept { return fresnel_; } ///< F term
    [[nodiscard]] constexpr const rgb<T>& k_s() const noexcept { return k_s_; } ///< specular weight
    [[nodiscard]] constexpr const rgb<T>& k_d() const noexcept { return k_d_; } ///< Lambert albedo

    /// Diffuse part k_d / pi (1/sr), 0 unless n·l > 0 and n·v > 0.
    [[nodiscard]] rgb<T> f_diffuse(const vec3<T>& l, const vec3<T>& v,
                                   const surface_point<T>& at) const noexcept {
        if (!(glm::dot(at.n(), l) > T(0)) || !(glm::dot(at.n(), v) > T(0))) return rgb<T>(0);
        return k_d_ * inv_pi<T>;
    }

    /// Specular part k_s scale F D G / ((n·l)(n·v)) (1/sr), plus k_s f_ms with
    /// kulla_conty; 0 unless n·l > 0 and n·v > 0.
    [[nodiscard]] rgb<T> f_specular(const vec3<T>& l, const vec3<T>& v,
                                    const surface_point<T>& at) const noexcept {
        const vec3<T> l_local = at.shading.to_local(l);
        const vec3<T> v_local = at.shading.to_local(v);
        if (!(l_local.z > T(0)) || !(v_local.z > T(0))) return rgb<T>(0);
        const auto [h, v_dot_h] = detail::half_vector_and_cos(l_local, v_local);
        if constexpr (compensated)
            return specular(l_local, v_local, h, v_dot_h, D_of(h)) + multiple_scattering(l_local, v_local);
        else
            return specular(l_local, v_local, h, v_dot_h, D_of(h));
    }

    /// With kulla_conty: the albedo E(mu) of the single-scattering lobe with F = 1 at
    /// the view cosine mu, read from the table at the model's roughness (in [0, 1]); for
    /// an anisotropic distribution, the isotropic table at sqrt(alpha_x alpha_y).
    [[nodiscard]] T single_scattering_albedo(T mu) const noexcept
        requires compensated
    {
        return detail::albedo_lookup(detail::albedo_tables_of<Distribution>::e, detail::albedo_grid_nodes, mu,
                                     ms_.alpha);
    }

    /// With kulla_conty: the E(w) f_ms uses for the unit local direction w (n = +z): the
    /// above at w.z, plus with kulla_conty_anisotropic its correction for w's azimuth.
    [[nodiscard]] T single_scattering_albedo(const vec3<T>& w_local) const noexcept
        requires compensated
    {
        return ms_.template albedo<Distribution>(w_local);
    }

    /// With kulla_conty: E_avg, the cosine-weighted average of single_scattering_albedo.
    [[nodiscard]] T average_single_scattering_albedo() const noexcept
        requires compensated
    {
        return ms_.e_avg;
    }

    /// With kulla_conty: the probability q that sample(), having chosen the specular lobe,
    /// draws from the cosine (f_ms) rather than the visible normals, for a view of cosine
    /// n_dot_v (see the class comment).
    [[nodiscard]] T multiple_scattering_probability(T n_dot_v) const noexcept
        requires compensated
    {
        const T e = single_scattering_albedo(n_dot_v);
        const T w_ms = ms_.f_ms_max * (T(1) - e);
        const T w_ss = ms_.f_avg_max * e;
        return w_ms > T(0) ? w_ms / (w_ms + w_ss) : T(0);
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
            if (cosine) {
                l_local = square_to_cosine_hemisphere(u);
            } else {
                const vec3<T> m = distribution_.sample_visible_normal(v_local, u);
                l_local = T(2) * glm::dot(v_local, m) * m - v_local;
            }
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
        const T w_s = detail::max_channel(k_s_ * fresnel_.F(n_dot_v)) *
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
    // what f() and pdf() return at its direction.
    template <bool with_f, bool with_pdf>
    [[nodiscard]] value_and_pdf evaluate(const vec3<T>& l_local, const vec3<T>& v_local,
                                         const lobe_choice& choice) const noexcept {
        value_and_pdf out;
        if (!(l_local.z > T(0)) || !(v_local.z > T(0))) return out;
        const auto [h, v_dot_h] = detail::half_vector_and_cos(l_local, v_local);
        const T d = D_of(h);
        if constexpr (with_f) {
            out.f = k_d_ * inv_pi<T> + specular(l_local, v_local, h, v_dot_h, d);
            if constexpr (compensated) out.f += multiple_scattering(l_local, v_local);
        }
        if constexpr (with_pdf) {
            const T p_s = choice.p_s;
            // pdf_s = G1(v) D(h) / (4 n·v); v_local.z > 0 here.
            T pdf_s = p_s > T(0) ? distribution_.G1(v_local) * d / (T(4) * v_local.z) : T(0);
            if constexpr (compensated) {
                const T q = choice.q;
                pdf_s = (T(1) - q) * pdf_s + q * l_local.z * inv_pi<T>;
            }
            out.pdf = p_s * pdf_s + (T(1) - p_s) * l_local.z * inv_pi<T>;
        }
        return out;
    }

    // D of the local half vector: D(h) when the distribution has the local form, else
    // D(n·h).
    [[nodiscard]] T D_of(const vec3<T>& h) const noexcept {
        if constexpr (requires { { distribution_.D(h) } -> std::same_as<T>; })
            return distribution_.D(h);
        else
            return distribution_.D(h.z);
    }

    // k_s scale F(v·h) D G / ((n·l)(n·v)) for local l, v, h with n·l, n·v > 0.
    [[nodiscard]] rgb<T> specular(const vec3<T>& l, const vec3<T>& v, const vec3<T>& h, T v_dot_h,
                                  T d) const noexcept {
        T g;
        if constexpr (requires { { masking_.G(distribution_, l, v, h, v_dot_h) } -> std::same_as<T>; })
            g = masking_.G(distribution_, l, v, h, v_dot_h);
        else
            g = masking_.G(distribution_, l.z, v.z, h.z, v_dot_h);
        const T lobe = Form::template scale<T>() * d * g /
                       (detail::floored_cos(l.z) * detail::floored_cos(v.z));
        return k_s_ * fresnel_.F(v_dot_h) * lobe;
    }

    // k_s f_ms = k_s F_ms (1 - E(l)) (1 - E(v)) / (pi (1 - E_avg)) for local l, v above
    // the surface (kulla_conty only). Each factor is computed the same way for l and v, so
    // the product is the same number with l and v exchanged.
    [[nodiscard]] rgb<T> multiple_scattering(const vec3<T>& l_local, const vec3<T>& v_local) const noexcept
        requires compensated
    {
        const T loss_l = T(1) - single_scattering_albedo(l_local);
        const T loss_v = T(1) - single_scattering_albedo(v_local);
        return k_s_ * ms_.scale * (loss_l * loss_v);
    }

    Distribution distribution_;
    Fresnel fresnel_;
    [[no_unique_address]] Masking masking_{};
    rgb<T> k_s_;
    rgb<T> k_d_;
    [[no_unique_address]] detail::scattering_state<Scattering, T> ms_{};
};

} // namespace shade
