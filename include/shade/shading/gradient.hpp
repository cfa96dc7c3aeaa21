#pragma once
// shade::gradient: a periodic blend of two shaders or BRDFs along a direction.

#include <cmath>
#include <concepts>
#include <limits>
#include <optional>
#include <utility>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <shade/brdf/brdf.hpp>
#include <shade/core/error.hpp>
#include <shade/core/math.hpp>
#include <shade/core/surface_point.hpp>
#include <shade/core/types.hpp>
#include <shade/light/light_sample.hpp>
#include <shade/shading/shader.hpp>

namespace shade {

namespace detail {

/// w * c for a blend weight w in [0, 1], but exactly 0 when w == 0: a child whose value
/// overflowed to inf (large valid parameters) must not turn its zero weight into
/// 0 x inf = NaN.
template <std::floating_point T>
[[nodiscard]] inline rgb<T> weighted(T w, const rgb<T>& c) noexcept {
    return w == T(0) ? rgb<T>(0) : w * c;
}

/// w * p for a blend weight w and a density p, exactly 0 when w == 0 (as weighted).
template <std::floating_point T>
[[nodiscard]] constexpr T weighted(T w, T p) noexcept {
    return w == T(0) ? T(0) : w * p;
}

/// x clamped below 1: a number in [0, 1) after a division that may round up to 1.
template <std::floating_point T>
[[nodiscard]] inline T below_one(T x) noexcept {
    return glm::min(x, T(1) - std::numeric_limits<T>::epsilon() / T(2));
}

} // namespace detail

/// A cosine gradient between two children along the unit direction d:
///
///   alpha(p) = (1 + cos(2 pi (p.d) / period + phase)) / 2      in [0, 1]
///   result   = alpha * first + (1 - alpha) * second
///
/// i.e. the first child is alpha-composited over the second with opacity alpha. With
/// phase 0, alpha = 1 (pure first child) on the planes p.d = k * period, alpha = 0 (pure
/// second child) at p.d = (k + 1/2) * period and alpha = 1/2 in between at
/// p.d = (k +- 1/4) * period. The cosine makes the blend C-infinity smooth and periodic.
///
/// If both children are BRDFs the gradient is a BRDF: f = alpha f_0 + (1 - alpha) f_1, a
/// convex combination, so it stays non-negative, reciprocal and energy conserving when
/// both children are (f_diffuse and f_specular blend likewise if both split). If both are
/// sampled BRDFs it is one too: sample() chooses the first child when uc < alpha and the
/// second otherwise, passes the child uc rescaled to [0, 1) (uc / alpha or
/// (uc - alpha) / (1 - alpha), so one number serves both choices), and returns the child's
/// direction with the blend's f and pdf, pdf = alpha pdf_0 + (1 - alpha) pdf_1. Otherwise it
/// is a shader blending the children's radiance (a BRDF child lifted by shade_of, i.e.
/// lit without ambient).
template <shader_or_brdf S0, shader_or_brdf S1>
class gradient {
public:
    using scalar_type = scalar_of<S0>;
    using T = scalar_type;
    static_assert(std::same_as<scalar_of<S0>, scalar_of<S1>>,
                  "both children must have the same scalar type");

    /// A gradient from s0 to s1 along `direction` (any finite non-zero length; normalised
    /// here) with the given period (> 0, world units) and phase (radians, finite). Throws
    /// shade::invalid_parameter naming "direction", "period" or "phase".
    gradient(S0 s0, S1 s1, const vec3<T>& direction, T period, T phase = T(0))
        : s0_(std::move(s0)), s1_(std::move(s1)),
          direction_(require_direction("direction", direction)),
          period_(require_positive("period", period)), phase_(require_finite("phase", phase)) {}

    /// The child weighted by alpha.
    [[nodiscard]] const S0& first() const noexcept { return s0_; }
    /// The child weighted by 1 - alpha.
    [[nodiscard]] const S1& second() const noexcept { return s1_; }
    /// The unit direction of the gradient.
    [[nodiscard]] const vec3<T>& direction() const noexcept { return direction_; }
    /// The period along the direction.
    [[nodiscard]] T period() const noexcept { return period_; }
    /// The phase in radians.
    [[nodiscard]] T phase() const noexcept { return phase_; }

