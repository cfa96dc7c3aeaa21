#pragma once
// shade::ggx: the GGX (Trowbridge-Reitz) microfacet distribution, isotropic or anisotropic,
// with its Smith masking (Lambda, G1) and the sampling of its visible normals; and the
// free functions D_ggx, Lambda_ggx, G1_smith_ggx.
//
// Local frame: n = +z, t = +x, b = +y. alpha_x is the roughness along t, alpha_y along b
// (Walter et al.'s alpha_g when they are equal); not a "perceptual roughness".

#include <cmath>
#include <concepts>
#include <string_view>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <shade/brdf/brdf.hpp>
#include <shade/brdf/microfacet/distribution.hpp>
#include <shade/core/math.hpp>
#include <shade/core/types.hpp>

namespace shade {

/// GGX (Trowbridge-Reitz) distribution, isotropic, from the cosine of the half angle.
///
/// Trowbridge, Reitz 1975, "Average irregularity representation of a rough surface for ray
/// reflection", JOSA 65(5); named GGX in Walter et al. 2007 (EGSR), eq. 33:
///
///     D(h) = alpha^2 / (pi cos^4(theta_h) (alpha^2 + tan^2(theta_h))^2)
///          = alpha^2 / (pi (alpha^2 cos^2(theta_h) + sin^2(theta_h))^2)
///
/// n_dot_h = cos(theta_h); alpha in [1e-4, 1e4]. Returns D in 1/sr; D(n) = 1/(pi alpha^2).
/// Two-sided: a normal below the surface is given the value of its mirror image,
/// D(-n_dot_h) = D(n_dot_h) (the convention of shade/brdf/microfacet/distribution.hpp), and a
/// normal on the horizon (n·h = 0, or NaN) 0. The second form, with sin^2 = (1 - c)(1 + c), has no
/// cancellation for tiny alpha (the usual (alpha^2 - 1) c^2 + 1 rounds to 0 at c = 1 when
/// alpha^2 < float epsilon, giving Inf). A cosine alone cannot give sin^2 to better than
/// the rounding of c near 1 (relative error ~ 6e-8 / sin^2 in float); the local-frame form
/// D_ggx(m, alpha_x, alpha_y) takes sin^2 from the tangent components instead.
template <std::floating_point T>
[[nodiscard]] inline T D_ggx(T n_dot_h, T alpha) noexcept {
    const T c = glm::min(std::abs(n_dot_h), T(1));
    if (!(c > T(0))) return T(0);
    const T a2 = alpha * alpha;
    const T s2 = (T(1) - c) * (T(1) + c);
    const T k = a2 * c * c + s2;
    return a2 / (pi<T> * k * k);
}

namespace detail {

/// D_ggx(m, alpha_x, alpha_y) from the reciprocals 1/alpha_x, 1/alpha_y and
/// 1/(pi alpha_x alpha_y), one division per evaluation (shade::ggx keeps them).
template <std::floating_point T>
[[nodiscard]] inline T D_ggx_from_reciprocals(const vec3<T>& m, T inv_alpha_x, T inv_alpha_y,
                                             T inv_pi_alpha_xy) noexcept {
    if (!(std::abs(m.z) > T(0))) return T(0);
    const T x = m.x * inv_alpha_x;
    const T y = m.y * inv_alpha_y;
    const T k = x * x + y * y + m.z * m.z;
    return inv_pi_alpha_xy / (k * k);
}

} // namespace detail

/// Anisotropic GGX distribution of a microfacet normal m in the local frame.
///
/// Heitz 2014, "Understanding the Masking-Shadowing Function in Microfacet-Based BRDFs",
/// JCGT 3(2), sec. 5 (the anisotropic GGX distribution, obtained by stretching the
/// isotropic one of Walter et al. 2007, eq. 33, by alpha_x and alpha_y):
///
///     D(m) = 1 / (pi alpha_x alpha_y (m_x^2/alpha_x^2 + m_y^2/alpha_y^2 + m_z^2)^2)
///
/// m a unit vector; alpha_x, alpha_y in [1e-4, 1e4]. Returns D in 1/sr; D(n) =
/// 1/(pi alpha_x alpha_y). Two-sided: D(-m) = D(m) (m_z enters squared), 0 for m_z = 0. With alpha_x = alpha_y = alpha it is D_ggx(m_z, alpha),
/// written as 1/(pi alpha^2 (cos^2 + sin^2/alpha^2)^2) with sin^2 = m_x^2 + m_y^2: taken
/// from the tangent components, sin^2 keeps full relative precision near the peak, where
/// 1 - cos^2 is lost to the rounding of cos (in float, cos(1e-3) carries an error up to
/// 3e-8 against 1 - cos = 5e-7, so sin^2 from it is off by up to 6 %, and D with
/// alpha = 0.01 by up to 1e-3).
template <std::floating_point T>
[[nodiscard]] inline T D_ggx(const vec3<T>& m, T alpha_x, T alpha_y) noexcept {
    return detail::D_ggx_from_reciprocals(m, T(1) / alpha_x, T(1) / alpha_y, T(1) / (pi<T> * alpha_x * alpha_y));
}

/// Smith's Lambda for the anisotropic GGX distribution, direction w in the local frame.
///
/// Heitz 2014, JCGT 3(2), eq. 86 (with the projected roughness of eq. 80,
/// alpha_w^2 tan^2(theta) = (alpha_x^2 w_x^2 + alpha_y^2 w_y^2) / w_z^2):
///
///     Lambda(w) = (-1 + sqrt(1 + (alpha_x^2 w_x^2 + alpha_y^2 w_y^2) / w_z^2)) / 2
///
/// evaluated without cancellation as q / (2 c (c + sqrt(c^2 + q))), c = w_z,
/// q = alpha_x^2 w_x^2 + alpha_y^2 w_y^2 (multiply and divide by sqrt(c^2 + q) + c).
/// Returns Lambda >= 0 (dimensionless); 0 at w = n. Two-sided: c = |w_z|, so a direction
/// below the surface has the Lambda of its mirror image (the microsurface seen from the
/// other side); +infinity on the horizon, w_z = 0 (then G1 = 1/(1 + Lambda) = 0).
template <std::floating_point T>
[[nodiscard]] inline T Lambda_ggx(const vec3<T>& w, T alpha_x, T alpha_y) noexcept {
    const T c = std::abs(w.z);
    if (!(c > T(0))) return infinity<T>;
    const T q = sqr(alpha_x * w.x) + sqr(alpha_y * w.y);
    return q / (T(2) * c * (c + std::sqrt(c * c + q)));
}

/// Smith masking for the GGX distribution, isotropic, from the cosine.
///
/// Walter et al. 2007 (EGSR), eq. 34: G1 = 2 / (1 + sqrt(1 + alpha^2 tan^2(theta))),
/// evaluated as the equal 2 c / (c + sqrt(c^2 + alpha^2 (1 - c^2))) with c = cos(theta), which
/// needs no tangent and goes smoothly to 0 as c -> 0 (the tan form overflows there).
/// Returns G1 in [0, 1]; 1 at n_dot_w = 1; two-sided, G1(-n_dot_w) = G1(n_dot_w) (c = |n·w|),
/// 0 on the horizon. (The side test of a microfacet normal m, chi+((w·m)/(w·n)), is
/// ggx::G1(w, m)'s.)
template <std::floating_point T>
[[nodiscard]] inline T G1_smith_ggx(T n_dot_w, T alpha) noexcept {
    const T c = glm::min(std::abs(n_dot_w), T(1));
    if (!(c > T(0))) return T(0);
    const T s2 = (T(1) - c) * (T(1) + c);
    return T(2) * c / (c + std::sqrt(c * c + alpha * alpha * s2));
}

/// Smith masking for the anisotropic GGX distribution, direction w in the local frame:
/// Smith's G1 = 1 / (1 + Lambda_ggx(w)) (Heitz 2014, JCGT 3(2), sec. 5, with Lambda of
/// eq. 86), evaluated as 2 c / (c + sqrt(c^2 + q)) with c and q as in Lambda_ggx (no
/// cancellation, no tangent). Returns G1 in [0, 1]; two-sided as Lambda_ggx (c = |w_z|),
/// 0 on the horizon.
template <std::floating_point T>
[[nodiscard]] inline T G1_smith_ggx(const vec3<T>& w, T alpha_x, T alpha_y) noexcept {
    const T c = std::abs(w.z);
    if (!(c > T(0))) return T(0);
    const T q = sqr(alpha_x * w.x) + sqr(alpha_y * w.y);
    return T(2) * c / (c + std::sqrt(c * c + q));
}

/// Smith's Lambda and G1 of one direction.
template <std::floating_point T>
struct smith_lambda_g1 {
    T lambda; ///< Lambda(w) >= 0
    T g1;     ///< G1(w) = 1 / (1 + Lambda(w)), in [0, 1]
};

/// Lambda_ggx(w, alpha_x, alpha_y) and G1_smith_ggx(w, alpha_x, alpha_y), the same two
/// numbers, from one square root sqrt(c^2 + q) (for a caller that needs both of the view).
template <std::floating_point T>
[[nodiscard]] inline smith_lambda_g1<T> Lambda_and_G1_ggx(const vec3<T>& w, T alpha_x, T alpha_y) noexcept {
    const T c = std::abs(w.z);
    if (!(c > T(0))) return {infinity<T>, T(0)};
    const T q = sqr(alpha_x * w.x) + sqr(alpha_y * w.y);
    const T c_plus_root = c + std::sqrt(c * c + q);
    return {q / (T(2) * c * c_plus_root), T(2) * c / c_plus_root};
}

/// Distribution term type: GGX / Trowbridge-Reitz, isotropic (one alpha) or anisotropic
/// (alpha_x along the tangent t, alpha_y along the bitangent b). Satisfies
/// shade::sampled_microfacet_distribution.
template <std::floating_point T>
class ggx {
public:
    using scalar_type = T;

