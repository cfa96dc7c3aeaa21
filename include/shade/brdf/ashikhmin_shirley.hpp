#pragma once
// shade::ashikhmin_shirley: the anisotropic Phong BRDF of Ashikhmin and Shirley, with its
// energy-preserving coupled diffuse term.

#include <cmath>
#include <concepts>
#include <optional>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <shade/brdf/brdf.hpp>
#include <shade/brdf/detail/directions.hpp>
#include <shade/brdf/detail/sampling.hpp>
#include <shade/brdf/fresnel.hpp>
#include <shade/core/error.hpp>
#include <shade/core/frame.hpp>
#include <shade/core/math.hpp>
#include <shade/core/sampling.hpp>
#include <shade/core/surface_point.hpp>
#include <shade/core/types.hpp>

namespace shade {

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
/// where (n·h)^anything = 1; the power is exp(exponent log(n·h)) with log(n·h) taken from
/// the same sin^2 near the peak (log_cos_theta_h), where n·h rounds close to 1. (v·h) and max(n·l, n·v) are floored at machine epsilon in the
/// denominator (detail::cos_floor) so f stays finite at grazing.
///
/// Reciprocal: yes (every factor is symmetric in l and v). Energy conserving: the paper
/// constructs f_d so that f_d + f_s conserves energy for R_s, R_d <= 1; the specular lobe's
/// normalization is approximate (its albedo is close to, not exactly, F), so the claim is
/// "albedo <= 1 up to that approximation", to be checked numerically.
///
/// The diffuse term's factors 1 - (1 - x/2)^5 are evaluated as (x/2)(1 + y + y^2 + y^3 + y^4)
/// with y = 1 - x/2 (the same polynomial, factored), which has no cancellation for the
/// small x of grazing directions.
///
/// Sampling (shade::sampled_brdf), the paper's sec. 4: the specular lobe draws h with
///
///     phi = atan(sqrt((p_u + 1)/(p_v + 1)) tan(pi u_1 / 2))       (u_1 stretched over each quadrant)
///     cos(theta_h) = u_2^(1 / (p_u cos^2(phi) + p_v sin^2(phi) + 1))
///
/// whose density is p_h(h) = sqrt((p_u + 1)(p_v + 1)) / (2 pi) (n·h)^(p_u cos^2 phi + p_v sin^2 phi),
/// and returns l = 2 (v·h) h - v, whose density is p_h / (4 v·h). The diffuse term draws the
/// cosine density n·l / pi. uc < P_s chooses the specular lobe, with
///
///     P_s = a_s / (a_d + a_s),   a_s = mean(R_s),   a_d = mean(R_d (1 - R_s))
///
/// (the specular albedo at normal incidence is about R_s, the diffuse about R_d (1 - R_s);
/// P_s = 1/2 when both are 0), and pdf() is the mixture (1 - P_s) n·l / pi + P_s p_h / (4 v·h),
/// with v·h floored at detail::cos_floor as in f. Lobe directions below the surface are
/// not returned (nullopt), so pdf integrates to at most 1 over the hemisphere.
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
          c_s_(specular_normalization(p_u, p_v)), p_lobe_(lobe_probability(r_d_, r_s_)),
          phi_scale_(std::sqrt((p_u + T(1)) / (p_v + T(1)))) {
        // f_s <= c_s / cos_floor^2 (F <= 1, (n·h)^e <= 1); f_d <= 28 R_d / (23 pi).
        const T floor2 = detail::cos_floor<T> * detail::cos_floor<T>;
        detail::require_finite_peak(p_u_ >= p_v_ ? "p_u" : "p_v", c_s_ / floor2);
        detail::require_finite_peak(
            "r_d", T(28) / (T(23) * pi<T>) * detail::max_channel(r_d_) + c_s_ / floor2);
    }

    /// Unchecked: the caller guarantees the rules of the validating constructor.
    ashikhmin_shirley(unchecked_t, const rgb<T>& r_d, const rgb<T>& r_s, T p_u, T p_v) noexcept
        : r_d_(r_d), r_s_(r_s), p_u_(p_u), p_v_(p_v), c_s_(specular_normalization(p_u, p_v)),
          p_lobe_(lobe_probability(r_d, r_s)), phi_scale_(std::sqrt((p_u + T(1)) / (p_v + T(1)))) {}

    [[nodiscard]] constexpr const rgb<T>& r_d() const noexcept { return r_d_; } ///< diffuse reflectance R_d
    [[nodiscard]] constexpr const rgb<T>& r_s() const noexcept { return r_s_; } ///< specular reflectance R_s
    [[nodiscard]] constexpr T p_u() const noexcept { return p_u_; } ///< exponent along t
    [[nodiscard]] constexpr T p_v() const noexcept { return p_v_; } ///< exponent along b
    /// P_s: the probability with which sample() draws the specular lobe (see the class comment).
    [[nodiscard]] constexpr T lobe_probability() const noexcept { return p_lobe_; }

