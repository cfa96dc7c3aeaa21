#pragma once
// shade::ashikhmin_shirley: the anisotropic Phong BRDF of Ashikhmin and Shirley, with its
// energy-preserving coupled diffuse term.

#include <algorithm>
#include <cmath>
#include <concepts>

#include <glm/geometric.hpp>

#include <shade/brdf/brdf.hpp>
#include "directions.hpp"
#include "fresnel.hpp"
#include <shade/core/error.hpp>
#include <shade/core/math.hpp>
#include <shade/core/surface_point.hpp>
#include <shade/core/types.hpp>
#include "namespace.hpp"

namespace shade_legacy {

/// The Ashikhmin-Shirley anisotropic Phong BRDF.
///
/// Ashikhmin, Shirley 2000, "An Anisotropic Phong BRDF Model", Journal of Graphics Tools
/// 5(2): 25-32. Specular term (h = normalize(l + v), t and b = at.shading.t and .b):
///
///     f_s = sqrt((p_u + 1)(p_v + 1)) / (8 pi)
///           * (n·h)^((p_u (h·t)^2 + p_v (h·b)^2) / (1 - (n·h)^2))
///           / ((v·h) max(n·l, n·v)) * F(v·h),      F = Schlick with f0 = R_s
///
/// and the coupled diffuse term, which takes away what the specular layer reflects:
///
///     f_d = 28 R_d / (23 pi) (1 - R_s) (1 - (1 - n·l / 2)^5) (1 - (1 - n·v / 2)^5)
///
/// f = f_d + f_s, in 1/sr, 0 unless n·l > 0 and n·v > 0. p_u and p_v are Phong-like
/// exponents along t and b (p_u = p_v is isotropic; larger is shinier); R_s is the
/// specular reflectance at normal incidence and R_d the diffuse reflectance, per channel.
/// The exponent is evaluated with 1 - (n·h)^2 = (h·t)^2 + (h·b)^2 (exact for unit h in an
/// orthonormal frame), so it is a weighted mean of p_u and p_v and stays finite at h = n,
/// where (n·h)^anything = 1. (v·h) and max(n·l, n·v) are floored at machine epsilon in the
/// denominator (detail::cos_floor) so f stays finite at grazing.
///
/// Reciprocal: yes (every factor is symmetric in l and v). Energy conserving: the paper
/// constructs f_d so that f_d + f_s conserves energy for R_s, R_d <= 1; the specular lobe's
/// normalization is approximate (its albedo is close to, not exactly, F), so the claim is
/// "albedo <= 1 up to that approximation", to be checked numerically.
template <std::floating_point T>
class ashikhmin_shirley {
public:
    using scalar_type = T;

    /// Validating constructor. Throws shade::invalid_parameter naming
    ///   "r_d" unless every channel is finite and >= 0,
    ///   "r_s" unless every channel is in [0, 1] (1 - R_s must not be negative),
    ///   "p_u" or "p_v" unless finite and >= 0 (or so large that f would overflow T).
    ashikhmin_shirley(const rgb<T>& r_d, const rgb<T>& r_s, T p_u, T p_v)
        : r_d_(require_non_negative("r_d", r_d)), r_s_(require_in_range("r_s", r_s, T(0), T(1))),
          p_u_(require_non_negative("p_u", p_u)), p_v_(require_non_negative("p_v", p_v)),
          c_s_(specular_normalization(p_u, p_v)) {
        // f_s <= c_s / cos_floor^2 (F <= 1, (n·h)^e <= 1); f_d <= 28 R_d / (23 pi).
        const T floor2 = detail::cos_floor<T> * detail::cos_floor<T>;
        detail::require_finite_peak(p_u_ >= p_v_ ? "p_u" : "p_v", c_s_ / floor2);
        detail::require_finite_peak(
            "r_d", T(28) / (T(23) * pi<T>) * detail::max_channel(r_d_) + c_s_ / floor2);
    }

