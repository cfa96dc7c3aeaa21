#pragma once
// The distribution (D) and shadowing-masking (G) terms of microfacet models, one function
// per term named term_model (D_beckmann, D_ggx, G1_smith_beckmann, G1_smith_ggx,
// G_v_groove), and the small term types shade::cook_torrance is composed from:
//
//   distributions  beckmann<T> (parameter m),  ggx<T> (parameter alpha)
//   masking        v_groove<T>,  smith_beckmann<T>,  smith_ggx<T>
//
// Roughness parameters: Beckmann's `m` is the RMS slope of the microfacets (Cook and
// Torrance's m, Walter et al.'s alpha_b); GGX's `alpha` is Walter et al.'s alpha_g. Neither
// is a "perceptual roughness" (shade does not use that name for either). Both must lie in
// [microfacet_parameter_min, microfacet_parameter_max] = [1e-4, 1e4].
//
// Fresnel terms live in shade/brdf/fresnel.hpp.

#include <algorithm>
#include <cmath>
#include <concepts>
#include <string_view>

#include <shade/brdf/brdf.hpp>
#include <shade/core/error.hpp>
#include <shade/core/math.hpp>
#include <shade/core/types.hpp>
#include "namespace.hpp"

namespace shade_legacy {

/// Smallest accepted microfacet roughness parameter (Beckmann m, GGX alpha): 1e-4. A lobe
/// narrower than this is below what float can resolve around the mirror direction (the
/// float spacing of cos(theta_h) just below 1, 6e-8, is theta_h ~ 3.5e-4 rad), and the
/// peak value 1/(pi m^2) = 3.2e7 still leaves f far from overflow.
template <std::floating_point T>
inline constexpr T microfacet_parameter_min = T(1e-4);

/// Largest accepted microfacet roughness parameter: 1e4. Beyond it the distributions are
/// numerically flat, and the bound keeps every term's intermediate values finite.
template <std::floating_point T>
inline constexpr T microfacet_parameter_max = T(1e4);

// ---------------------------------------------------------------------------------------
// D: normal distribution functions. Each returns D(h) in 1/sr, normalized so that
// integral over the hemisphere of D(h) (n·h) dh = 1, and 0 for n·h <= 0.

/// Beckmann distribution.
///
/// Beckmann, Spizzichino 1963, "The Scattering of Electromagnetic Waves from Rough
/// Surfaces"; normalized form: Walter, Marschner, Li, Torrance 2007, "Microfacet Models for
/// Refraction through Rough Surfaces", EGSR, eq. 25 (their alpha_b is our m):
///
///     D(h) = exp(-tan^2(theta_h) / m^2) / (pi m^2 cos^4(theta_h))
///
/// n_dot_h = cos(theta_h); m = RMS slope, in [1e-4, 1e4]. D(n) = 1/(pi m^2).
/// 1 - cos^2 is computed as (1 - c)(1 + c), which keeps its accuracy for c near 1 (the
/// peak of narrow lobes). Where exp(...) underflows to 0 the result is 0 (also when
/// cos^4 underflows, which cannot happen with exp(...) > 0 for m in the valid range).
template <std::floating_point T>
[[nodiscard]] inline T D_beckmann(T n_dot_h, T m) noexcept {
    if (!(n_dot_h > T(0))) return T(0);
    const T c = std::min(n_dot_h, T(1));
    const T c2 = c * c;
    const T m2 = m * m;
    const T tan2 = (T(1) - c) * (T(1) + c) / c2;
    const T e = std::exp(-tan2 / m2);
    if (!(e > T(0))) return T(0);
    return e / (pi<T> * m2 * c2 * c2);
}

/// GGX (Trowbridge-Reitz) distribution.
///
/// Trowbridge, Reitz 1975, "Average irregularity representation of a rough surface for ray
/// reflection", JOSA 65(5); named GGX in Walter et al. 2007 (EGSR), eq. 33:
///
///     D(h) = alpha^2 / (pi cos^4(theta_h) (alpha^2 + tan^2(theta_h))^2)
///          = alpha^2 / (pi (alpha^2 cos^2(theta_h) + sin^2(theta_h))^2)
///
/// n_dot_h = cos(theta_h); alpha in [1e-4, 1e4]. D(n) = 1/(pi alpha^2). The second form,
/// with sin^2 = (1 - c)(1 + c), has no cancellation for tiny alpha (the usual
/// (alpha^2 - 1) c^2 + 1 rounds to 0 at c = 1 when alpha^2 < float epsilon, giving Inf).
template <std::floating_point T>
[[nodiscard]] inline T D_ggx(T n_dot_h, T alpha) noexcept {
    if (!(n_dot_h > T(0))) return T(0);
    const T c = std::min(n_dot_h, T(1));
    const T a2 = alpha * alpha;
    const T s2 = (T(1) - c) * (T(1) + c);
    const T k = a2 * c * c + s2;
    return a2 / (pi<T> * k * k);
}

// ---------------------------------------------------------------------------------------
// G: shadowing-masking. G1 is the masking of one direction (dimensionless, in [0, 1]);
// the separable Smith G = G1(l) G1(v) (Walter et al. 2007, eq. 23).

/// Smith masking for the Beckmann distribution, rational approximation.
///
/// Smith 1967, "Geometrical shadowing of a random rough surface", IEEE Trans. Antennas
/// Propag. 15(5); the approximation of Walter et al. 2007 (EGSR), eq. 27:
///
///     a = cos(theta) / (m sin(theta))
///     G1 = (3.535 a + 2.181 a^2) / (1 + 2.276 a + 2.577 a^2)   if a < 1.6,   else 1
///
/// n_dot_w = cos(theta) of the direction w (l or v) with the normal; m as in D_beckmann.
/// Returns G1 in [0, 1]; 0 for n_dot_w <= 0, 1 at n_dot_w = 1. (The approximation departs
/// from the exact erf form of eq. 26 by well under 1%.)
template <std::floating_point T>
[[nodiscard]] inline T G1_smith_beckmann(T n_dot_w, T m) noexcept {
    if (!(n_dot_w > T(0))) return T(0);
    const T c = std::min(n_dot_w, T(1));
    const T s = std::sqrt((T(1) - c) * (T(1) + c));
    // a >= 1.6 (including s = 0, where a would be +inf) gives exactly 1.
    if (!(m * s * T(1.6) > c)) return T(1);
    const T a = c / (m * s);
    return (T(3.535) * a + T(2.181) * a * a) / (T(1) + T(2.276) * a + T(2.577) * a * a);
}

/// Smith masking for the GGX distribution.
///
/// Walter et al. 2007 (EGSR), eq. 34: G1 = 2 / (1 + sqrt(1 + alpha^2 tan^2(theta))),
/// evaluated as the equal 2 c / (c + sqrt(c^2 + alpha^2 (1 - c^2))) with c = cos(theta), which
/// needs no tangent and goes smoothly to 0 as c -> 0 (the tan form overflows there).
/// Returns G1 in [0, 1]; 0 for n_dot_w <= 0, 1 at n_dot_w = 1.
template <std::floating_point T>
[[nodiscard]] inline T G1_smith_ggx(T n_dot_w, T alpha) noexcept {
    if (!(n_dot_w > T(0))) return T(0);
    const T c = std::min(n_dot_w, T(1));
    const T s2 = (T(1) - c) * (T(1) + c);
    return T(2) * c / (c + std::sqrt(c * c + alpha * alpha * s2));
}

/// The V-groove shadowing-masking of Torrance and Sparrow.
///
/// Torrance, Sparrow 1967, "Theory for Off-Specular Reflection from Roughened Surfaces",
/// JOSA 57(9); in this form Blinn 1977, "Models of Light Reflection for Computer
/// Synthesized Pictures", SIGGRAPH, and Cook, Torrance 1982, "A Reflectance Model for
/// Computer Graphics", ACM ToG 1(1) (the geometrical attenuation factor G):
///
///     G = min(1, 2 (n·h)(n·v) / (v·h), 2 (n·h)(n·l) / (l·h))
///
/// with v·h = l·h. Returns G in [0, 1]; 0 if n·l, n·v or v·h is <= 0. G = 1 for l = v = n.
template <std::floating_point T>
[[nodiscard]] constexpr T G_v_groove(T n_dot_l, T n_dot_v, T n_dot_h, T v_dot_h) noexcept {
    if (!(n_dot_l > T(0)) || !(n_dot_v > T(0)) || !(n_dot_h > T(0)) || !(v_dot_h > T(0)))
        return T(0);
    // Written as min(v·h, 2 (n·h) min(n·l, n·v)) / (v·h) so there is one division, by
    // v·h > 0, and the result cannot exceed 1 through rounding.
    const T shadowed = T(2) * n_dot_h * std::min(n_dot_l, n_dot_v);
    return std::min(v_dot_h, shadowed) / v_dot_h;
}

// ---------------------------------------------------------------------------------------
// Term types.

namespace detail {

template <std::floating_point T>
T require_microfacet_parameter(std::string_view name, T x) {
    return require_in_range(name, x, microfacet_parameter_min<T>, microfacet_parameter_max<T>);
}

} // namespace detail

/// Distribution term type: Beckmann with RMS slope m (see D_beckmann).
template <std::floating_point T>
class beckmann {
public:
    using scalar_type = T;

