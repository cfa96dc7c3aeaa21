#pragma once
// Internal: what shade::phong and shade::blinn_phong have in common. Both are a Lambertian
// base k_d / pi plus a lobe k_s c cos^s [/ (n·l)] with s the shininess (the exponent), and
// differ only in the cosine raised to the power s (r·v for Phong, n·h for Blinn-Phong) and
// in their normalized forms (the constant c). Each public class derives from
// power_lobe_brdf with its own cosine and documents its forms; the constructor rules,
// accessors, evaluation, sampling and the two forms both models have (classic and
// modified) live here once.

#include <cmath>
#include <concepts>
#include <limits>
#include <optional>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <shade/brdf/brdf.hpp>
#include <shade/brdf/detail/directions.hpp>
#include <shade/brdf/detail/sampling.hpp>
#include <shade/core/error.hpp>
#include <shade/core/frame.hpp>
#include <shade/core/math.hpp>
#include <shade/core/sampling.hpp>
#include <shade/core/surface_point.hpp>
#include <shade/core/types.hpp>

namespace shade::detail {

/// F describes a form of a power lobe: `normalization<T>(shininess)` (the constant c
/// multiplying k_s cos^s), `divides_by_n_dot_l` (the lobe is further divided by n·l) and
/// `reciprocal` (whether f(l, v) == f(v, l)).
template <class F, class T>
concept power_lobe_form = std::floating_point<T> && requires(T x) {
    { F::template normalization<T>(x) } -> std::same_as<T>;
    { F::divides_by_n_dot_l } -> std::convertible_to<bool>;
    { F::reciprocal } -> std::convertible_to<bool>;
};

/// The classic lighting-model form shared by Phong and Blinn-Phong: c = 1/pi and the lobe
/// divided by n·l, so that pi f I_s (n·l) (shade::lit) is the classic term k_s I_s cos^s.
/// Documented, with its citation, as shade::phong_form::classic and
/// shade::blinn_phong_form::classic.
struct classic_power_lobe {
    static constexpr bool divides_by_n_dot_l = true;
    static constexpr bool reciprocal = false;
    template <std::floating_point T>
    [[nodiscard]] static constexpr T normalization(T /*shininess*/) noexcept {
        return inv_pi<T>;
    }
};

/// The unnormalized reciprocal form shared by Phong and Blinn-Phong: c = 1, f_s = k_s cos^s.
/// Documented as shade::phong_form::modified and shade::blinn_phong_form::modified.
struct modified_power_lobe {
    static constexpr bool divides_by_n_dot_l = false;
    static constexpr bool reciprocal = true;
    template <std::floating_point T>
    [[nodiscard]] static constexpr T normalization(T /*shininess*/) noexcept {
        return T(1);
    }
};

/// The cosine a lobe raises to the power s at (l, v), together with the factor that turns
/// the power-cosine density of what the lobe samples into the density of l:
/// pdf(l) = (s + 1)/(2 pi) cosine^s * jacobian.
template <std::floating_point T>
struct lobe_geometry {
    T cosine = 0;   ///< in [0, 1]
    T jacobian = 1; ///< d(sampled direction) / dl, as a ratio of solid angles
};

/// C is a lobe cosine for T: `C::cosine(n, l, v)` (the cosine in [0, 1] for unit n, l, v with
/// n·l > 0 and n·v > 0), `C::geometry(n, l, v)` (the same cosine with its jacobian),
/// `C::sample(v, s, u, at)` (a direction l drawn with that density; it may be below the
/// surface) and `C::unit_albedo(s, divides_by_n_dot_l)` (the directional albedo at v = n of
/// cos^s [/ (n·l)], i.e. of the lobe with c = 1 and k_s = 1).
template <class C, class T>
concept lobe_cosine = std::floating_point<T> &&
    requires(const vec3<T>& d, T s, const vec2<T>& u, const surface_point<T>& at) {
        { C::cosine(d, d, d) } -> std::same_as<T>;
        { C::geometry(d, d, d) } -> std::same_as<lobe_geometry<T>>;
        { C::sample(d, s, u, at) } -> std::same_as<vec3<T>>;
        { C::unit_albedo(s, true) } -> std::same_as<T>;
    };

/// Phong's cosine max(r·v, 0) with r = 2 (n·l) n - l, l mirrored about n; capped at 1,
/// which rounding can exceed, so that a large exponent cannot overflow. r·v is symmetric
/// in l and v (2 (n·l)(n·v) - l·v), so the lobe is also the power cosine about the mirror
/// direction of v, and that is how it is sampled (Lafortune, Willems 1994, "Using the
/// Modified Phong Reflectance Model for Physically Based Rendering", Tech. Rep. CW 197,
/// K.U. Leuven, the sampling of the specular lobe): l is drawn about 2 (n·v) n - v with
/// the density (s + 1)/(2 pi) cos^s, jacobian 1.
///
/// Precision: unit vectors of T are unit only to within rounding (an ulp or so), and cos^s
/// multiplies the relative error of cos by s; at s = 10^4 the textbook 2 (n·l)(n·v) - l·v,
/// which grows with |n|^2, |l| and |v|, is 0.5 % too large for |n| = 1 + 2^-23. So the
/// cosine is computed as 1 - d with
///
///     d = ((n·(l - v))^2 / (n·n) + |P (l + v)|^2) / 2,   P (l + v) = (l + v) - (n·(l + v))/(n·n) n
///
/// the part of l + v perpendicular to n: for unit l, v this is 1 - r·v exactly, r the mirror
/// of l about n / |n| (splitting l and v into parts along and across n), and for l, v, n a
/// little off unit length it still is 1 - cos(angle between r and v) up to terms of second
/// order near the peak, where d is small. d is a sum of squares, so it keeps its relative
/// precision there (no cancellation against 1), and l - v = -(v - l), l + v = v + l make it
/// the same for (l, v) as for (v, l) to the last bit. The sampler's axis is the mirror of v
/// about n / |n| likewise.
struct mirror_cosine {
    template <std::floating_point T>
    [[nodiscard]] static T cosine(const vec3<T>& n, const vec3<T>& l, const vec3<T>& v) noexcept {
        const T n_dot_n = glm::dot(n, n);
        const T n_dot_u = glm::dot(n, l - v);
        const vec3<T> w = l + v;
        const vec3<T> w_across = w - (glm::dot(n, w) / n_dot_n) * n;
        const T d = T(0.5) * (n_dot_u * n_dot_u / n_dot_n + glm::dot(w_across, w_across));
        const T r_dot_v = T(1) - d;
        return r_dot_v > T(0) ? r_dot_v : T(0);
    }
    template <std::floating_point T>
    [[nodiscard]] static lobe_geometry<T> geometry(const vec3<T>& n, const vec3<T>& l,
                                                   const vec3<T>& v) noexcept {
        return {cosine(n, l, v), T(1)};
    }
    template <std::floating_point T>
    [[nodiscard]] static vec3<T> sample(const vec3<T>& v, T s, const vec2<T>& u,
                                        const surface_point<T>& at) noexcept {
        const vec3<T>& n = at.n();
        const frame<T> about_r = frame<T>::from_normal(T(2) * glm::dot(v, n) / glm::dot(n, n) * n - v);
        return about_r.to_world(square_to_power_cosine_hemisphere(u, s));
    }
    /// At v = n, r·l = n·l: 2 pi / (s + 2), or 2 pi / (s + 1) when divided by n·l.
    template <std::floating_point T>
    [[nodiscard]] static T unit_albedo(T s, bool divides_by_n_dot_l) noexcept {
        return T(2) * pi<T> / (s + (divides_by_n_dot_l ? T(1) : T(2)));
    }
};

/// Blinn's cosine n·h with h = normalize(l + v) (detail::half_vector_and_cos), in [0, 1],
/// computed so that it does not depend on the length of n (scale_free_cosine). Sampled as
/// the Blinn microfacet distribution is in Pharr, Humphreys 2010, "Physically Based
/// Rendering", 2nd ed., sec. 14.5.1: h is drawn about n with the density
/// (s + 1)/(2 pi) (n·h)^s and l = 2 (v·h) h - v; the half-vector map has
/// |dh/dl| = 1/(4 v·h) (Torrance, Sparrow 1967, "Theory for Off-Specular Reflection from
/// Roughened Surfaces", JOSA 57(9)), the jacobian. v·h is floored at
/// detail::cos_floor there so that a density never overflows.
struct half_vector_cosine {
    /// cos(n, h) whatever the length of n: n·h / |n|, clamped to [0, 1] (h is unit). n·h
    /// itself grows with |n|, and a float normal one ulp off unit length would scale cos^s
    /// by about 1 + s (|n| - 1) at shininess s (1e-3 at s = 10^4); dividing by |n| removes
    /// that systematic error, leaving the rounding of h and of the product, which varies
    /// in sign from direction to direction.
    template <std::floating_point T>
    [[nodiscard]] static T scale_free_cosine(const vec3<T>& n, const vec3<T>& h) noexcept {
        return glm::min(clamped_dot(n, h) / std::sqrt(glm::dot(n, n)), T(1));
    }
    template <std::floating_point T>
    [[nodiscard]] static T cosine(const vec3<T>& n, const vec3<T>& l, const vec3<T>& v) noexcept {
        return scale_free_cosine(n, half_vector_and_cos(l, v).h);
    }
    template <std::floating_point T>
    [[nodiscard]] static lobe_geometry<T> geometry(const vec3<T>& n, const vec3<T>& l,
                                                   const vec3<T>& v) noexcept {
        const half_angle<T> ha = half_vector_and_cos(l, v);
        return {scale_free_cosine(n, ha.h), T(0.25) / floored_cos(ha.cos_theta_d)};
    }
    /// h with v·h <= 0 gives an l below the surface (n·l = 2 (v·h)(n·h) - n·v < 0), which
    /// the caller drops.
    template <std::floating_point T>
    [[nodiscard]] static vec3<T> sample(const vec3<T>& v, T s, const vec2<T>& u,
                                        const surface_point<T>& at) noexcept {
        const vec3<T> h = at.shading.to_world(square_to_power_cosine_hemisphere(u, s));
        return reflect_about(v, h);
    }
    /// At v = n, theta_h = theta_l / 2 (Giesen 2009, "The Blinn-Phong Normalization Zoo"):
    /// 2 pi int_0^{pi/2} cos^s(theta/2) cos(theta) sin(theta) dtheta
    ///   = 8 pi (s + 2^(-s/2)) / ((s + 2)(s + 4)),
    /// and without the cos(theta) (divided by n·l), with x = theta/2,
    /// 2 pi int_0^{pi/4} cos^s(x) 4 sin(x) cos(x) dx = 8 pi (1 - 2^(-(s+2)/2)) / (s + 2).
    template <std::floating_point T>
    [[nodiscard]] static T unit_albedo(T s, bool divides_by_n_dot_l) noexcept {
        if (divides_by_n_dot_l) return T(8) * pi<T> * (T(1) - std::exp2(-(s + T(2)) / T(2))) / (s + T(2));
        return T(8) * pi<T> / (s + T(2)) * ((s + std::exp2(-s / T(2))) / (s + T(4)));
    }
};

/// The Lambertian base plus the power lobe:
///
///     f = k_d / pi + k_s c cos^s [/ (n·l) when Form::divides_by_n_dot_l]     (1/sr)
///
/// with c = Form::normalization(s), s = shininess and cos = Cosine::cosine(n, l, v);
/// 0 unless n·l > 0 and n·v > 0. n·l in the divisor is floored at detail::cos_floor.
/// Satisfies shade::split_brdf (f_diffuse = k_d / pi, f_specular = the lobe), so
/// shade::lit lights the lobe with the light's specular colour, and shade::sampled_brdf:
/// sample() chooses the lobe with uc < P_s and the cosine lobe n·l / pi otherwise, where
///
///     P_s = a_s / (a_d + a_s),  a_d = mean(k_d),  a_s = mean(k_s) c Cosine::unit_albedo(s)
///
/// (the two parts' albedos at normal incidence; P_s = 1/2 when both are 0), and pdf() is the
/// mixture (1 - P_s) n·l / pi + P_s (s + 1)/(2 pi) cos^s jacobian. The part of the lobe
/// below the surface is never returned (sample() gives nullopt there), so pdf integrates
/// to at most 1 over the hemisphere. One gap: with shininess 0, Phong's lobe is k_s c also
/// where r·v <= 0 (0^0 = 1) but the power cosine draws only r·l > 0, so with k_d = 0 those
/// directions have f > 0 and pdf 0 (with k_d > 0 the cosine lobe covers them).
template <std::floating_point T, class Form, class Cosine>
    requires power_lobe_form<Form, T> && lobe_cosine<Cosine, T>
class power_lobe_brdf {
public:
    using scalar_type = T;
    using form_type = Form;

