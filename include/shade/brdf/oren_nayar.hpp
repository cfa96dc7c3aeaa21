#pragma once
// shade::oren_nayar: the qualitative Oren-Nayar model of rough diffuse surfaces, with two
// evaluations of the same function chosen by a type (for comparison and benchmarks) and
// two forms of its coefficient A:
//
//   oren_nayar<T>        = oren_nayar<T, oren_nayar_evaluation::trig_free>   dot products only
//   oren_nayar_trig<T>   = oren_nayar<T, oren_nayar_evaluation::trig>        the paper's sin(alpha) tan(beta) cos(phi)
//   oren_nayar<T, E, oren_nayar_form::qualitative>   A = 1 - 0.5 sigma^2/(sigma^2 + 0.33)  (default, eq. 30)
//   oren_nayar<T, E, oren_nayar_form::course>        A = 1 - 0.5 sigma^2/(sigma^2 + 0.57)
//
// Sampling (shade::sampled_brdf): the cosine density n·l / pi.

#include <cmath>
#include <concepts>
#include <optional>
#include <type_traits>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <shade/brdf/brdf.hpp>
#include <shade/brdf/detail/directions.hpp>
#include <shade/brdf/detail/sampling.hpp>
#include <shade/core/error.hpp>
#include <shade/core/math.hpp>
#include <shade/core/surface_point.hpp>
#include <shade/core/types.hpp>

