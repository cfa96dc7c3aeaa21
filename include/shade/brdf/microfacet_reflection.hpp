#pragma once
// shade::microfacet_reflection: the specular microfacet lobe on its own, F D G / (4 (n·l)(n·v))
// (or another normalization), composed at compile time from a distribution D, a Fresnel
// term F, a masking term G (shade/brdf/microfacet.hpp, shade/brdf/fresnel.hpp), a
// normalization form and a Scattering policy (shade/brdf/multiple_scattering.hpp):
//
//   microfacet_reflection<ggx<T>, schlick<T>, smith_height_correlated<T>>                    a rough metal
//   microfacet_reflection<ggx<T>, schlick<T>, smith_height_correlated<T>, cook_torrance_form::walter, kulla_conty>
//
// It is a sampled BRDF (shade::sampled_brdf, so a shade::sampled_bsdf too) that combines
// with others through shade::mix and shade::layer (shade/bsdf); shade::cook_torrance is this
// lobe under a Lambertian term with a lobe choice of its own. With its last parameter
// reflection_sides::both it also reflects below the surface (a coat seen from inside), and
// is a BSDF with its own sampler instead. Also the home of the normalization forms
// (shade::cook_torrance_form), the sides (shade::reflection_sides) and the Scattering
// policy concepts.
//
// Example:
//   const shade::microfacet_reflection<shade::ggx<float>, shade::schlick<float>, shade::smith_ggx<float>>
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
#include <shade/bsdf/bsdf.hpp>
#include <shade/core/error.hpp>
#include <shade/core/math.hpp>
#include <shade/core/sampling.hpp>
#include <shade/core/surface_point.hpp>
#include <shade/core/types.hpp>