    /// Isotropic, alpha_x = alpha_y = alpha. Throws shade::invalid_parameter naming
    /// "alpha" unless alpha is in [1e-4, 1e4].
    explicit ggx(T alpha) : alpha_x_(detail::require_microfacet_parameter("alpha", alpha)), alpha_y_(alpha) {}

    /// Anisotropic. Throws shade::invalid_parameter naming "alpha_x" or "alpha_y" unless
    /// each is in [1e-4, 1e4].
    ggx(T alpha_x, T alpha_y)
        : alpha_x_(detail::require_microfacet_parameter("alpha_x", alpha_x)),
          alpha_y_(detail::require_microfacet_parameter("alpha_y", alpha_y)) {}

    /// Unchecked, isotropic: the caller guarantees alpha in [1e-4, 1e4].
    constexpr ggx(unchecked_t, T alpha) noexcept : alpha_x_(alpha), alpha_y_(alpha) {}

    /// Unchecked, anisotropic: the caller guarantees alpha_x, alpha_y in [1e-4, 1e4].
    constexpr ggx(unchecked_t, T alpha_x, T alpha_y) noexcept : alpha_x_(alpha_x), alpha_y_(alpha_y) {}

    /// The parameter alpha of an isotropic distribution (Walter et al.'s alpha_g); for an
    /// anisotropic one, alpha_x.
    [[nodiscard]] constexpr T alpha() const noexcept { return alpha_x_; }
    [[nodiscard]] constexpr T alpha_x() const noexcept { return alpha_x_; } ///< roughness along t
    [[nodiscard]] constexpr T alpha_y() const noexcept { return alpha_y_; } ///< roughness along b
    /// True when alpha_x == alpha_y.
    [[nodiscard]] constexpr bool isotropic() const noexcept { return alpha_x_ == alpha_y_; }

