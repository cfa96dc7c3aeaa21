#pragma once
// shade::beckmann: the Beckmann microfacet distribution, isotropic or anisotropic, with its
// exact Smith masking (Lambda, G1, erf form) and the sampling of its visible normals; the
// free functions D_beckmann, Lambda_beckmann, G1_smith_beckmann (Walter et al.'s rational
// approximation) and G1_smith_beckmann_exact.
//
// Local frame: n = +z, t = +x, b = +y. m_x and m_y are the RMS slopes of the microfacets
// along t and b (Cook and Torrance's m, Walter et al.'s alpha_b when they are equal).

#include <cmath>
#include <concepts>
#include <limits>
#include <numbers>
#include <string_view>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <shade/brdf/brdf.hpp>
#include <shade/brdf/microfacet/distribution.hpp>
#include <shade/core/math.hpp>
#include <shade/core/types.hpp>

namespace shade {

/// Beckmann distribution, isotropic, from the cosine of the half angle.
///
/// Beckmann, Spizzichino 1963, "The Scattering of Electromagnetic Waves from Rough
/// Surfaces"; normalized form: Walter, Marschner, Li, Torrance 2007, "Microfacet Models for
/// Refraction through Rough Surfaces", EGSR, eq. 25 (their alpha_b is our m):
///
///     D(h) = exp(-tan^2(theta_h) / m^2) / (pi m^2 cos^4(theta_h))
///
/// n_dot_h = cos(theta_h); m = RMS slope, in [1e-4, 1e4]. Returns D in 1/sr; D(n) =
/// 1/(pi m^2). Two-sided: D(-n_dot_h) = D(n_dot_h) (the convention of
/// shade/brdf/microfacet/distribution.hpp), 0 on the horizon (n·h = 0, or NaN). 1 - cos^2 is computed as (1 - c)(1 + c), which keeps its
/// accuracy for c near 1 (the peak of narrow lobes). Where exp(...) underflows to 0 the
/// result is 0 (also when cos^4 underflows, which cannot happen with exp(...) > 0 for m in
/// the valid range).
template <std::floating_point T>
[[nodiscard]] inline T D_beckmann(T n_dot_h, T m) noexcept {
    const T c = glm::min(std::abs(n_dot_h), T(1));
    if (!(c > T(0))) return T(0);
    const T c2 = c * c;
    const T m2 = m * m;
    const T tan2 = (T(1) - c) * (T(1) + c) / c2;
    const T e = std::exp(-tan2 / m2);
    if (!(e > T(0))) return T(0);
    return e / (pi<T> * m2 * c2 * c2);
}

namespace detail {

/// D_beckmann(m, m_x, m_y) from the reciprocals 1/m_x, 1/m_y and 1/(pi m_x m_y), with
/// 1/m_z^2 taken once: one division per evaluation (shade::beckmann keeps the reciprocals).
template <std::floating_point T>
[[nodiscard]] inline T D_beckmann_from_reciprocals(const vec3<T>& m, T inv_m_x, T inv_m_y, T inv_pi_m_xy) noexcept {
    if (!(std::abs(m.z) > T(0))) return T(0);
    const T inv_c2 = T(1) / (m.z * m.z);
    const T x = m.x * inv_m_x;
    const T y = m.y * inv_m_y;
    const T e = std::exp(-(x * x + y * y) * inv_c2);
    if (!(e > T(0))) return T(0);
    return e * inv_pi_m_xy * (inv_c2 * inv_c2);
}

} // namespace detail

/// Anisotropic Beckmann distribution of a microfacet normal m in the local frame.
///
/// Heitz 2014, "Understanding the Masking-Shadowing Function in Microfacet-Based BRDFs",
/// JCGT 3(2), sec. 5 (the anisotropic Beckmann distribution: Walter et al. 2007, eq. 25,
/// stretched by m_x and m_y):
///
///     D(m) = exp(-(m_x^2/m_x'^2 + m_y^2/m_y'^2) / m_z^2) / (pi m_x' m_y' m_z^4)
///
/// (m_x', m_y' the two RMS slopes, m the unit normal). Returns D in 1/sr, 0 where the
/// exponential underflows; D(n) = 1/(pi m_x' m_y'). Two-sided: D(-m) = D(m) (m_z enters
/// squared), 0 for m_z = 0. The tangent-plane components
/// give tan^2 with full relative precision near the peak.
template <std::floating_point T>
[[nodiscard]] inline T D_beckmann(const vec3<T>& m, T m_x, T m_y) noexcept {
    return detail::D_beckmann_from_reciprocals(m, T(1) / m_x, T(1) / m_y, T(1) / (pi<T> * m_x * m_y));
}

namespace detail {

/// Smith's Lambda of the Beckmann distribution as a function of a = 1/(m_w tan(theta)):
///
///     Lambda(a) = (erf(a) - 1)/2 + exp(-a^2) / (2 a sqrt(pi))
///               = (exp(-a^2) / (a sqrt(pi)) - erfc(a)) / 2
///
/// (Heitz 2014, JCGT 3(2), sec. 5, the Beckmann Lambda; Walter et al. 2007, eq. 26 is the
/// G1 = 1/(1 + Lambda) it gives). For large a both terms are tiny and nearly equal, so
/// Lambda loses relative (not absolute) accuracy there; G1 = 1/(1 + Lambda) does not
/// notice. Clamped at 0 against that rounding. a = 0 (grazing) gives +infinity.
template <std::floating_point T>
[[nodiscard]] inline T lambda_beckmann_of_a(T a) noexcept {
    constexpr T inv_sqrt_pi = std::numbers::inv_sqrtpi_v<T>;
    if (!(a > T(0))) return infinity<T>;
    const T value = T(0.5) * (std::exp(-a * a) * inv_sqrt_pi / a - std::erfc(a));
    return value > T(0) ? value : T(0);
}

/// Walter et al. 2007, eq. 27: the rational approximation of the Smith-Beckmann G1 as a
/// function of a = 1/(m_w tan(theta)): (3.535 a + 2.181 a^2) / (1 + 2.276 a + 2.577 a^2)
/// for a < 1.6, else 1.
template <std::floating_point T>
[[nodiscard]] constexpr T G1_beckmann_rational_of_a(T a) noexcept {
    if (!(a < T(1.6))) return T(1);
    return (T(3.535) * a + T(2.181) * a * a) / (T(1) + T(2.276) * a + T(2.577) * a * a);
}

/// a = |w_z| / sqrt(m_x^2 w_x^2 + m_y^2 w_y^2) = 1 / (m_w |tan(theta)|), with m_w the RMS
/// slope projected on w's azimuth (Heitz 2014, JCGT 3(2), eq. 80); the same for w and its
/// mirror image below the surface. +infinity at w = n.
template <std::floating_point T>
[[nodiscard]] inline T beckmann_a(const vec3<T>& w, T m_x, T m_y) noexcept {
    const T q = sqr(m_x * w.x) + sqr(m_y * w.y);
    if (!(q > T(0))) return infinity<T>;
    return std::abs(w.z) / std::sqrt(q);
}

/// K(x) = (sqrt(pi)/2) erfc(-x) + (k/2) exp(-x^2): 1/cot(theta) times the cumulative
/// distribution, up to slope x, of the visible slopes of the standard Beckmann surface
/// (m = 1) seen at tan(theta) = k: integral from -inf to x of (1 - k t) exp(-t^2) dt. Its
/// derivative (1 - k x) exp(-x^2) is > 0 for x < 1/k.
template <std::floating_point T>
[[nodiscard]] inline T beckmann_visible_slope_cdf(T x, T k) noexcept {
    constexpr T half_sqrt_pi = T(0.5) / std::numbers::inv_sqrtpi_v<T>;
    return half_sqrt_pi * std::erfc(-x) + T(0.5) * k * std::exp(-x * x);
}

/// The slope x in [-9, min(1/k, 9)] with K(x) = u K(x_max) (K as above): the visible
/// slope, along the view's azimuth, of the standard Beckmann surface seen at
/// tan(theta) = k >= 0, for u uniform in [0,1). k = 0 (normal view) gives the normal
/// distribution with variance 1/2 (then x = erfinv(2u - 1)).
///
/// Heitz, d'Eon 2014, "Importance Sampling Microfacet-Based BSDFs using the Distribution
/// of Visible Normals", EGSR, sec. 4 and appendix (the visible-slope density
/// (1 - k x) exp(-x^2) for x < 1/k, up to a constant), and Jakob 2014, "An Improved Visible
/// Normal Sampling Routine for the Beckmann Distribution" (inverting its CDF by Newton's
/// method inside a shrinking bracket). Here Newton runs on x itself, corrected to Halley's
/// step near the root (x - 2 r K' / (2 K'^2 - r K'') for the residual r; Scavo and Thoo
/// 1995, "On the Geometry of Halley's Method", American Mathematical Monthly 102(5), which
/// derives this iteration), started from Winitzki's approximation of erfinv(2u - 1)
/// (Winitzki 2008, "A handy approximation for the error function and its inverse",
/// a = 0.147), with a bisection step whenever the step would leave the bracket, until the
/// step is below a few ulps of x or the residual |K(x) - u K(x_max)| is within 2 epsilon
/// of K(x_max), the rounding of K itself, beyond which no step can make the drawn quantile
/// more accurate.
/// The bracket [-9, 9] loses a mass below exp(-81) ~ 7e-36 (smaller than any u > 0 that
/// float can pass in the valid range) and keeps exp(-x^2) finite and non-zero.
template <std::floating_point T>
[[nodiscard]] inline T beckmann_visible_slope(T k, T u) noexcept {
    constexpr T limit = T(9);
    T lo = -limit;
    T hi = k > T(1) / limit ? T(1) / k : limit;
    // K(9) at k = 0 is (sqrt(pi)/2) erfc(-9), which rounds to sqrt(pi) (erfc(-9) = 2 - 4e-37):
    // the same number as 2 (0.5/inv_sqrtpi), the cdf's own constant doubled.
    const T total = k > T(0) ? beckmann_visible_slope_cdf(hi, k) : T(1) / std::numbers::inv_sqrtpi_v<T>;
    const T target = u * total;
    const T resolution = T(2) * std::numeric_limits<T>::epsilon() * total;
    // Winitzki's erfinv(y), y = 2u - 1, 1 - y^2 = 4 u (1 - u).
    const T one_minus_y2 = T(4) * u * (T(1) - u);
    T x = T(0);
    if (one_minus_y2 > T(0)) {
        constexpr T a = T(0.147);
        const T ln = std::log(one_minus_y2);
        const T b = T(2) / (pi<T> * a) + T(0.5) * ln;
        x = std::copysign(safe_sqrt(std::sqrt(b * b - ln / a) - b), u - T(0.5));
    }
    if (!(x > lo && x < hi)) x = T(0.5) * (lo + hi);
    for (int i = 0; i < 64; ++i) {
        const T value = beckmann_visible_slope_cdf(x, k) - target;
        if (value > T(0))
            hi = x;
        else if (value < T(0))
            lo = x;
        else
            return x;
        if (std::abs(value) <= resolution) return x;
        // Newton's step r / K' on the residual r, with K' = (1 - k x) exp(-x^2), corrected
        // to Halley's (r / K') / (1 - t), t = r K'' / (2 K'^2), once t is small (near the
        // root, where Halley converges cubically);
        // K'' = -(k + 2 x (1 - k x)) exp(-x^2) shares the exponential.
        const T e = std::exp(-x * x);
        const T slope = (T(1) - k * x) * e;
        const T newton = value / slope;
        const T t = newton * (-(k + T(2) * x * (T(1) - k * x)) * e) / (T(2) * slope);
        T next = std::abs(t) < T(0.25) ? x - newton / (T(1) - t) : x - newton;
        if (!(next > lo && next < hi)) next = T(0.5) * (lo + hi);
        const T step = std::abs(next - x);
        x = next;
        if (step <= T(4) * std::numeric_limits<T>::epsilon() * glm::max(std::abs(x), T(1))) break;
    }
    return x;
}

} // namespace detail

/// Smith's Lambda for the anisotropic Beckmann distribution, direction w in the local frame
/// (see detail::lambda_beckmann_of_a; a = w_z / sqrt(m_x^2 w_x^2 + m_y^2 w_y^2), Heitz 2014,
/// JCGT 3(2), eq. 80). Returns Lambda >= 0; 0 at w = n. Two-sided: a direction below the
/// surface has the Lambda of its mirror image; +infinity on the horizon, w_z = 0.
template <std::floating_point T>
[[nodiscard]] inline T Lambda_beckmann(const vec3<T>& w, T m_x, T m_y) noexcept {
    if (!(std::abs(w.z) > T(0))) return infinity<T>;
    const T a = detail::beckmann_a(w, m_x, m_y);
    if (!(a < infinity<T>)) return T(0);
    return detail::lambda_beckmann_of_a(a);
}

/// Smith masking for the Beckmann distribution, isotropic, rational approximation.
///
/// Smith 1967, "Geometrical shadowing of a random rough surface", IEEE Trans. Antennas
/// Propag. 15(5); the approximation of Walter et al. 2007 (EGSR), eq. 27:
///
///     a = cos(theta) / (m sin(theta))
///     G1 = (3.535 a + 2.181 a^2) / (1 + 2.276 a + 2.577 a^2)   if a < 1.6,   else 1
///
/// n_dot_w = cos(theta) of the direction w (l or v) with the normal; m as in D_beckmann.
/// Returns G1 in [0, 1]; 1 at n_dot_w = 1; two-sided, G1(-n_dot_w) = G1(n_dot_w) (c = |n·w|),
/// 0 on the horizon. (The approximation departs from the exact erf form,
/// G1_smith_beckmann_exact, by well under 1%.)
template <std::floating_point T>
[[nodiscard]] inline T G1_smith_beckmann(T n_dot_w, T m) noexcept {
    const T c = glm::min(std::abs(n_dot_w), T(1));
    if (!(c > T(0))) return T(0);
    const T s = std::sqrt((T(1) - c) * (T(1) + c));
    // a >= 1.6 (including s = 0, where a would be +inf) gives exactly 1.
    if (!(m * s * T(1.6) > c)) return T(1);
    const T a = c / (m * s);
    return (T(3.535) * a + T(2.181) * a * a) / (T(1) + T(2.276) * a + T(2.577) * a * a);
}

/// Smith masking for the Beckmann distribution, isotropic, exact (erf form).
///
/// Walter et al. 2007 (EGSR), eq. 26, G1 = 2 / (1 + erf(a) + exp(-a^2) / (a sqrt(pi))),
/// which is 1/(1 + Lambda(a)) with the Beckmann Lambda of Heitz 2014 (JCGT 3(2), sec. 5);
/// a = cos(theta) / (m sin(theta)). n_dot_w = cos(theta). Returns G1 in [0, 1]; 1 at
/// n_dot_w = 1; two-sided, G1(-n_dot_w) = G1(n_dot_w), 0 on the horizon.
template <std::floating_point T>
[[nodiscard]] inline T G1_smith_beckmann_exact(T n_dot_w, T m) noexcept {
    const T c = glm::min(std::abs(n_dot_w), T(1));
    if (!(c > T(0))) return T(0);
    const T s = std::sqrt((T(1) - c) * (T(1) + c));
    if (!(s > T(0))) return T(1);
    return T(1) / (T(1) + detail::lambda_beckmann_of_a(c / (m * s)));
}

/// Distribution term type: Beckmann, isotropic (one RMS slope m) or anisotropic (m_x along
/// the tangent t, m_y along the bitangent b). Its Lambda and G1 are the exact (erf) Smith
/// terms; the rational approximation is shade::smith_beckmann. Satisfies
/// shade::sampled_microfacet_distribution.
template <std::floating_point T>
class beckmann {
public:
    using scalar_type = T;