namespace shade {

/// The normalizations of the Cook-Torrance specular term, used as the Form parameter of
/// shade::microfacet_reflection and shade::cook_torrance. Each form is f_s = scale * F D G / ((n·l)(n·v)) with D the
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

/// Which sides of the surface shade::microfacet_reflection reflects on: its Sides
/// parameter.
namespace reflection_sides {

/// Above the surface only (default): l and v with n·l > 0 and n·v > 0, f = 0 otherwise (the
/// BRDF contract); the lobe is a shade::sampled_brdf.
struct above {};

/// Above, and below when l and v are both below (the surface's underside, e.g. a coat seen
/// from inside the medium it covers). The lobe is then a BSDF with its own sampler
/// (shade::bsdf_sampler), not a BRDF.
struct both {};

} // namespace reflection_sides

/// X is one of the shade::reflection_sides tags.
template <class X>
concept reflection_sides_tag = std::same_as<X, reflection_sides::above> || std::same_as<X, reflection_sides::both>;

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

/// S is a Scattering policy of shade::microfacet_reflection and shade::cook_torrance for
/// this distribution, masking and
/// form: single_scattering always, kulla_conty (or kulla_conty_anisotropic, derived from
/// it) when kulla_conty_compensable.
template <class S, class Distribution, class Masking, class Form>
concept scattering_policy_for =
    std::same_as<S, single_scattering> ||
    (std::derived_from<S, kulla_conty> && kulla_conty_compensable<Distribution, Masking, Form>);

/// The specular microfacet lobe: reflection from a surface of microscopic mirrors.
///
///     f = scale * F(v·h) D(h) G(l, v, h) / ((n·l)(n·v)),   h = normalize(l + v)
///
/// in 1/sr, without the cosine. With the default form (scale = 1/4) this is Walter,
/// Marschner, Li, Torrance 2007, "Microfacet Models for Refraction through Rough
/// Surfaces", EGSR, eq. 20, the specular term of Cook, Torrance 1982, "A Reflectance Model
/// for Computer Graphics", ACM ToG 1(1) with a normalized D; the other forms are in
/// shade::cook_torrance_form. The terms are evaluated in the local frame of at.shading
/// (t, b, n): l, v and h become vectors with n = +z and t = +x, so an anisotropic
/// distribution's alpha_x (m_x) runs along the frame's tangent. Returns 0 unless n·l > 0
/// and n·v > 0 (a BRDF: reflection above the surface; l and v on opposite sides give 0),
/// except that with Sides = reflection_sides::both it reflects below too (see below).
/// n·l and n·v are floored at machine epsilon in the denominator (detail::cos_floor) so f
/// stays finite at grazing. Reciprocal: yes (every factor is symmetric in l and v). With a
/// Smith G, F <= 1 and the walter form, its directional albedo is at most 1 (single
/// scattering loses the energy of light that bounces between microfacets).
///
/// Sampling (sample, pdf), when the distribution is a shade::sampled_microfacet_distribution
/// (ggx, beckmann): the normal m drawn from the visible normals of v,
/// D_v(m) = G1(v) max(0, v·m) D(m)/(n·v) (shade::D_visible), l the mirror of v about m,
/// whose density in l is
///
///     pdf(l) = D_v(h) / (4 v·h) = G1(v) D(h) / (4 n·v)
///
/// (Heitz 2018, "Sampling the GGX Distribution of Visible Normals", JCGT 7(4), the density
/// of the reflected direction; 1/(4 v·h) is the Jacobian of the reflection, Walter et al.
/// 2007, eq. 14), with the distribution's own Smith G1 whatever masking term G the lobe
/// uses. uc is not used.
///
/// With Scattering = kulla_conty (or kulla_conty_anisotropic) the lobe is f_ss + f_ms, f_ss
/// the lobe above and f_ms Kulla and Conty's multiple-scattering lobe
/// (shade/brdf/multiple_scattering.hpp):
///
///     f = f_ss + F_ms (1 - E(n·l)) (1 - E(n·v)) / (pi (1 - E_avg))
///
/// With F = 1 its albedo is 1 at every view to the accuracy of the albedo tables. It is
/// sampled as a mixture: the cosine when uc < q(v) = w_ms / (w_ss + w_ms), w_ms = max
/// channel of F_ms times 1 - E(n·v) (f_ms's albedo), w_ss = max channel of F_avg times
/// E(n·v) (an estimate of f_ss's), otherwise the visible normals; pdf becomes
/// (1 - q) G1(v) D(h) / (4 n·v) + q (n·l) / pi. With F = 1, q = 1 - E(n·v).
///
/// Distribution: beckmann<T> or ggx<T> (or any shade::microfacet_distribution).
/// Fresnel: schlick<T>, dielectric_fresnel<T> or conductor_fresnel<T> (or any
///          shade::fresnel_term).
/// Masking: v_groove<T>, smith_beckmann<T> (with beckmann), smith_ggx<T> (with ggx),
///          smith_separable<T>, smith_height_correlated<T> (with either);
///          default-constructed (the masking terms are stateless).
/// Scattering: single_scattering (default), kulla_conty or kulla_conty_anisotropic (with
///          ggx or beckmann, smith_height_correlated and the walter form).
/// Sides: reflection_sides::above (default: a BRDF, f = 0 unless both directions are above)
///          or reflection_sides::both (with single_scattering only; below).
///
/// Reflection from below (Sides = reflection_sides::both). When n·l < 0 and n·v < 0 the lobe
/// reflects off the surface's underside: f(l, v) is the above formula at the mirror images
/// l', v' of l and v in the tangent plane, with the Fresnel term evaluated at the cosine
/// -(v'·h') < 0, h' = normalize(l' + v'): the cosine of v against the microfacet normal
/// turned to n's side, as in rough_dielectric's reflection (Walter, Marschner, Li, Torrance
/// 2007, eq. 20 with the generalized half vector of eq. 16 on n's side). This is the
/// two-sided form of every term: D(m) = D(-m), Lambda and G1 of a direction below are its
/// mirror image's, and a negative cosine gives F_dielectric with 1/eta (shade::F_dielectric:
/// light inside the medium), Schlick's and the conductor Fresnel the value at |cos|. So a
/// dielectric_fresnel(eta) lobe seen from below has the values of a dielectric_fresnel(1/eta)
/// lobe at the mirrored pair, total internal reflection included. l and v on opposite sides
/// give 0 (this lobe does not transmit). sample(v, uc, u, at, mode) draws from v's side:
/// below, the mirror image of the draw for v' (visible normals of v'), with the mirrored
/// density; bsdf_sample flags glossy_reflection, eta 1. Only with single_scattering: the
/// Kulla-Conty factor F_ms comes from F's average over the outer side, which inside a
/// dielectric (total internal reflection) is another number.
template <class Distribution, class Fresnel, class Masking,
          class Form = cook_torrance_form::walter, class Scattering = single_scattering,
          class Sides = reflection_sides::above>
    requires microfacet_distribution<Distribution> &&
             fresnel_term<Fresnel, scalar_of<Distribution>> &&
             masking_for<Masking, Distribution> && std::default_initializable<Masking> &&
             cook_torrance_normalization<Form, scalar_of<Distribution>> &&
             scattering_policy_for<Scattering, Distribution, Masking, Form> && reflection_sides_tag<Sides> &&
             (std::same_as<Sides, reflection_sides::above> || std::same_as<Scattering, single_scattering>)
class microfacet_reflection {
public:
    using scalar_type = scalar_of<Distribution>;
    using distribution_type = Distribution;
    using fresnel_type = Fresnel;
    using masking_type = Masking;
    using form_type = Form;
    using scattering_type = Scattering;
    using sides_type = Sides;

private:
    using T = scalar_type;
    static constexpr bool compensated = std::derived_from<Scattering, kulla_conty>;
    static constexpr bool two_sided = std::same_as<Sides, reflection_sides::both>;

public:
    /// Validating constructor (the distribution and Fresnel term validated their own
    /// parameters when they were built). Throws shade::invalid_parameter naming the
    /// distribution's parameter ("alpha", "m", or the anisotropic one that sets the peak)
    /// if the peak value of f (peak()) would overflow T.
    microfacet_reflection(const Distribution& distribution, const Fresnel& fresnel)
        : distribution_(distribution), fresnel_(fresnel) {
        if constexpr (compensated) ms_ = detail::scattering_state<Scattering, T>(distribution_, fresnel_);
        detail::require_finite_peak(detail::peak_parameter_of(distribution_), peak());
    }