    /// Validating constructor. Throws shade::invalid_parameter naming
    ///   "k_d" or "k_s" unless every channel is finite and >= 0,
    ///   "shininess" unless it is finite and >= 0, or if the form's constant c overflows T,
    ///   "k_s" / "k_d" if the peak value of f overflows T.
    power_lobe_brdf(const rgb<T>& k_d, const rgb<T>& k_s, T shininess)
        : k_d_(require_non_negative("k_d", k_d)), k_s_(require_non_negative("k_s", k_s)),
          shininess_(require_non_negative("shininess", shininess)),
          c_(Form::template normalization<T>(shininess)),
          p_lobe_(lobe_probability(k_d_, k_s_, shininess_, c_)) {
        require_finite_peak("shininess", c_);
        T peak = max_channel(k_s_) * c_;
        if constexpr (Form::divides_by_n_dot_l) peak /= cos_floor<T>;
        require_finite_peak("k_s", peak);
        require_finite_peak("k_d", max_channel(k_d_) * inv_pi<T> + peak);
    }

    /// Unchecked: the caller guarantees the rules of the validating constructor.
    power_lobe_brdf(unchecked_t, const rgb<T>& k_d, const rgb<T>& k_s, T shininess) noexcept
        : k_d_(k_d), k_s_(k_s), shininess_(shininess),
          c_(Form::template normalization<T>(shininess)),
          p_lobe_(lobe_probability(k_d, k_s, shininess, c_)) {}