    /// The weight of the first child at p (see the class comment).
    [[nodiscard]] T alpha(const vec3<T>& p) const noexcept {
        // (p.d) mod period first (std::fmod is exact): the same angle modulo 2 pi, but it
        // stays finite and accurate far from the origin, where 2 pi (p.d) / period
        // overflowed to inf for a huge finite p and cos(inf) gave NaN.
        const T along = std::fmod(glm::dot(p, direction_), period_);
        const T angle = T(2) * pi<T> * (along / period_) + phase_;
        // Non-finite only when p.d itself overflows (|p| near the largest finite value),
        // where the pattern is far below the resolution of T: use the mean weight 1/2.
        if (!std::isfinite(angle)) return T(0.5);
        return (T(1) + std::cos(angle)) * T(0.5);
    }

    /// BRDF value (1/sr, no cosine): alpha f_0 + (1 - alpha) f_1.
    [[nodiscard]] rgb<T> f(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const
        requires(brdf<S0> && brdf<S1>)
    {
        const T a = alpha(at.p);
        return detail::weighted(a, s0_.f(l, v, at)) + detail::weighted(T(1) - a, s1_.f(l, v, at));
    }

    /// Diffuse part of the BRDF value, blended like f.
    [[nodiscard]] rgb<T> f_diffuse(const vec3<T>& l, const vec3<T>& v,
                                   const surface_point<T>& at) const
        requires(split_brdf<S0> && split_brdf<S1>)
    {
        const T a = alpha(at.p);
        return detail::weighted(a, s0_.f_diffuse(l, v, at)) +
               detail::weighted(T(1) - a, s1_.f_diffuse(l, v, at));
    }

    /// Specular part of the BRDF value, blended like f.
    [[nodiscard]] rgb<T> f_specular(const vec3<T>& l, const vec3<T>& v,
                                    const surface_point<T>& at) const
        requires(split_brdf<S0> && split_brdf<S1>)
    {
        const T a = alpha(at.p);
        return detail::weighted(a, s0_.f_specular(l, v, at)) +
               detail::weighted(T(1) - a, s1_.f_specular(l, v, at));
    }

    /// The density (1/sr) with which sample() draws l: alpha pdf_0 + (1 - alpha) pdf_1.
    [[nodiscard]] T pdf(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const
        requires(sampled_brdf<S0> && sampled_brdf<S1>)
    {
        const T a = alpha(at.p);
        return detail::weighted(a, s0_.pdf(l, v, at)) + detail::weighted(T(1) - a, s1_.pdf(l, v, at));
    }

    /// Draws l from the first child when uc < alpha, else from the second (see the class
    /// comment); f and pdf are the blend's f(l, v, at) and pdf(l, v, at). nullopt when the
    /// child returns none.
    [[nodiscard]] std::optional<brdf_sample<T>> sample(const vec3<T>& v, T uc, const vec2<T>& u,
                                                       const surface_point<T>& at) const
        requires(sampled_brdf<S0> && sampled_brdf<S1>)
    {
        const T a = alpha(at.p);
        const std::optional<brdf_sample<T>> child =
            uc < a ? s0_.sample(v, detail::below_one(uc / a), u, at)
                   : s1_.sample(v, detail::below_one((uc - a) / (T(1) - a)), u, at);
        if (!child) return std::nullopt;
        const vec3<T>& l = child->l;
        return detail::make_brdf_sample(l, f(l, v, at), pdf(l, v, at), std::abs(glm::dot(at.n(), l)));
    }

    /// Radiance (light_sample units): alpha shade_0 + (1 - alpha) shade_1.
    [[nodiscard]] rgb<T> shade(const surface_point<T>& at, const vec3<T>& v,
                               const light_sample<T>& s) const
        requires(!(brdf<S0> && brdf<S1>))
    {
        const T a = alpha(at.p);
        return detail::weighted(a, shade_of(s0_, at, v, s)) +
               detail::weighted(T(1) - a, shade_of(s1_, at, v, s));
    }

private:
    S0 s0_;
    S1 s1_;
    vec3<T> direction_;
    T period_;
    T phase_;
};

template <shader_or_brdf S0, shader_or_brdf S1>
gradient(S0, S1, vec3<scalar_of<S0>>, scalar_of<S0>) -> gradient<S0, S1>;
template <shader_or_brdf S0, shader_or_brdf S1>
gradient(S0, S1, vec3<scalar_of<S0>>, scalar_of<S0>, scalar_of<S0>) -> gradient<S0, S1>;

} // namespace shade