    /// Coupled diffuse term f_d (1/sr), 0 unless n·l > 0 and n·v > 0.
    [[nodiscard]] rgb<T> f_diffuse(const vec3<T>& l, const vec3<T>& v,
                                   const surface_point<T>& at) const noexcept {
        detail::assert_unit_directions(l, v, at);
        const T n_dot_l = glm::dot(at.n(), l);
        const T n_dot_v = glm::dot(at.n(), v);
        if (!(n_dot_l > T(0)) || !(n_dot_v > T(0))) return rgb<T>(0);
        return diffuse(n_dot_l, n_dot_v);
    }

    /// Anisotropic specular term f_s (1/sr), 0 unless n·l > 0 and n·v > 0.
    [[nodiscard]] rgb<T> f_specular(const vec3<T>& l, const vec3<T>& v,
                                    const surface_point<T>& at) const noexcept {
        detail::assert_unit_directions(l, v, at);
        const T n_dot_l = glm::dot(at.n(), l);
        const T n_dot_v = glm::dot(at.n(), v);
        if (!(n_dot_l > T(0)) || !(n_dot_v > T(0))) return rgb<T>(0);
        const half_lobe s = specular_lobe(l, v, at.shading);
        return specular(s, n_dot_l, n_dot_v);
    }

    /// BRDF value in 1/sr without the cosine: f_diffuse + f_specular.
    [[nodiscard]] rgb<T> f(const vec3<T>& l, const vec3<T>& v,
                           const surface_point<T>& at) const noexcept {
        return f_diffuse(l, v, at) + f_specular(l, v, at);
    }