    /// Isotropic, m_x = m_y = m. Throws shade::invalid_parameter naming "m" unless m is in
    /// [1e-4, 1e4].
    explicit beckmann(T m) : m_x_(detail::require_microfacet_parameter("m", m)), m_y_(m) {}

    /// Anisotropic. Throws shade::invalid_parameter naming "m_x" or "m_y" unless each is
    /// in [1e-4, 1e4].
    beckmann(T m_x, T m_y)
        : m_x_(detail::require_microfacet_parameter("m_x", m_x)),
          m_y_(detail::require_microfacet_parameter("m_y", m_y)) {}

    /// Unchecked, isotropic: the caller guarantees m in [1e-4, 1e4].
    constexpr beckmann(unchecked_t, T m) noexcept : m_x_(m), m_y_(m) {}

    /// Unchecked, anisotropic: the caller guarantees m_x, m_y in [1e-4, 1e4].
    constexpr beckmann(unchecked_t, T m_x, T m_y) noexcept : m_x_(m_x), m_y_(m_y) {}

    /// The RMS slope m of an isotropic distribution; for an anisotropic one, m_x.
    [[nodiscard]] constexpr T m() const noexcept { return m_x_; }
    [[nodiscard]] constexpr T m_x() const noexcept { return m_x_; } ///< RMS slope along t
    [[nodiscard]] constexpr T m_y() const noexcept { return m_y_; } ///< RMS slope along b
    /// True when m_x == m_y.
    [[nodiscard]] constexpr bool isotropic() const noexcept { return m_x_ == m_y_; }