    /// Throws shade::invalid_parameter naming "m" unless m is in [1e-4, 1e4].
    explicit beckmann(T m) : m_(detail::require_microfacet_parameter("m", m)) {}

    /// Unchecked: the caller guarantees m in [1e-4, 1e4].
    constexpr beckmann(unchecked_t, T m) noexcept : m_(m) {}

    /// The RMS slope m.
    [[nodiscard]] constexpr T m() const noexcept { return m_; }

    /// D(h) in 1/sr (see D_beckmann).
    [[nodiscard]] T D(T n_dot_h) const noexcept { return D_beckmann(n_dot_h, m_); }

    /// The largest value of D over all h: 1/(pi m^2) if m^2 <= 1/2 (peak at h = n), else
    /// 4 m^2 exp(1/m^2 - 2) / pi (peak where 1/cos^2(theta_h) = 2 m^2; from d/dx of
    /// x^2 exp(-(x - 1)/m^2) = 0 with x = 1/cos^2).
    [[nodiscard]] T peak() const noexcept {
        const T m2 = m_ * m_;
        if (m2 <= T(0.5)) return T(1) / (pi<T> * m2);
        return T(4) * m2 * std::exp(T(1) / m2 - T(2)) / pi<T>;
    }

private:
    T m_;
};

/// Distribution term type: GGX / Trowbridge-Reitz with parameter alpha (see D_ggx).
template <std::floating_point T>
class ggx {
public:
    using scalar_type = T;