    [[nodiscard]] constexpr const rgb<T>& k_d() const noexcept { return k_d_; } ///< diffuse reflectance
    [[nodiscard]] constexpr const rgb<T>& k_s() const noexcept { return k_s_; } ///< specular coefficient
    [[nodiscard]] constexpr T shininess() const noexcept { return shininess_; } ///< the exponent s
    /// The form's constant c.
    [[nodiscard]] constexpr T normalization() const noexcept { return c_; }
    /// P_s: the probability with which sample() draws from the lobe rather than the
    /// cosine lobe (see the class comment).
    [[nodiscard]] constexpr T lobe_probability() const noexcept { return p_lobe_; }

    /// Diffuse part k_d / pi (1/sr), 0 unless n·l > 0 and n·v > 0.
    [[nodiscard]] rgb<T> f_diffuse(const vec3<T>& l, const vec3<T>& v,
                                   const surface_point<T>& at) const noexcept {
        assert_unit_directions(l, v, at);
        if (!above(l, v, at)) return rgb<T>(0);
        return k_d_ * inv_pi<T>;
    }

    /// Specular lobe k_s c cos^s [/ (n·l)] (1/sr), 0 unless n·l > 0 and n·v > 0.
    [[nodiscard]] rgb<T> f_specular(const vec3<T>& l, const vec3<T>& v,
                                    const surface_point<T>& at) const noexcept {
        assert_unit_directions(l, v, at);
        if (!above(l, v, at)) return rgb<T>(0);
        const vec3<T>& n = at.n();
        return k_s_ * lobe(std::pow(Cosine::cosine(n, l, v), shininess_), glm::dot(n, l));
    }