    /// D in 1/sr from the cosine of the half angle (see D_beckmann(n_dot_h, m)), with m_x:
    /// the isotropic distribution, or for an anisotropic one D of a normal in the t-n plane.
    [[nodiscard]] T D(T n_dot_h) const noexcept { return D_beckmann(n_dot_h, m_x_); }

    /// D(m) in 1/sr of a unit microfacet normal in the local frame: D_beckmann(m, m_x, m_y),
    /// the same number, from the reciprocals computed at construction.
    [[nodiscard]] T D(const vec3<T>& m) const noexcept {
        return detail::D_beckmann_from_reciprocals(m, inv_m_x_, inv_m_y_, inv_pi_m_xy_);
    }

    /// Smith's Lambda of the local direction w, exact (see Lambda_beckmann).
    [[nodiscard]] T Lambda(const vec3<T>& w) const noexcept { return Lambda_beckmann(w, m_x_, m_y_); }

    /// Smith masking G1(w) = 1/(1 + Lambda(w)) of the local direction w, in [0, 1] (either
    /// side: the value of |w_z|; 0 on the horizon).
    [[nodiscard]] T G1(const vec3<T>& w) const noexcept { return T(1) / (T(1) + Lambda(w)); }

    /// Smith masking of the microfacet normal m seen from w, either side (see
    /// shade::detail::G1_of_normal): G1(w) when w·m has the sign of w_z, else 0. In [0, 1].
    [[nodiscard]] T G1(const vec3<T>& w, const vec3<T>& m) const noexcept { return detail::G1_of_normal(*this, w, m); }