    /// The density (1/sr) with which sample() draws l: the mixture in the class comment,
    /// 0 unless n·l > 0 and n·v > 0.
    [[nodiscard]] T pdf(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const noexcept {
        const T n_dot_l = glm::dot(at.n(), l);
        if (!(n_dot_l > T(0)) || !(glm::dot(at.n(), v) > T(0))) return T(0);
        return mixture_pdf(n_dot_l, specular_lobe(l, v, at.shading));
    }

    /// Draws l for v (class comment): the specular lobe when uc < lobe_probability(), else
    /// the cosine lobe, u placing the direction within it. nullopt when v or the drawn l is
    /// not above the surface. The returned f and pdf are f(l, v, at) and pdf(l, v, at).
    [[nodiscard]] std::optional<brdf_sample<T>> sample(const vec3<T>& v, T uc, const vec2<T>& u,
                                                       const surface_point<T>& at) const noexcept {
        const T n_dot_v = glm::dot(at.n(), v);
        if (!(n_dot_v > T(0))) return std::nullopt;
        const vec3<T> l = uc < p_lobe_ ? detail::reflect_about(v, sample_h(u, at.shading))
                                       : detail::sample_cosine_lobe(u, at);
        const T n_dot_l = glm::dot(at.n(), l);
        if (!(n_dot_l > T(0))) return std::nullopt;
        const half_lobe s = specular_lobe(l, v, at.shading);
        return detail::make_brdf_sample(l, diffuse(n_dot_l, n_dot_v) + specular(s, n_dot_l, n_dot_v),
                                        mixture_pdf(n_dot_l, s), n_dot_l);
    }

private:
    /// The parts of the specular term that depend on h: v·h (= l·h) and
    /// power = c_s (n·h)^e, which is p_h / 4.
    struct half_lobe {
        T v_dot_h;
        T power;
    };

    [[nodiscard]] half_lobe specular_lobe(const vec3<T>& l, const vec3<T>& v,
                                          const frame<T>& fr) const noexcept {
        const auto [h, v_dot_h] = detail::half_vector_and_cos(l, v);
        const T n_dot_h = glm::clamp(glm::dot(fr.n, h), T(0), T(1));
        const T h_dot_t = glm::dot(h, fr.t);
        const T h_dot_b = glm::dot(h, fr.b);
        const T t2 = h_dot_t * h_dot_t;
        const T b2 = h_dot_b * h_dot_b;
        const T sin2 = t2 + b2;
        // At h = n (sin2 = 0) the exponent is undefined but (n·h)^e = 1 for any e; so is
        // x^0 (p_u = p_v = 0), also at n·h = 0.
        const T exponent = sin2 > T(0) ? (p_u_ * t2 + p_v_ * b2) / sin2 : p_u_;
        if (!(sin2 > T(0)) || !(exponent > T(0))) return {v_dot_h, c_s_};
        return {v_dot_h, c_s_ * std::exp(exponent * log_cos_theta_h(sin2, n_dot_h))};
    }

    /// log(n·h) from sin^2(theta_h) = (h·t)^2 + (h·b)^2 and n·h. Near the peak n·h rounds
    /// close to 1, where its rounding (up to 2^-24 in float) is multiplied by the exponent
    /// in (n·h)^e (1.4e-4 at e = 1000); sin^2 taken from the tangent components keeps its
    /// relative precision there, and log(n·h) = log1p(-sin^2)/2 keeps it too (Goldberg 1991,
    /// "What Every Computer Scientist Should Know About Floating-Point Arithmetic", ACM
    /// Computing Surveys 23(1): 5-48, Theorem 4, ln(1 + x) for small x). Beyond 45 degrees
    /// (sin^2 >= 1/2) n·h itself is accurate and 1 - sin^2 would cancel instead.
    [[nodiscard]] static T log_cos_theta_h(T sin2, T n_dot_h) noexcept {
        return sin2 < T(0.5) ? T(0.5) * std::log1p(-sin2) : std::log(n_dot_h);
    }

    /// f_s from the h-dependent parts: F(v·h) power / ((v·h) max(n·l, n·v)).
    [[nodiscard]] rgb<T> specular(const half_lobe& s, T n_dot_l, T n_dot_v) const noexcept {
        return F_schlick(r_s_, s.v_dot_h) *
               (s.power / (detail::floored_cos(s.v_dot_h) *
                           detail::floored_cos(glm::max(n_dot_l, n_dot_v))));
    }

    /// f_d for n·l, n·v > 0.
    [[nodiscard]] rgb<T> diffuse(T n_dot_l, T n_dot_v) const noexcept {
        const T g = one_minus_pow5_of_one_minus_half(glm::min(n_dot_l, T(1))) *
                    one_minus_pow5_of_one_minus_half(glm::min(n_dot_v, T(1)));
        return (T(28) / (T(23) * pi<T>) * g) * r_d_ * (rgb<T>(1) - r_s_);
    }

    /// (1 - P_s) n·l / pi + P_s p_h / (4 v·h), p_h / 4 = power.
    [[nodiscard]] T mixture_pdf(T n_dot_l, const half_lobe& s) const noexcept {
        return detail::mixture_pdf(p_lobe_, detail::cosine_lobe_pdf(n_dot_l),
                                   s.power / detail::floored_cos(s.v_dot_h));
    }

    /// A half vector drawn with the density p_h (class comment) in world space.
    [[nodiscard]] vec3<T> sample_h(const vec2<T>& u, const frame<T>& fr) const noexcept {
        // u.x picks the quadrant (its integer part after scaling by 4) and the position
        // within it (the fraction), where the paper's formula gives phi in [0, pi/2).
        // tan(phi_q) = scale tan(pi/2 t) = scale sin / cos, so (cos, sin)(phi_q) is
        // (cos, scale sin)(pi/2 t) normalised: no tangent, arctangent or division by a
        // cosine that reaches 0.
        const T u4 = T(4) * u.x;
        const T quadrant = glm::min(std::floor(u4), T(3));
        const detail::sin_cos<T> sc = detail::sin_cos_half_pi(u4 - quadrant);
        const T y_q = phi_scale_ * sc.sin;
        const T inv_len = T(1) / std::sqrt(sc.cos * sc.cos + y_q * y_q);
        const T cos_phi_q = sc.cos * inv_len;
        const T sin_phi_q = y_q * inv_len;
        const T exponent = p_u_ * cos_phi_q * cos_phi_q + p_v_ * sin_phi_q * sin_phi_q;
        const polar_cosines<T> c = power_cosine_polar(u.y, exponent);
        // Quadrants 1 and 2 mirror x (phi = pi - phi_q, pi + phi_q), 2 and 3 mirror y.
        const T x = (quadrant == T(1) || quadrant == T(2)) ? -cos_phi_q : cos_phi_q;
        const T y = quadrant >= T(2) ? -sin_phi_q : sin_phi_q;
        return fr.to_world(vec3<T>(c.sin_theta * x, c.sin_theta * y, c.cos_theta));
    }

    static T lobe_probability(const rgb<T>& r_d, const rgb<T>& r_s) noexcept {
        return detail::second_lobe_probability(detail::mean_channel(r_d * (rgb<T>(1) - r_s)),
                                               detail::mean_channel(r_s));
    }

    static T specular_normalization(T p_u, T p_v) noexcept {
        // sqrt(p_u + 1) sqrt(p_v + 1) rather than sqrt of the product, which could overflow.
        return std::sqrt(p_u + T(1)) * std::sqrt(p_v + T(1)) / (T(8) * pi<T>);
    }
    /// 1 - (1 - x/2)^5 = (x/2)(1 + y + y^2 + y^3 + y^4), y = 1 - x/2, for x in [0, 1]:
    /// every term is positive, so there is no cancellation when x is small.
    static constexpr T one_minus_pow5_of_one_minus_half(T x) noexcept {
        const T y = T(1) - T(0.5) * x;
        return T(0.5) * x * (T(1) + y * (T(1) + y * (T(1) + y * (T(1) + y))));
    }

    rgb<T> r_d_;
    rgb<T> r_s_;
    T p_u_;
    T p_v_;
    T c_s_;
    T p_lobe_;
    T phi_scale_; ///< sqrt((p_u + 1)/(p_v + 1)), the tangent scale of the azimuth sampling
};

} // namespace shade