    /// Unchecked: the caller guarantees the rules of the validating constructor.
    ashikhmin_shirley(unchecked_t, const rgb<T>& r_d, const rgb<T>& r_s, T p_u, T p_v) noexcept
        : r_d_(r_d), r_s_(r_s), p_u_(p_u), p_v_(p_v), c_s_(specular_normalization(p_u, p_v)) {}

    [[nodiscard]] constexpr const rgb<T>& r_d() const noexcept { return r_d_; } ///< diffuse reflectance R_d
    [[nodiscard]] constexpr const rgb<T>& r_s() const noexcept { return r_s_; } ///< specular reflectance R_s
    [[nodiscard]] constexpr T p_u() const noexcept { return p_u_; } ///< exponent along t
    [[nodiscard]] constexpr T p_v() const noexcept { return p_v_; } ///< exponent along b

    /// Coupled diffuse term f_d (1/sr), 0 unless n·l > 0 and n·v > 0.
    [[nodiscard]] rgb<T> f_diffuse(const vec3<T>& l, const vec3<T>& v,
                                   const surface_point<T>& at) const noexcept {
        const T n_dot_l = glm::dot(at.n(), l);
        const T n_dot_v = glm::dot(at.n(), v);
        if (!(n_dot_l > T(0)) || !(n_dot_v > T(0))) return rgb<T>(0);
        const T g = one_minus_pow5(T(1) - T(0.5) * std::min(n_dot_l, T(1))) *
                    one_minus_pow5(T(1) - T(0.5) * std::min(n_dot_v, T(1)));
        return (T(28) / (T(23) * pi<T>) * g) * r_d_ * (rgb<T>(1) - r_s_);
    }

    /// Anisotropic specular term f_s (1/sr), 0 unless n·l > 0 and n·v > 0.
    [[nodiscard]] rgb<T> f_specular(const vec3<T>& l, const vec3<T>& v,
                                    const surface_point<T>& at) const noexcept {
        const frame<T>& fr = at.shading;
        const T n_dot_l = glm::dot(fr.n, l);
        const T n_dot_v = glm::dot(fr.n, v);
        if (!(n_dot_l > T(0)) || !(n_dot_v > T(0))) return rgb<T>(0);
        const auto [h, v_dot_h] = detail::half_vector_and_cos(l, v);
        const T n_dot_h = std::clamp(glm::dot(fr.n, h), T(0), T(1));
        const T h_dot_t = glm::dot(h, fr.t);
        const T h_dot_b = glm::dot(h, fr.b);
        const T t2 = h_dot_t * h_dot_t;
        const T b2 = h_dot_b * h_dot_b;
        const T sin2 = t2 + b2;
        // At h = n (sin2 = 0) the exponent is undefined but (n·h)^e = 1 for any e.
        const T exponent = sin2 > T(0) ? (p_u_ * t2 + p_v_ * b2) / sin2 : p_u_;
        const T lobe = c_s_ * std::pow(n_dot_h, exponent) /
                       (detail::floored_cos(v_dot_h) *
                        detail::floored_cos(std::max(n_dot_l, n_dot_v)));
        return F_schlick(r_s_, v_dot_h) * lobe;
    }

    /// BRDF value in 1/sr without the cosine: f_diffuse + f_specular.
    [[nodiscard]] rgb<T> f(const vec3<T>& l, const vec3<T>& v,
                           const surface_point<T>& at) const noexcept {
        return f_diffuse(l, v, at) + f_specular(l, v, at);
    }

private:
    static T specular_normalization(T p_u, T p_v) noexcept {
        // sqrt(p_u + 1) sqrt(p_v + 1) rather than sqrt of the product, which could overflow.
        return std::sqrt(p_u + T(1)) * std::sqrt(p_v + T(1)) / (T(8) * pi<T>);
    }
    static constexpr T one_minus_pow5(T x) noexcept {
        const T x2 = x * x;
        return T(1) - x2 * x2 * x;
    }

    rgb<T> r_d_;
    rgb<T> r_s_;
    T p_u_;
    T p_v_;
    T c_s_;
};

} // namespace shade_legacy