    /// The largest value of D over all m. Along an azimuth phi the distribution is the
    /// isotropic one with slope s(phi) (1/s^2 = cos^2(phi)/m_x^2 + sin^2(phi)/m_y^2) times
    /// s^2/(m_x m_y); the isotropic peak P(s) is 1/(pi s^2) if s^2 <= 1/2 (at h = n), else
    /// 4 s^2 exp(1/s^2 - 2)/pi (where 1/cos^2(theta_h) = 2 s^2; from d/dx of
    /// x^2 exp(-(x - 1)/s^2) = 0 with x = 1/cos^2). s^2 P(s) does not decrease with s, so
    /// the peak is s^2 P(s) / (m_x m_y) at s = max(m_x, m_y).
    [[nodiscard]] T peak() const noexcept {
        const T s = glm::max(m_x_, m_y_);
        const T s2 = s * s;
        if (s2 <= T(0.5)) return T(1) / (pi<T> * m_x_ * m_y_);
        return (T(4) * s2 / (pi<T> * m_x_)) * (s2 / m_y_) * std::exp(T(1) / s2 - T(2));
    }

    /// The parameter that sets the peak (used by error messages): "m" when isotropic (or both
    /// NaN), else the smaller of "m_x" and "m_y".
    [[nodiscard]] constexpr std::string_view peak_parameter() const noexcept {
        // (NaN == NaN is false: an unchecked isotropic NaN still names "m".)
        if (m_x_ == m_y_ || (m_x_ != m_x_ && m_y_ != m_y_)) return "m";
        return m_x_ < m_y_ ? "m_x" : "m_y";
    }