    /// D in 1/sr from the cosine of the half angle (see D_ggx(n_dot_h, alpha)), with
    /// alpha_x: the isotropic distribution, or for an anisotropic one D of a normal in the
    /// t-n plane.
    [[nodiscard]] T D(T n_dot_h) const noexcept { return D_ggx(n_dot_h, alpha_x_); }

    /// D(m) in 1/sr of a unit microfacet normal m in the local frame: D_ggx(m, alpha_x,
    /// alpha_y), the same number, from the reciprocals computed at construction.
    [[nodiscard]] T D(const vec3<T>& m) const noexcept {
        return detail::D_ggx_from_reciprocals(m, inv_alpha_x_, inv_alpha_y_, inv_pi_alpha_xy_);
    }

    /// Smith's Lambda of the local direction w (see Lambda_ggx).
    [[nodiscard]] T Lambda(const vec3<T>& w) const noexcept { return Lambda_ggx(w, alpha_x_, alpha_y_); }

    /// Smith masking G1(w) = 1/(1 + Lambda(w)) of the local direction w, in [0, 1] (either
    /// side: the value of |w_z|).
    [[nodiscard]] T G1(const vec3<T>& w) const noexcept { return G1_smith_ggx(w, alpha_x_, alpha_y_); }

    /// Lambda(w) and G1(w) together (see Lambda_and_G1_ggx): the same numbers.
    [[nodiscard]] smith_lambda_g1<T> Lambda_and_G1(const vec3<T>& w) const noexcept {
        return Lambda_and_G1_ggx(w, alpha_x_, alpha_y_);
    }

    /// Smith masking of the microfacet normal m seen from w, either side (see
    /// shade::detail::G1_of_normal): G1(w) when w·m has the sign of w_z, else 0. In [0, 1].
    [[nodiscard]] T G1(const vec3<T>& w, const vec3<T>& m) const noexcept { return detail::G1_of_normal(*this, w, m); }

    /// The largest value of D over all m: max(alpha_x, alpha_y, 1)^4 / (pi alpha_x alpha_y).
    /// (D's denominator holds the quadratic form m_x^2/alpha_x^2 + m_y^2/alpha_y^2 + m_z^2,
    /// whose minimum over unit m is 1/max(alpha_x, alpha_y, 1)^2: at m = n when both
    /// alphas are <= 1, else at grazing m along the rougher axis. Isotropic: 1/(pi alpha^2)
    /// for alpha <= 1, alpha^2/pi above.)
    [[nodiscard]] T peak() const noexcept {
        const T a = glm::max(glm::max(alpha_x_, alpha_y_), T(1));
        const T a2 = a * a;
        return (a2 / (pi<T> * alpha_x_)) * (a2 / alpha_y_);
    }