    /// Unchecked: the caller guarantees that peak() is finite.
    microfacet_reflection(unchecked_t, const Distribution& distribution, const Fresnel& fresnel) noexcept
        : distribution_(distribution), fresnel_(fresnel) {
        if constexpr (compensated) ms_ = detail::scattering_state<Scattering, T>(distribution_, fresnel_);
    }

    [[nodiscard]] constexpr const Distribution& distribution() const noexcept { return distribution_; } ///< D term
    [[nodiscard]] constexpr const Fresnel& fresnel() const noexcept { return fresnel_; } ///< F term

    /// An upper bound of f over all pairs (1/sr): scale D_peak / cos_floor^2 (D <= its
    /// peak, F <= 1, G <= 1, 1/((n·l)(n·v)) <= 1/cos_floor^2), plus with kulla_conty the
    /// largest channel of f_ms's scale (each 1 - E factor is <= 1).
    [[nodiscard]] T peak() const noexcept {
        const T floor2 = detail::cos_floor<T> * detail::cos_floor<T>;
        T bound = Form::template scale<T>() * (distribution_.peak() / floor2);
        if constexpr (compensated) bound += detail::max_channel(ms_.scale);
        return bound;
    }

    /// BRDF value in 1/sr without the cosine (class comment); 0 unless n·l > 0 and n·v > 0,
    /// or with reflection_sides::both, n·l < 0 and n·v < 0 (the underside).
    [[nodiscard]] rgb<T> f(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const noexcept {
        detail::assert_unit_directions(l, v, at);
        if constexpr (two_sided) {
            const vec3<T> l_local = at.shading.to_local(l);
            const vec3<T> v_local = at.shading.to_local(v);
            if (v_local.z < T(0)) return evaluate_below<true, false>(l_local, v_local).single;
            return evaluate_local<true, false>(l_local, v_local, rgb<T>(1), T(0)).single;
        }
        const parts value = evaluate_local<true, false>(at.shading.to_local(l), at.shading.to_local(v), rgb<T>(1), T(0));
        if constexpr (compensated)
            return value.single + value.multiple;
        else
            return value.single;
    }

    /// The solid-angle density (1/sr) with which sample() draws l for the view v (class
    /// comment); 0 unless n·l > 0 and n·v > 0, or with reflection_sides::both, both < 0.
    [[nodiscard]] T pdf(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const noexcept
        requires sampled_microfacet_distribution<Distribution>
    {
        const vec3<T> v_local = at.shading.to_local(v);
        if constexpr (two_sided) {
            if (v_local.z < T(0)) return evaluate_below<false, true>(at.shading.to_local(l), v_local).pdf;
        }
        if (!(v_local.z > T(0))) return T(0);
        return evaluate_local<false, true>(at.shading.to_local(l), v_local, rgb<T>(1), cosine_share(v_local.z)).pdf;
    }

    /// Draws a direction l toward the light for the view v: a visible normal from u in
    /// [0,1)^2 and the mirror of v about it (with kulla_conty, the cosine when uc < q, uc in
    /// [0,1)). Returns l with f(l, v, at), pdf(l, v, at) and the weight f (n·l) / pdf;
    /// nullopt when v is not above the surface or the drawn l is not.
    [[nodiscard]] std::optional<brdf_sample<T>> sample(const vec3<T>& v, T uc, const vec2<T>& u,
                                                       const surface_point<T>& at) const noexcept
        requires sampled_microfacet_distribution<Distribution> && (!two_sided)
    {
        const vec3<T> v_local = at.shading.to_local(v);
        if (!(v_local.z > T(0))) return std::nullopt;
        const T q = cosine_share(v_local.z);
        const vec3<T> l = at.shading.to_world(draw_local(v_local, compensated && uc < q, u));
        // f and pdf from l as f() and pdf() would take it (its local form recomputed from
        // the world direction returned), so the sample carries exactly their values.
        const vec3<T> l_back = at.shading.to_local(l);
        if (!(l_back.z > T(0))) return std::nullopt;
        const parts value = evaluate_local<true, true>(l_back, v_local, rgb<T>(1), q);
        if constexpr (compensated)
            return detail::make_brdf_sample(l, value.single + value.multiple, value.pdf, l_back.z);
        else
            return detail::make_brdf_sample(l, value.single, value.pdf, l_back.z);
    }

    /// With reflection_sides::both: draws l on v's side for the view v in the given mode,
    /// from the visible normals of v above the surface, of v's mirror image below it
    /// (mirrored back). Returns l with f in the mode (shade::bsdf_f), pdf(l, v, at), the
    /// weight f |n·l| / pdf, flags glossy_reflection and eta 1; nullopt when v is on the
    /// surface or the drawn l is not on v's side.
    [[nodiscard]] std::optional<bsdf_sample<T>> sample(const vec3<T>& v, T /*uc*/, const vec2<T>& u,
                                                       const surface_point<T>& at,
                                                       transport_mode mode = transport_mode::radiance) const noexcept
        requires sampled_microfacet_distribution<Distribution> && two_sided
    {
        const vec3<T> v_local = at.shading.to_local(v);
        if (!(v_local.z > T(0)) && !(v_local.z < T(0))) return std::nullopt; // on the surface, or NaN
        const bool below = v_local.z < T(0);
        const vec3<T> l_drawn = draw_local(below ? mirror(v_local) : v_local, false, u);
        const vec3<T> l = at.shading.to_world(below ? mirror(l_drawn) : l_drawn);
        // f and pdf from l as f() and pdf() take it, so the sample carries exactly their values.
        const T l_z = at.shading.to_local(l).z;
        if (below ? !(l_z < T(0)) : !(l_z > T(0))) return std::nullopt;
        const rgb<T> value = mode == transport_mode::radiance ? f(l, v, at) : f(v, l, at);
        const std::optional<brdf_sample<T>> s = detail::make_brdf_sample(l, value, pdf(l, v, at), below ? -l_z : l_z);
        if (!s) return std::nullopt;
        return bsdf_sample<T>{s->l, s->f, s->pdf, s->weight, bsdf_flags::glossy_reflection, T(1)};
    }

    /// With kulla_conty: the albedo E(mu) of the single-scattering lobe with F = 1 at
    /// the view cosine mu, read from the table at the lobe's roughness (in [0, 1]); for
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

    /// With kulla_conty: the probability q that sample() draws from the cosine (f_ms)
    /// rather than the visible normals, for a view of cosine n_dot_v (class comment).
    [[nodiscard]] T multiple_scattering_probability(T n_dot_v) const noexcept
        requires compensated
    {
        const T e = single_scattering_albedo(n_dot_v);
        const T w_ms = ms_.f_ms_max * (T(1) - e);
        const T w_ss = ms_.f_avg_max * e;
        return w_ms > T(0) ? w_ms / (w_ms + w_ss) : T(0);
    }

    // Building blocks in the local frame (n = +z), for models that contain this lobe
    // (shade::cook_torrance) and weigh or mix it with a lobe choice of their own.

    /// The lobe's parts at a pair of local directions: k times f_ss, k times f_ms (0 with
    /// single_scattering), both in 1/sr, and the lobe's density (1/sr) for the share q of
    /// cosine draws (read with kulla_conty only).
    struct parts {
        rgb<T> single{0};   ///< k f_ss
        rgb<T> multiple{0}; ///< k f_ms
        T pdf{0};           ///< (1 - q) G1(v) D(h) / (4 n·v) + q (n·l)/pi; without kulla_conty G1(v) D(h) / (4 n·v)
    };

    /// The parts (with_f: single and multiple; with_pdf: pdf) for unit local l and v; all 0
    /// unless l.z > 0 and v.z > 0. k (per channel) multiplies the values as k F(v·h) lobe
    /// and k f_ms_scale (1 - E(l))(1 - E(v)); k = 1 gives f exactly. The pdf needs a
    /// shade::sampled_microfacet_distribution.
    template <bool with_f, bool with_pdf>
    [[nodiscard]] parts evaluate_local(const vec3<T>& l, const vec3<T>& v, const rgb<T>& k, T q) const noexcept {
        if (!(l.z > T(0)) || !(v.z > T(0))) return parts{};
        return evaluate_local<with_f, with_pdf>(l, v, detail::half_vector_and_cos(l, v), k, q);
    }

    /// evaluate_local(l, v, k, q) for a caller that has half = detail::half_vector_and_cos(l,
    /// v) already (several lobes evaluated at one pair).
    template <bool with_f, bool with_pdf>
    [[nodiscard]] parts evaluate_local(const vec3<T>& l, const vec3<T>& v, const detail::half_angle<T>& half,
                                       const rgb<T>& k, T q) const noexcept {
        parts out;
        if (!(l.z > T(0)) || !(v.z > T(0))) return out;
        const vec3<T>& h = half.h;
        const T v_dot_h = half.cos_theta_d;
        const T d = D_of(h);
        // Height-correlated Smith masking over a distribution that gives Lambda(v) and
        // G1(v) together (shade::ggx): f's G2 and the density's G1(v) share a square root.
        constexpr bool shared_view_masking =
            with_f && with_pdf && std::same_as<Masking, smith_height_correlated<T>> &&
            requires(const Distribution& distribution, const vec3<T>& w) { distribution.Lambda_and_G1(w); };
        if constexpr (shared_view_masking) {
            const auto masking_v = distribution_.Lambda_and_G1(v);
            // smith_height_correlated::G, the same sum.
            const T g = T(1) / (T(1) + (distribution_.Lambda(l) + masking_v.lambda));
            out.single = specular_of_masking(l, v, g, d, k, v_dot_h);
            if constexpr (compensated) out.multiple = multiple_scattering(l, v, k);
            out.pdf = masking_v.g1 * d / (T(4) * v.z);
            if constexpr (compensated) out.pdf = (T(1) - q) * out.pdf + q * l.z * inv_pi<T>;
            return out;
        }
        if constexpr (with_f) {
            out.single = specular(l, v, h, v_dot_h, d, k, v_dot_h);
            if constexpr (compensated) out.multiple = multiple_scattering(l, v, k);
        }
        if constexpr (with_pdf) {
            // G1(v) D(h) / (4 n·v); v.z > 0 here.
            out.pdf = distribution_.G1(v) * d / (T(4) * v.z);
            if constexpr (compensated) out.pdf = (T(1) - q) * out.pdf + q * l.z * inv_pi<T>;
        }
        return out;
    }

    /// A local direction drawn for the local view v (v.z > 0) from u in [0,1)^2: the
    /// cosine (square_to_cosine_hemisphere) when from_cosine, else the mirror of v about a
    /// visible normal. It may lie below the surface (the caller drops it there).
    [[nodiscard]] vec3<T> draw_local(const vec3<T>& v, bool from_cosine, const vec2<T>& u) const noexcept
        requires sampled_microfacet_distribution<Distribution>
    {
        if (from_cosine) return square_to_cosine_hemisphere(u);
        const vec3<T> m = distribution_.sample_visible_normal(v, u);
        return T(2) * glm::dot(v, m) * m - v;
    }

private:
    // w mirrored in the tangent plane (local frame): (x, y, -z).
    [[nodiscard]] static constexpr vec3<T> mirror(const vec3<T>& w) noexcept { return vec3<T>(w.x, w.y, -w.z); }

    // The parts for local l, v below the surface (reflection_sides::both): those of the
    // mirror images l', v', with F at -(v'·h') (class comment); all 0 unless l.z < 0 and
    // v.z < 0.
    template <bool with_f, bool with_pdf>
    [[nodiscard]] parts evaluate_below(const vec3<T>& l, const vec3<T>& v) const noexcept {
        parts out;
        if (!(l.z < T(0)) || !(v.z < T(0))) return out;
        const vec3<T> l_up = mirror(l);
        const vec3<T> v_up = mirror(v);
        const auto [h, v_dot_h] = detail::half_vector_and_cos(l_up, v_up);
        const T d = D_of(h);
        if constexpr (with_f) out.single = specular(l_up, v_up, h, v_dot_h, d, rgb<T>(1), -v_dot_h);
        if constexpr (with_pdf) out.pdf = distribution_.G1(v_up) * d / (T(4) * v_up.z);
        return out;
    }

    // q(v) with kulla_conty, 0 otherwise.
    [[nodiscard]] T cosine_share(T n_dot_v) const noexcept {
        if constexpr (compensated)
            return multiple_scattering_probability(n_dot_v);
        else
            return T(0);
    }

    // D of the local half vector: D(h) when the distribution has the local form, else
    // D(n·h).
    [[nodiscard]] T D_of(const vec3<T>& h) const noexcept {
        if constexpr (requires { { distribution_.D(h) } -> std::same_as<T>; })
            return distribution_.D(h);
        else
            return distribution_.D(h.z);
    }

    // k F(cos_fresnel) scale D G / ((n·l)(n·v)) for local l, v, h with n·l, n·v > 0;
    // cos_fresnel is v·h from above, -(v·h) for the mirror image of a pair below.
    [[nodiscard]] rgb<T> specular(const vec3<T>& l, const vec3<T>& v, const vec3<T>& h, T v_dot_h, T d,
                                  const rgb<T>& k, T cos_fresnel) const noexcept {
        T g;
        if constexpr (requires { { masking_.G(distribution_, l, v, h, v_dot_h) } -> std::same_as<T>; })
            g = masking_.G(distribution_, l, v, h, v_dot_h);
        else
            g = masking_.G(distribution_, l.z, v.z, h.z, v_dot_h);
        return specular_of_masking(l, v, g, d, k, cos_fresnel);
    }

    // specular() with its masking term g = G(l, v) given.
    [[nodiscard]] rgb<T> specular_of_masking(const vec3<T>& l, const vec3<T>& v, T g, T d, const rgb<T>& k,
                                             T cos_fresnel) const noexcept {
        const T lobe = Form::template scale<T>() * d * g /
                       (detail::floored_cos(l.z) * detail::floored_cos(v.z));
        return k * fresnel_.F(cos_fresnel) * lobe;
    }

    // k f_ms = k F_ms (1 - E(l)) (1 - E(v)) / (pi (1 - E_avg)) for local l, v above the
    // surface (kulla_conty only). Each factor is computed the same way for l and v, so the
    // product is the same number with l and v exchanged.
    [[nodiscard]] rgb<T> multiple_scattering(const vec3<T>& l, const vec3<T>& v, const rgb<T>& k) const noexcept
        requires compensated
    {
        const T loss_l = T(1) - single_scattering_albedo(l);
        const T loss_v = T(1) - single_scattering_albedo(v);
        return k * ms_.scale * (loss_l * loss_v);
    }

    Distribution distribution_;
    Fresnel fresnel_;
    [[no_unique_address]] Masking masking_{};
    [[no_unique_address]] detail::scattering_state<Scattering, T> ms_{};
};

} // namespace shade