    /// A microfacet normal (local frame) drawn from the distribution of normals visible
    /// from w, D_w(m) = G1(w) max(0, w·m) D(m) / w_z (shade::D_visible), for u uniform in
    /// [0,1)^2. Precondition: w unit, w_z > 0. Returns a unit m with m_z > 0.
    ///
    /// Heitz, d'Eon 2014, "Importance Sampling Microfacet-Based BSDFs using the Distribution
    /// of Visible Normals", EGSR, sec. 4: stretch w by (m_x, m_y, 1) to the standard
    /// surface (m = 1), draw its visible slopes (x along the view's azimuth with density
    /// proportional to (1 - x tan(theta)) exp(-x^2), detail::beckmann_visible_slope; y
    /// normal with variance 1/2, independent), rotate them to the view's azimuth, unstretch
    /// by (m_x, m_y) and return the normal (-x, -y, 1)/|.| of those slopes.
    [[nodiscard]] vec3<T> sample_visible_normal(const vec3<T>& w, const vec2<T>& u) const noexcept {
        const vec3<T> w_s = glm::normalize(vec3<T>(m_x_ * w.x, m_y_ * w.y, w.z));
        const T sin_theta = std::sqrt(w_s.x * w_s.x + w_s.y * w_s.y);
        const T cos_phi = sin_theta > T(0) ? w_s.x / sin_theta : T(1);
        const T sin_phi = sin_theta > T(0) ? w_s.y / sin_theta : T(0);
        const T x = detail::beckmann_visible_slope(sin_theta / w_s.z, u.x);
        // y is normal: the k = 0 case, drawn in the lower half and mirrored so that the
        // tail u_y -> 1 keeps the accuracy of the tail u_y -> 0 (1 - u_y is exact there).
        const T y_half = detail::beckmann_visible_slope(T(0), glm::min(u.y, T(1) - u.y));
        const T y = u.y < T(0.5) ? y_half : -y_half;
        const T slope_x = m_x_ * (cos_phi * x - sin_phi * y);
        const T slope_y = m_y_ * (sin_phi * x + cos_phi * y);
        return glm::normalize(vec3<T>(-slope_x, -slope_y, T(1)));
    }

private:
    T m_x_;
    T m_y_;
    // Reciprocals used by D(m); set from the slopes by every constructor.
    T inv_m_x_ = T(1) / m_x_;
    T inv_m_y_ = T(1) / m_y_;
    T inv_pi_m_xy_ = T(1) / (pi<T> * m_x_ * m_y_);
};

} // namespace shade
