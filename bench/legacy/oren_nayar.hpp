#pragma once
// shade::oren_nayar: the qualitative Oren-Nayar model of rough diffuse surfaces, with two
// evaluations of the same function chosen by a type (for comparison and benchmarks):
//
//   oren_nayar<T>        = oren_nayar<T, oren_nayar_evaluation::trig_free>   dot products only
//   oren_nayar_trig<T>   = oren_nayar<T, oren_nayar_evaluation::trig>        acos, sin, tan as in the paper

#include <algorithm>
#include <cmath>
#include <concepts>
#include <type_traits>

#include <glm/geometric.hpp>

#include <shade/brdf/brdf.hpp>
#include "directions.hpp"
#include <shade/core/error.hpp>
#include <shade/core/math.hpp>
#include <shade/core/surface_point.hpp>
#include <shade/core/types.hpp>
#include "namespace.hpp"

namespace shade_legacy {

/// How shade::oren_nayar evaluates sin(alpha) tan(beta) max(0, cos(phi_v - phi_l)).
namespace oren_nayar_evaluation {

/// Without trigonometry. With theta the angles to n and phi the azimuths,
///   cos(phi_v - phi_l) sin(theta_l) sin(theta_v) = l·v - (n·l)(n·v)
/// (expand l·v in spherical coordinates), and since {alpha, beta} = {theta_l, theta_v},
///   sin(alpha) sin(beta) = sin(theta_l) sin(theta_v),   cos(beta) = max(n·l, n·v),
/// so  max(0, cos(phi_v - phi_l)) sin(alpha) tan(beta) = max(0, l·v - (n·l)(n·v)) / max(n·l, n·v).
/// At normal incidence (l = n or v = n) the numerator is exactly 0.
struct trig_free {};

/// As the paper writes it: theta = acos(n·w), alpha = max, beta = min, cos(phi_v - phi_l)
/// from the NORMALIZED projections of l and v onto the tangent plane (0 when either
/// projection is zero, i.e. at normal incidence, where tan(beta) = 0 anyway), then
/// std::sin(alpha) * std::tan(beta). tan(beta) is evaluated as sin(beta) / cos(beta) with
/// cos(beta) floored at machine epsilon, because acos of a tiny n·w can round to just
/// above pi/2, where tan would be huge and negative. Slower, and less accurate near the
/// normal (acos is ill-conditioned there); kept to check and benchmark the trig-free form.
struct trig {};

} // namespace oren_nayar_evaluation

/// The qualitative Oren-Nayar model.
///
/// Oren, Nayar 1994, "Generalization of Lambert's Reflectance Model", SIGGRAPH '94,
/// eq. 30 (the "qualitative model"), written as a BRDF (their radiance divided by
/// E_0 cos(theta_i)):
///
///     f = (rho / pi) (A + B max(0, cos(phi_v - phi_l)) sin(alpha) tan(beta))
///     A = 1 - 0.5 sigma^2 / (sigma^2 + 0.33),   B = 0.45 sigma^2 / (sigma^2 + 0.09)
///     alpha = max(theta_l, theta_v),   beta = min(theta_l, theta_v)
///
/// rho is the albedo of the Lambertian facets (per channel), sigma the standard deviation
/// of the facet slope angle in RADIANS (sigma = 0 gives Lambert, f = rho / pi). The 0.33
/// is eq. 30's constant; 0.57, seen in some implementations, is a variant that folds in
/// an approximation of interreflections and is not used here. Returns 0 unless n·l > 0 and
/// n·v > 0. The division by max(n·l, n·v) (= cos(beta)) is floored at machine epsilon so
/// both-grazing pairs stay finite (detail::cos_floor).
///
/// Reciprocal: yes (symmetric in l and v). Energy conserving: NOT guaranteed. The model
/// drops interreflections, and its retro-reflective term grows like 1/cos(beta) when both
/// directions approach grazing with similar azimuths, so the albedo for grazing views can
/// exceed rho (and 1 for rho close to 1); it is <= rho near normal incidence.
template <std::floating_point T, class Evaluation = oren_nayar_evaluation::trig_free>
    requires std::same_as<Evaluation, oren_nayar_evaluation::trig_free> ||
             std::same_as<Evaluation, oren_nayar_evaluation::trig>
class oren_nayar {
public:
    using scalar_type = T;
    using evaluation_type = Evaluation;

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
    [[nodiscard]] constexpr T a() const noexcept { return a_; } ///< A = 1 - 0.5 sigma^2/(sigma^2 + 0.33)
    [[nodiscard]] constexpr T b() const noexcept { return b_; } ///< B = 0.45 sigma^2/(sigma^2 + 0.09)

    /// BRDF value in 1/sr without the cosine (see the class comment); 0 unless n·l > 0 and
    /// n·v > 0.
    [[nodiscard]] rgb<T> f(const vec3<T>& l, const vec3<T>& v,
                           const surface_point<T>& at) const noexcept {
        const vec3<T>& n = at.n();
        const T n_dot_l = glm::dot(n, l);
        const T n_dot_v = glm::dot(n, v);
        if (!(n_dot_l > T(0)) || !(n_dot_v > T(0))) return rgb<T>(0);
        T angular;
        if constexpr (std::is_same_v<Evaluation, oren_nayar_evaluation::trig_free>) {
            const T s = glm::dot(l, v) - n_dot_l * n_dot_v;
            angular = s > T(0) ? s / detail::floored_cos(std::max(n_dot_l, n_dot_v)) : T(0);
        } else {
            const T theta_l = std::acos(std::min(n_dot_l, T(1)));
            const T theta_v = std::acos(std::min(n_dot_v, T(1)));
            const T alpha = std::max(theta_l, theta_v);
            const T beta = std::min(theta_l, theta_v);
            const vec3<T> l_t = l - n_dot_l * n;
            const vec3<T> v_t = v - n_dot_v * n;
            const T len_l = glm::length(l_t);
            const T len_v = glm::length(v_t);
            T cos_phi = T(0);
            if (len_l > T(0) && len_v > T(0))
                cos_phi = std::clamp(glm::dot(l_t / len_l, v_t / len_v), T(-1), T(1));
            const T tan_beta = std::sin(beta) / detail::floored_cos(std::cos(beta));
            angular = std::max(cos_phi, T(0)) * std::sin(alpha) * tan_beta;
        }
        return rho_ * (inv_pi<T> * (a_ + b_ * angular));
    }

private:
    // sigma is capped at 1e4 rad before squaring: beyond it A and B equal their limits
    // 0.5 and 0.45 to better than 1e-8, and sigma^2 can no longer overflow to Inf/Inf.
    static constexpr T coefficient_a(T sigma) noexcept {
        const T s2 = sqr(std::min(sigma, T(1e4)));
        return T(1) - T(0.5) * s2 / (s2 + T(0.33));
    }
    static constexpr T coefficient_b(T sigma) noexcept {
        const T s2 = sqr(std::min(sigma, T(1e4)));
        return T(0.45) * s2 / (s2 + T(0.09));
    }

    rgb<T> rho_;
    T sigma_;
    T a_;
    T b_;
};

/// The qualitative Oren-Nayar model evaluated with acos/sin/tan as in the paper.
template <std::floating_point T>
using oren_nayar_trig = oren_nayar<T, oren_nayar_evaluation::trig>;

} // namespace shade_legacy