    /// BRDF value in 1/sr without the cosine: f_diffuse + f_specular.
    [[nodiscard]] rgb<T> f(const vec3<T>& l, const vec3<T>& v,
                           const surface_point<T>& at) const noexcept {
        return f_diffuse(l, v, at) + f_specular(l, v, at);
    }

    /// The solid-angle density (1/sr) with which sample() draws l for v: the mixture in
    /// the class comment; 0 unless n·l > 0 and n·v > 0.
    [[nodiscard]] T pdf(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const noexcept {
        if (!above(l, v, at)) return T(0);
        const T n_dot_l = glm::dot(at.n(), l);
        const lobe_geometry<T> g = Cosine::geometry(at.n(), l, v);
        return lobe_pdf(n_dot_l, g, std::pow(g.cosine, shininess_));
    }

    /// Draws l for v (see the class comment): the lobe when uc < lobe_probability(), else
    /// the cosine lobe, u placing the direction within it. nullopt when v or the drawn l
    /// is not above the surface. The returned f and pdf are f(l, v, at) and pdf(l, v, at).
    [[nodiscard]] std::optional<brdf_sample<T>> sample(const vec3<T>& v, T uc, const vec2<T>& u,
                                                       const surface_point<T>& at) const noexcept {
        const vec3<T>& n = at.n();
        if (!(glm::dot(n, v) > T(0))) return std::nullopt;
        const vec3<T> l = uc < p_lobe_ ? Cosine::sample(v, shininess_, u, at) : sample_cosine_lobe(u, at);
        const T n_dot_l = glm::dot(n, l);
        if (!(n_dot_l > T(0))) return std::nullopt;
        const lobe_geometry<T> g = Cosine::geometry(n, l, v);
        const T power = std::pow(g.cosine, shininess_);
        return make_brdf_sample(l, k_d_ * inv_pi<T> + k_s_ * lobe(power, n_dot_l),
                                lobe_pdf(n_dot_l, g, power), n_dot_l);
    }

private:
    [[nodiscard]] static bool above(const vec3<T>& l, const vec3<T>& v,
                                    const surface_point<T>& at) noexcept {
        return glm::dot(at.n(), l) > T(0) && glm::dot(at.n(), v) > T(0);
    }

    /// c cos^s [/ (n·l)] from power = cos^s.
    [[nodiscard]] T lobe(T power, T n_dot_l) const noexcept {
        T value = c_ * power;
        if constexpr (Form::divides_by_n_dot_l) value /= floored_cos(n_dot_l);
        return value;
    }

    /// The mixture density from n·l, the lobe geometry and power = cosine^s. The power
    /// cosine is drawn only where cosine > 0 (0^0 = 1 would otherwise give shininess 0 a
    /// density where the lobe is never drawn).
    /// As v·h -> 0 the half-vector Jacobian 1/(4 v·h) overflows: the density there exceeds
    /// every finite T, so it saturates at the largest finite value instead of becoming +inf
    /// (or NaN where power is 0).
    [[nodiscard]] T lobe_pdf(T n_dot_l, const lobe_geometry<T>& g, T power) const noexcept {
        T lobe_density = g.cosine > T(0) && power > T(0)
                             ? (shininess_ + T(1)) / (T(2) * pi<T>) * power * g.jacobian
                             : T(0);
        if (!(lobe_density <= std::numeric_limits<T>::max())) lobe_density = std::numeric_limits<T>::max();
        return mixture_pdf(p_lobe_, cosine_lobe_pdf(n_dot_l), lobe_density);
    }

    static T lobe_probability(const rgb<T>& k_d, const rgb<T>& k_s, T shininess, T c) noexcept {
        return second_lobe_probability(
            mean_channel(k_d),
            mean_channel(k_s) * c * Cosine::unit_albedo(shininess, Form::divides_by_n_dot_l));
    }

    rgb<T> k_d_;
    rgb<T> k_s_;
    T shininess_;
    T c_;
    T p_lobe_;
};

} // namespace shade::detail