namespace shade {

/// How shade::oren_nayar evaluates sin(alpha) tan(beta) max(0, cos(phi_v - phi_l)).
namespace oren_nayar_evaluation {

/// Without trigonometry. With theta the angles to n and phi the azimuths,
///   cos(phi_v - phi_l) sin(theta_l) sin(theta_v) = l·v - (n·l)(n·v)
/// (expand l·v in spherical coordinates), and since {alpha, beta} = {theta_l, theta_v},
///   sin(alpha) sin(beta) = sin(theta_l) sin(theta_v),   cos(beta) = max(n·l, n·v),
/// so  max(0, cos(phi_v - phi_l)) sin(alpha) tan(beta) = max(0, l·v - (n·l)(n·v)) / max(n·l, n·v).
/// At normal incidence (l = n or v = n) the numerator is exactly 0.
struct trig_free {};

/// In the paper's variables, each factor on its own: cos(phi_v - phi_l) from the
/// NORMALIZED projections of l and v onto the tangent plane (0 when either projection is
/// zero, i.e. at normal incidence, where tan(beta) = 0 anyway), and sin(alpha), tan(beta)
/// from the cosines themselves, without forming the angles: alpha = max(theta_l, theta_v)
/// has cos(alpha) = min(n·l, n·v), beta has cos(beta) = max(n·l, n·v), sin = sqrt((1 - c)(1 + c))
/// and tan(beta) = sin(beta) / cos(beta) with cos(beta) floored at machine epsilon (as in the
/// trig-free form). Going through theta = acos(n·w) and back would lose the small cosines
/// of grazing directions to the rounding of theta near pi/2. Slower than trig_free
/// (two square roots and a normalisation more); kept to check and benchmark it.
struct trig {};

} // namespace oren_nayar_evaluation

/// The forms of the coefficient A = 1 - 0.5 sigma^2 / (sigma^2 + a) of shade::oren_nayar,
/// used as its Form parameter. Each is a stateless type whose `a_constant<T>()` returns a.
/// B = 0.45 sigma^2 / (sigma^2 + 0.09) is the same in both.
namespace oren_nayar_form {

/// a = 0.33 (default): Oren, Nayar 1994, "Generalization of Lambert's Reflectance Model",
/// SIGGRAPH '94, eq. 30, the qualitative model, which leaves out interreflections between
/// the facets.
struct qualitative {
    template <std::floating_point T>
    [[nodiscard]] static constexpr T a_constant() noexcept {
        return T(0.33);
    }
};

/// a = 0.57: the A of the course slides this project follows and of several secondary
/// sources, where replacing 0.33 by 0.57 is described as a rough allowance for
/// interreflections (that attribution to the paper was not checked against its text).
/// A is larger than the default's for every sigma > 0 (sigma^2 / (sigma^2 + a) decreases in
/// a), so this form reflects more: up to 1 - 0.5 sigma^2 / (sigma^2 + 0.57) instead of
/// 1 - 0.5 sigma^2 / (sigma^2 + 0.33) times rho at normal incidence.
/// It is not energy conserving: with rho = 1 its albedo exceeds 1 at grazing views (the
/// property sweep, tests/sweep, shows it failing the energy check at sigma = 0.3), where
/// the default form stays below 1.
struct course {
    template <std::floating_point T>
    [[nodiscard]] static constexpr T a_constant() noexcept {
        return T(0.57);
    }
};

} // namespace oren_nayar_form

/// X is one of the shade::oren_nayar_form types (or a user type with the same member).
template <class X, class T>
concept oren_nayar_coefficient_form = std::floating_point<T> && requires {
    { X::template a_constant<T>() } -> std::same_as<T>;
};

/// The qualitative Oren-Nayar model.
///
/// Oren, Nayar 1994, "Generalization of Lambert's Reflectance Model", SIGGRAPH '94,
/// eq. 30 (the "qualitative model"), written as a BRDF (their radiance divided by
/// E_0 cos(theta_i)):
///
///     f = (rho / pi) (A + B max(0, cos(phi_v - phi_l)) sin(alpha) tan(beta))
///     A = 1 - 0.5 sigma^2 / (sigma^2 + a),   B = 0.45 sigma^2 / (sigma^2 + 0.09)
///     alpha = max(theta_l, theta_v),   beta = min(theta_l, theta_v)
///
/// rho is the albedo of the Lambertian facets (per channel), sigma the standard deviation
/// of the facet slope angle in RADIANS (sigma = 0 gives Lambert, f = rho / pi), and
/// a = Form::a_constant(): eq. 30's 0.33 by default, 0.57 with oren_nayar_form::course.
/// Returns 0 unless n·l > 0 and
/// n·v > 0. The division by max(n·l, n·v) (= cos(beta)) is floored at machine epsilon so
/// both-grazing pairs stay finite (detail::cos_floor).
///
/// Reciprocal: yes (symmetric in l and v). Energy conserving: NOT guaranteed. The model
/// drops interreflections, and its retro-reflective term grows like 1/cos(beta) when both
/// directions approach grazing with similar azimuths, so the albedo for grazing views can
/// exceed rho (and 1 for rho close to 1); it is <= rho near normal incidence.
///
/// Sampling (shade::sampled_brdf): the cosine density n·l / pi (uc is not used), which
/// covers every direction where f > 0.
template <std::floating_point T, class Evaluation = oren_nayar_evaluation::trig_free,
          class Form = oren_nayar_form::qualitative>
    requires(std::same_as<Evaluation, oren_nayar_evaluation::trig_free> ||
             std::same_as<Evaluation, oren_nayar_evaluation::trig>) &&
            oren_nayar_coefficient_form<Form, T>
class oren_nayar {
public:
    using scalar_type = T;
    using evaluation_type = Evaluation;
    using form_type = Form;

    /// Throws shade::invalid_parameter naming "rho" unless every channel is finite and
    /// >= 0, or "sigma" unless sigma is finite and >= 0 (radians).
    oren_nayar(const rgb<T>& rho, T sigma)
        : rho_(require_non_negative("rho", rho)), sigma_(require_non_negative("sigma", sigma)),
          a_(coefficient_a(sigma)), b_(coefficient_b(sigma)) {
        // f <= rho/pi (A + B / cos_floor) (the trig-free bound; the trig path is the same).
        detail::require_finite_peak(
            "rho", detail::max_channel(rho_) * inv_pi<T> * (a_ + b_ / detail::cos_floor<T>));
    }

    /// Unchecked: the caller guarantees rho >= 0 per channel and sigma >= 0, all finite.
    oren_nayar(unchecked_t, const rgb<T>& rho, T sigma) noexcept
        : rho_(rho), sigma_(sigma), a_(coefficient_a(sigma)), b_(coefficient_b(sigma)) {}