    /// The parameter that sets the peak (used by error messages): "alpha" when isotropic
    /// (or both NaN), else the smaller of "alpha_x" and "alpha_y".
    [[nodiscard]] constexpr std::string_view peak_parameter() const noexcept {
        // (NaN == NaN is false: an unchecked isotropic NaN still names "alpha".)
        if (alpha_x_ == alpha_y_ || (alpha_x_ != alpha_x_ && alpha_y_ != alpha_y_)) return "alpha";
        return alpha_x_ < alpha_y_ ? "alpha_x" : "alpha_y";
    }

    /// A microfacet normal (local frame) drawn from the distribution of normals visible
    /// from w, D_w(m) = G1(w) max(0, w·m) D(m) / w_z (shade::D_visible), for u uniform in
    /// [0,1)^2. Precondition: w unit, w_z > 0. Returns a unit m with m_z > 0.
    ///
    /// Dupuy, Benyoub 2023, "Sampling Visible GGX Normals with Spherical Caps", Computer
    /// Graphics Forum 42(8) (HPG), which simplifies Heitz 2018, "Sampling the GGX
    /// Distribution of Visible Normals", JCGT 7(4): stretch w by (alpha_x, alpha_y, 1), where
    /// the GGX microsurface becomes the unit hemisphere; a visible normal of the hemisphere
    /// is the half vector of w_h and a point c drawn uniformly on the spherical cap
    /// c_z >= -w_hz; unstretch that half vector by (alpha_x, alpha_y, 1) and normalize.
    /// With phi = 2 pi u_x and z = (1 - u_y)(1 + w_hz) - w_hz: 1 - z = u_y (1 + w_hz) and
    /// the half vector's z, z + w_hz = (1 - u_y)(1 + w_hz), are computed in these forms,
    /// which have no cancellation (the second is > 0 for u_y < 1).
    [[nodiscard]] vec3<T> sample_visible_normal(const vec3<T>& w, const vec2<T>& u) const noexcept {
        const T phi = T(2) * pi<T> * u.x;
        return visible_normal(stretch(w), u.y, [phi] { return vec2<T>(std::cos(phi), std::sin(phi)); });
    }

    /// The view w stretched into the configuration of sample_visible_normal:
    /// normalize(alpha_x w_x, alpha_y w_y, w_z). Precondition: w_z > 0.
    [[nodiscard]] vec3<T> stretch(const vec3<T>& w) const noexcept {
        return glm::normalize(vec3<T>(alpha_x_ * w.x, alpha_y_ * w.y, w.z));
    }

    /// sample_visible_normal(w, u) from w_h = stretch(w) and cos(2 pi u_x), sin(2 pi u_x):
    /// the same unit normal, for quadratures that visit many u at one view (the stretch and
    /// the cosine and sine of each column computed once).
    [[nodiscard]] vec3<T> sample_visible_normal_stretched(const vec3<T>& w_h, T cos_phi, T sin_phi,
                                                          T u_y) const noexcept {
        return visible_normal(w_h, u_y, [cos_phi, sin_phi] { return vec2<T>(cos_phi, sin_phi); });
    }

private:
    // The body of sample_visible_normal for the stretched view w_h: trig() returns (cos phi,
    // sin phi), called where they are used (after the square root, as the per-sample path
    // schedules best).
    template <class Trig>
    [[nodiscard]] vec3<T> visible_normal(const vec3<T>& w_h, T u_y, const Trig& trig) const noexcept {
        const T one_minus_z = u_y * (T(1) + w_h.z);
        const T h_z = (T(1) - u_y) * (T(1) + w_h.z);
        const T sin_theta = safe_sqrt(one_minus_z * (T(2) - one_minus_z));
        const vec2<T> cs = trig();
        const vec3<T> h(sin_theta * cs.x + w_h.x, sin_theta * cs.y + w_h.y, h_z);
        const vec3<T> m(alpha_x_ * h.x, alpha_y_ * h.y, h.z);
        const T length = glm::length(m);
        // Zero only for u_y = 1, outside the documented domain; n keeps the result a unit vector.
        if (!(length > T(0))) return vec3<T>(0, 0, 1);
        return m / length;
    }

    T alpha_x_;
    T alpha_y_;
    // Reciprocals used by D(m); set from the alphas by every constructor.
    T inv_alpha_x_ = T(1) / alpha_x_;
    T inv_alpha_y_ = T(1) / alpha_y_;
    T inv_pi_alpha_xy_ = T(1) / (pi<T> * alpha_x_ * alpha_y_);
};

} // namespace shade
