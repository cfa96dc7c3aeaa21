#pragma once
// shade::cook_torrance: the microfacet specular BRDF F D G / (c (n·l)(n·v)) over a
// Lambertian base, composed at compile time from a distribution D, a Fresnel term F, a
// masking term G (shade/brdf/microfacet.hpp, shade/brdf/fresnel.hpp) and a normalization
// form:
//
//   cook_torrance<beckmann<T>, schlick<T>, v_groove<T>>                  default: Walter et al.
//   cook_torrance<ggx<T>, dielectric_fresnel<T>, smith_ggx<T>, cook_torrance_form::course>
//
// Example:
//   const shade::cook_torrance<shade::ggx<float>, shade::schlick<float>, shade::smith_ggx<float>>
//       metal(shade::ggx<float>(0.3f), shade::schlick<float>({0.95f, 0.64f, 0.54f}));

#include <concepts>

#include <glm/geometric.hpp>

#include <shade/brdf/brdf.hpp>
#include "directions.hpp"
#include "fresnel.hpp"
#include "microfacet.hpp"
#include <shade/core/error.hpp>
#include <shade/core/math.hpp>
#include <shade/core/surface_point.hpp>
#include <shade/core/types.hpp>
#include "namespace.hpp"

namespace shade_legacy {

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

/// Cook-Torrance reflection: a Lambertian base plus a microfacet specular lobe.
///
///     f = k_d / pi + k_s * scale * F(v·h) D(n·h) G(l, v, h) / ((n·l)(n·v))
///
/// Cook, Torrance 1982, "A Reflectance Model for Computer Graphics", ACM ToG 1(1): the
/// paper mixes a diffuse and a specular bidirectional reflectance as R = d R_d + s R_s with
/// s + d = 1; here the two weights are the per-channel colours k_d (Lambert albedo, f_d =
/// k_d / pi) and k_s (multiplies the specular term), which reproduce the paper's mixing
/// with k_d = d * (diffuse reflectance) and k_s = s. Neither is coupled to F, so
/// energy conservation needs k_d + k_s * (specular albedo) <= 1 (e.g. k_d + k_s <= 1 with
/// the walter form and a Smith G); the form constants are in shade::cook_torrance_form.
///
/// h = normalize(l + v). Returns 0 unless n·l > 0 and n·v > 0. n·l and n·v are floored at
/// machine epsilon in the denominator (detail::cos_floor) so f stays finite at grazing.
/// Reciprocal: yes. Satisfies shade::split_brdf (f_diffuse = k_d / pi, f_specular = lobe).
///
/// Distribution: beckmann<T> or ggx<T> (or any shade::microfacet_distribution).
/// Fresnel: schlick<T> or dielectric_fresnel<T> (or any shade::fresnel_term).
/// Masking: v_groove<T>, smith_beckmann<T> (with beckmann), smith_ggx<T> (with ggx);
///          default-constructed (the masking terms are stateless).
template <class Distribution, class Fresnel, class Masking,
          class Form = cook_torrance_form::walter>
    requires microfacet_distribution<Distribution> &&
             fresnel_term<Fresnel, scalar_of<Distribution>> &&
             masking_for<Masking, Distribution> && std::default_initializable<Masking> &&
             cook_torrance_normalization<Form, scalar_of<Distribution>>
class cook_torrance {
public:
    using scalar_type = scalar_of<Distribution>;
    using distribution_type = Distribution;
    using fresnel_type = Fresnel;
    using masking_type = Masking;
    using form_type = Form;

private:
    using T = scalar_type;

public:
    /// Validating constructor (the distribution and Fresnel term validated their own
    /// parameters when they were built). Throws shade::invalid_parameter naming "k_s" or
    /// "k_d" unless every channel is finite and >= 0, or if the peak value of f would
    /// overflow T.
    cook_torrance(const Distribution& distribution, const Fresnel& fresnel,
                  const rgb<T>& k_s = rgb<T>(1), const rgb<T>& k_d = rgb<T>(0))
        : distribution_(distribution), fresnel_(fresnel),
          k_s_(require_non_negative("k_s", k_s)), k_d_(require_non_negative("k_d", k_d)) {
        // D <= peak, F <= 1, G <= 1, 1/((n·l)(n·v)) <= 1/cos_floor^2.
        const T floor2 = detail::cos_floor<T> * detail::cos_floor<T>;
        const T peak = detail::max_channel(k_s_) * Form::template scale<T>() *
                       (distribution_.peak() / floor2);
        detail::require_finite_peak("k_s", peak);
        detail::require_finite_peak("k_d", detail::max_channel(k_d_) * inv_pi<T> + peak);
    }

    /// Unchecked: the caller guarantees k_s, k_d finite and >= 0 (and not so large that f
    /// overflows).
    cook_torrance(unchecked_t, const Distribution& distribution, const Fresnel& fresnel,
                  const rgb<T>& k_s = rgb<T>(1), const rgb<T>& k_d = rgb<T>(0)) noexcept
        : distribution_(distribution), fresnel_(fresnel), k_s_(k_s), k_d_(k_d) {}

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

    /// Specular part k_s scale F D G / ((n·l)(n·v)) (1/sr), 0 unless n·l > 0 and n·v > 0.
    [[nodiscard]] rgb<T> f_specular(const vec3<T>& l, const vec3<T>& v,
                                    const surface_point<T>& at) const noexcept {
        const vec3<T>& n = at.n();
        const T n_dot_l = glm::dot(n, l);
        const T n_dot_v = glm::dot(n, v);
        if (!(n_dot_l > T(0)) || !(n_dot_v > T(0))) return rgb<T>(0);
        const auto [h, v_dot_h] = detail::half_vector_and_cos(l, v);
        const T n_dot_h = glm::dot(n, h);
        const T d = distribution_.D(n_dot_h);
        const T g = masking_.G(distribution_, n_dot_l, n_dot_v, n_dot_h, v_dot_h);
        const T lobe = Form::template scale<T>() * d * g /
                       (detail::floored_cos(n_dot_l) * detail::floored_cos(n_dot_v));
        return k_s_ * fresnel_.F(v_dot_h) * lobe;
    }

    /// BRDF value in 1/sr without the cosine: f_diffuse + f_specular.
    [[nodiscard]] rgb<T> f(const vec3<T>& l, const vec3<T>& v,
                           const surface_point<T>& at) const noexcept {
        return f_diffuse(l, v, at) + f_specular(l, v, at);
    }

private:
    Distribution distribution_;
    Fresnel fresnel_;
    [[no_unique_address]] Masking masking_{};
    rgb<T> k_s_;
    rgb<T> k_d_;
};

} // namespace shade_legacy