    [[nodiscard]] constexpr const rgb<T>& rho() const noexcept { return rho_; } ///< facet albedo
    [[nodiscard]] constexpr T sigma() const noexcept { return sigma_; } ///< slope-angle deviation, radians
    [[nodiscard]] constexpr T a() const noexcept { return a_; } ///< A = 1 - 0.5 sigma^2/(sigma^2 + a)
    [[nodiscard]] constexpr T b() const noexcept { return b_; } ///< B = 0.45 sigma^2/(sigma^2 + 0.09)

    /// BRDF value in 1/sr without the cosine (see the class comment); 0 unless n·l > 0 and
    /// n·v > 0.
    [[nodiscard]] rgb<T> f(const vec3<T>& l, const vec3<T>& v,
                           const surface_point<T>& at) const noexcept {
        detail::assert_unit_directions(l, v, at);
        const vec3<T>& n = at.n();
        const T n_dot_l = glm::dot(n, l);
        const T n_dot_v = glm::dot(n, v);
        if (!(n_dot_l > T(0)) || !(n_dot_v > T(0))) return rgb<T>(0);
        T angular;
        if constexpr (std::is_same_v<Evaluation, oren_nayar_evaluation::trig_free>) {
            const T s = glm::dot(l, v) - n_dot_l * n_dot_v;
            angular = s > T(0) ? s / detail::floored_cos(glm::max(n_dot_l, n_dot_v)) : T(0);
        } else {
            const T cos_alpha = glm::min(glm::min(n_dot_l, n_dot_v), T(1));
            const T cos_beta = glm::min(glm::max(n_dot_l, n_dot_v), T(1));
            const T sin_alpha = safe_sqrt((T(1) - cos_alpha) * (T(1) + cos_alpha));
            const T sin_beta = safe_sqrt((T(1) - cos_beta) * (T(1) + cos_beta));
            const vec3<T> l_t = l - n_dot_l * n;
            const vec3<T> v_t = v - n_dot_v * n;
            const T len_l = glm::length(l_t);
            const T len_v = glm::length(v_t);
            T cos_phi = T(0);
            if (len_l > T(0) && len_v > T(0))
                cos_phi = glm::clamp(glm::dot(l_t / len_l, v_t / len_v), T(-1), T(1));
            const T tan_beta = sin_beta / detail::floored_cos(cos_beta);
            angular = glm::max(cos_phi, T(0)) * sin_alpha * tan_beta;
        }
        return rho_ * (inv_pi<T> * (a_ + b_ * angular));
    }

    /// The density (1/sr) with which sample() draws l: n·l / pi, 0 unless n·l > 0 and n·v > 0.
    [[nodiscard]] T pdf(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const noexcept {
        return detail::cosine_brdf_pdf(l, v, at);
    }

    /// Draws l with the cosine density from u (uc is not used); nullopt when v is not above
    /// the surface or l falls on the horizon.
    [[nodiscard]] std::optional<brdf_sample<T>> sample(const vec3<T>& v, T /*uc*/, const vec2<T>& u,
                                                       const surface_point<T>& at) const noexcept {
        return detail::sample_cosine_brdf(v, u, at, [&](const vec3<T>& w) { return f(w, v, at); });
    }

private:
    // sigma is capped at 1e4 rad before squaring: beyond it A and B equal their limits
    // 0.5 and 0.45 to better than 1e-8, and sigma^2 can no longer overflow to Inf/Inf.
    static constexpr T coefficient_a(T sigma) noexcept {
        const T s2 = sqr(glm::min(sigma, T(1e4)));
        return T(1) - T(0.5) * s2 / (s2 + Form::template a_constant<T>());
    }
    static constexpr T coefficient_b(T sigma) noexcept {
        const T s2 = sqr(glm::min(sigma, T(1e4)));
        return T(0.45) * s2 / (s2 + T(0.09));
    }

    rgb<T> rho_;
    T sigma_;
    T a_;
    T b_;
};

/// The qualitative Oren-Nayar model evaluated with the paper's separate factors
/// (oren_nayar_evaluation::trig).
template <std::floating_point T>
using oren_nayar_trig = oren_nayar<T, oren_nayar_evaluation::trig>;

} // namespace shade