    /// Throws shade::invalid_parameter naming "alpha" unless alpha is in [1e-4, 1e4].
    explicit ggx(T alpha) : alpha_(detail::require_microfacet_parameter("alpha", alpha)) {}

    /// Unchecked: the caller guarantees alpha in [1e-4, 1e4].
    constexpr ggx(unchecked_t, T alpha) noexcept : alpha_(alpha) {}

    /// The parameter alpha (Walter et al.'s alpha_g).
    [[nodiscard]] constexpr T alpha() const noexcept { return alpha_; }

    /// D(h) in 1/sr (see D_ggx).
    [[nodiscard]] T D(T n_dot_h) const noexcept { return D_ggx(n_dot_h, alpha_); }

    /// The largest value of D over all h: 1/(pi alpha^2) at h = n if alpha <= 1, else
    /// alpha^2/pi at grazing h (the denominator alpha^2 c^2 + 1 - c^2 is smallest there).
    [[nodiscard]] T peak() const noexcept {
        const T a2 = alpha_ * alpha_;
        return alpha_ <= T(1) ? T(1) / (pi<T> * a2) : a2 / pi<T>;
    }

private:
    T alpha_;
};

/// X is a microfacet distribution: it names its scalar type, `x.D(n_dot_h)` returns D in
/// 1/sr and `x.peak()` an upper bound of D.
template <class X>
concept microfacet_distribution = has_scalar_type<X> &&
    requires(const X& x, typename X::scalar_type c) {
        { x.D(c) } -> std::same_as<typename X::scalar_type>;
        { x.peak() } -> std::same_as<typename X::scalar_type>;
    };

/// Masking term type: V-groove (see G_v_groove); works with any distribution.
template <std::floating_point T>
struct v_groove {
    using scalar_type = T;

    /// G in [0, 1] for the given cosines (n·l, n·v, n·h, v·h); the distribution is unused.
    template <class Distribution>
    [[nodiscard]] static constexpr T G(const Distribution& /*distribution*/, T n_dot_l, T n_dot_v,
                                       T n_dot_h, T v_dot_h) noexcept {
        return G_v_groove(n_dot_l, n_dot_v, n_dot_h, v_dot_h);
    }
};

/// Masking term type: separable Smith for Beckmann, G1(l) G1(v) (see G1_smith_beckmann).
template <std::floating_point T>
struct smith_beckmann {
    using scalar_type = T;

    /// G = G1(n·l) G1(n·v) in [0, 1], with the distribution's m.
    [[nodiscard]] static T G(const beckmann<T>& distribution, T n_dot_l, T n_dot_v,
                             T /*n_dot_h*/, T /*v_dot_h*/) noexcept {
        return G1_smith_beckmann(n_dot_l, distribution.m()) *
               G1_smith_beckmann(n_dot_v, distribution.m());
    }
};

/// Masking term type: separable Smith for GGX, G1(l) G1(v) (see G1_smith_ggx).
template <std::floating_point T>
struct smith_ggx {
    using scalar_type = T;

    /// G = G1(n·l) G1(n·v) in [0, 1], with the distribution's alpha.
    [[nodiscard]] static T G(const ggx<T>& distribution, T n_dot_l, T n_dot_v, T /*n_dot_h*/,
                             T /*v_dot_h*/) noexcept {
        return G1_smith_ggx(n_dot_l, distribution.alpha()) *
               G1_smith_ggx(n_dot_v, distribution.alpha());
    }
};

/// X is a masking term usable with distribution D: `x.G(d, n·l, n·v, n·h, v·h)` returns G.
/// (smith_beckmann accepts only beckmann, smith_ggx only ggx.)
template <class X, class D>
concept masking_for = microfacet_distribution<D> &&
    requires(const X& x, const D& d, typename D::scalar_type c) {
        { x.G(d, c, c, c, c) } -> std::same_as<typename D::scalar_type>;
    };

} // namespace shade_legacy
