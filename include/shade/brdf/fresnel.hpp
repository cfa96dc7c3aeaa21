#pragma once
// Fresnel terms F of the microfacet models and of the smooth interfaces in shade/bsdf:
// Schlick's approximation and the exact unpolarized Fresnel reflectance of a dielectric
// interface and of a conductor (complex index of refraction). Each exists as a function
// (F_schlick, F_dielectric, F_conductor) and as a small term type (schlick<T>,
// dielectric_fresnel<T>, conductor_fresnel<T>) for shade::cook_torrance and
// shade::ashikhmin_shirley; F_dielectric_two_sided takes a signed cosine for light from
// either side of a dielectric. dielectric_fresnel_average is the hemispherical average of
// F_dielectric (E_F of OpenPBR's coat). Measured metals: shade/brdf/metals.hpp.
//
// The argument cos_theta is the cosine between the incident direction and the normal of
// the reflecting (micro)facet, e.g. l·h = v·h in a microfacet model, on either side: a
// negative cosine is light arriving from the side opposite the normal. Schlick's and the
// conductor's reflectance depend on |cos_theta| (a conductor is opaque: only the side the
// light comes from matters); the dielectric's also on the side, through eta, which is the
// index opposite the normal over the index on its side and is inverted for light from the
// other side (pbrt-v4's FrDielectric convention, Pharr, Jakob, Humphreys 2023, "Physically
// Based Rendering", 4th ed., sec. 9.3.2).

#include <cmath>
#include <concepts>
#include <limits>

#include <glm/common.hpp>

#include <shade/brdf/brdf.hpp>
#include <shade/core/error.hpp>
#include <shade/core/math.hpp>
#include <shade/core/quadrature.hpp>
#include <shade/core/types.hpp>

namespace shade {

/// Schlick's approximation of the Fresnel reflectance, per channel.
///
/// Schlick 1994, "An Inexpensive BRDF Model for Physically-based Rendering", Computer
/// Graphics Forum 13(3): 233-246 (the Fresnel approximation):
///
///     F(cos_theta) = f0 + (1 - f0) (1 - cos_theta)^5
///
/// Returns the reflectance (dimensionless, in [f0, 1] per channel for f0 in [0, 1]);
/// F(1) = f0 (normal incidence), F(0) = 1 (grazing). Two-sided: F(-c) = F(c). |cos_theta|
/// is clamped to 1 (a cosine slightly above by rounding would otherwise push F below f0).
template <std::floating_point T>
[[nodiscard]] constexpr rgb<T> F_schlick(const rgb<T>& f0, T cos_theta) noexcept {
    const T c = glm::clamp(cos_theta < T(0) ? -cos_theta : cos_theta, T(0), T(1));
    const T m = T(1) - c;
    const T m2 = m * m;
    const T m5 = m2 * m2 * m;
    return f0 + (rgb<T>(1) - f0) * m5;
}

/// Reflectance at normal incidence of an interface with relative index of refraction
/// eta = eta_t / eta_i: ((eta - 1)/(eta + 1))^2 (e.g. 0.04 for glass, eta = 1.5). The
/// usual way to get Schlick's f0 for a dielectric.
template <std::floating_point T>
[[nodiscard]] constexpr T f0_from_ior(T eta) noexcept {
    return sqr((eta - T(1)) / (eta + T(1)));
}

/// The exact Fresnel reflectance of a dielectric interface for unpolarized light.
///
/// Cook, Torrance 1982, "A Reflectance Model for Computer Graphics", ACM ToG 1(1): 7-24
/// (the Fresnel equation in the form they give it), also Walter, Marschner, Li, Torrance
/// 2007, "Microfacet Models for Refraction through Rough Surfaces", EGSR, eq. 22:
///
///     g = sqrt(eta^2 - 1 + c^2),   c = cos_theta
///     F = 1/2 (g - c)^2/(g + c)^2 (1 + (c (g + c) - 1)^2 / (c (g - c) + 1)^2)
///
/// which is the average of the s- and p-polarized reflectances. eta = eta_t / eta_i is
/// the relative index of refraction (transmitted side over incident side), > 0; eta < 1
/// means light arrives from the denser medium, and when eta^2 - 1 + c^2 < 0 it is totally
/// internally reflected: F = 1. Returns the reflectance in [0, 1]; F(1) = f0_from_ior(eta).
/// cos_theta is clamped to 1 (see F_schlick). eta = 1 (no interface) returns 0, also at
/// c = 0 where the formula would be 0/0.
///
/// Two-sided: eta is the index on the side opposite the normal over the index on its side,
/// and a negative cos_theta is light arriving from the side opposite the normal, for which
/// the relative index is 1/eta: F(cos_theta, eta) = F(-cos_theta, 1/eta) for cos_theta < 0
/// (light leaving glass of eta 1.5 through a normal pointing out is totally reflected
/// beyond the critical angle, sin(theta) > 1/1.5). eta must be > 0.
template <std::floating_point T>
[[nodiscard]] inline T F_dielectric(T cos_theta, T eta) noexcept {
    if (cos_theta < T(0)) {
        cos_theta = -cos_theta;
        eta = T(1) / eta;
    }
    const T c = glm::clamp(cos_theta, T(0), T(1));
    const T g2 = eta * eta - T(1) + c * c;
    if (g2 < T(0)) return T(1); // total internal reflection
    // eta^2 overflows for a huge (valid, finite) eta, e.g. 1e20 in float: then g = inf and
    // a = inf/inf = NaN. F tends to 1 as eta -> inf at every angle (a -> 1, b^2 -> 1).
    if (!(g2 <= std::numeric_limits<T>::max())) return T(1);
    const T g = std::sqrt(g2);
    const T g_plus_c = g + c;
    if (!(g_plus_c > T(0))) return T(0); // g = c = 0 only when eta = 1: no interface
    const T g_minus_c = g - c;
    const T a = g_minus_c / g_plus_c;
    // c (g - c) + 1 > 0: for eta > 1, g > c; for eta < 1 without TIR, c (c - g) < c^2 <= 1.
    // In floating point it is 0 at c = 1 when eta^2 is lost in eta^2 - 1 + c^2 (g = 0;
    // eta < ~2e-4 in float): numerator and denominator then both equal g in exact
    // arithmetic, so b takes its limit 1 instead of 0/0 = NaN.
    const T denominator = c * g_minus_c + T(1);
    const T b = denominator > T(0) ? (c * g_plus_c - T(1)) / denominator : T(1);
    return glm::min(T(0.5) * a * a * (T(1) + b * b), T(1));
}

/// The exact Fresnel reflectance of a dielectric interface seen from either side: for
/// light arriving along w with cos_theta = n·w, where n is the normal pointing outside and
/// eta = n_inside / n_outside (shade's convention for transmission, docs/conventions.md).
/// cos_theta > 0 (w outside) is F_dielectric(cos_theta, eta); cos_theta < 0 (w inside,
/// e.g. a ray leaving glass) is F_dielectric(-cos_theta, 1 / eta), totally internally
/// reflected (1) beyond the critical angle, sin(theta) > 1 / eta for eta > 1. Returns the
/// reflectance in [0, 1]; at cos_theta = 0 (grazing, from either side) it is 1 for
/// eta != 1. eta must be finite and > 0. The same function as F_dielectric, which is
/// two-sided too; this name says so at the call.
template <std::floating_point T>
[[nodiscard]] inline T F_dielectric_two_sided(T cos_theta, T eta) noexcept {
    return cos_theta >= T(0) ? F_dielectric(cos_theta, eta) : F_dielectric(-cos_theta, T(1) / eta);
}

/// The hemispherical (cosine-weighted) average of the exact dielectric Fresnel reflectance,
/// E_F(eta) = 2 integral_0^1 F_dielectric(mu, eta) mu dmu, for any eta > 0. For eta >= 1 by
/// 5-point Gauss-Legendre quadrature on 16 equal intervals (shade/core/quadrature.hpp; F is
/// smooth there: no total internal reflection from the rarer side); for eta < 1 by the
/// relation E_F(eta) = 1 - eta^2 (1 - E_F(1 / eta)) (the light the denser side lets out is
/// what the rarer side lets in, scaled by the solid-angle compression eta^2; e.g. d'Eon 2021,
/// "A Hitchhiker's Guide to Multiple Scattering"). Dimensionless, in [0, 1].
template <std::floating_point T>
[[nodiscard]] inline T dielectric_fresnel_average(T eta) noexcept {
    const double e = double(eta) >= 1 ? double(eta) : 1 / double(eta);
    const double above = gauss_legendre_integral([e](double mu) { return 2 * mu * F_dielectric(mu, e); }, 0, 1, 16);
    const double average = double(eta) >= 1 ? above : 1 - double(eta) * double(eta) * (1 - above);
    return T(glm::clamp(average, 0.0, 1.0));
}

/// The exact Fresnel reflectance of a conductor (complex index of refraction) for
/// unpolarized light.
///
/// Born, Wolf 1999, "Principles of Optics", 7th ed., sec. 14.2 (reflection at an absorbing
/// medium: Snell's law and the Fresnel coefficients hold with the complex index
/// eta_c = eta + i kappa); the same closed form as Pharr, Jakob, Humphreys 2023, "Physically
/// Based Rendering", 4th ed., sec. 9.3.6. With c = cos_theta and s^2 = 1 - c^2 of the
/// incident direction, Snell's law gives eta_c cos(theta_t) = w = sqrt(eta_c^2 - s^2), and
///
///     r_s = (c - w) / (c + w),          r_p = (eta_c^2 c - w) / (eta_c^2 c + w)
///     F   = (|r_s|^2 + |r_p|^2) / 2
///
/// (r_p is (eta_c c - cos(theta_t)) / (eta_c c + cos(theta_t)) multiplied through by
/// eta_c). With eta_c^2 = A + i B (A = eta^2 - kappa^2, B = 2 eta kappa) and w = a + i b
/// (the root with a >= 0; b >= 0 since B >= 0), in real arithmetic:
///
///     |r_s|^2 = ((c - a)^2 + b^2) / ((c + a)^2 + b^2)
///     |r_p|^2 = ((A c - a)^2 + (B c - b)^2) / ((A c + a)^2 + (B c + b)^2)
///
/// At normal incidence (c = 1, w = eta_c) both are ((eta - 1)^2 + kappa^2) /
/// ((eta + 1)^2 + kappa^2); at grazing (c = 0) both are 1; with kappa = 0 this is the
/// dielectric Fresnel of F_dielectric (w real, or w = i b under total internal reflection,
/// where |r_s| = |r_p| = 1). w is the square root of z = A - s^2 + i B taken in the stable
/// form (Re z >= 0: a = sqrt((|z| + Re z)/2), b = B/(2a); Re z < 0: b = sqrt((|z| - Re z)/2),
/// a = B/(2b)), which does not cancel when A - s^2 is large and negative (metals: kappa > eta).
///
/// Two-sided: F(-c) = F(c) (|cos_theta|, clamped to 1). eta > 0 and kappa >= 0 are the real
/// and imaginary parts of the conductor's index relative to the incident medium (eta in
/// [1e-4, 1e4], kappa in [0, 1e4], as conductor_fresnel validates). Returns the reflectance in [0, 1].
/// eta = 1, kappa = 0 at c = 0 (no interface, 0/0) returns 0, as F_dielectric does.
template <std::floating_point T>
[[nodiscard]] inline T F_conductor(T cos_theta, T eta, T kappa) noexcept {
    const T c = glm::clamp(std::abs(cos_theta), T(0), T(1));
    const T s2 = (T(1) - c) * (T(1) + c);
    const T A = (eta - kappa) * (eta + kappa);
    const T B = T(2) * eta * kappa;
    const T re = A - s2;
    const T modulus = std::hypot(re, B);
    T a;
    T b;
    if (re >= T(0)) {
        a = std::sqrt(T(0.5) * (modulus + re));
        b = a > T(0) ? B / (T(2) * a) : T(0);
    } else {
        b = std::sqrt(T(0.5) * (modulus - re));
        a = B / (T(2) * b);
    }
    const T rs_den = sqr(c + a) + b * b;
    if (!(rs_den > T(0))) return T(0); // c = a = b = 0: eta_c = 1 at grazing, no interface
    const T rs = (sqr(c - a) + b * b) / rs_den;
    const T rp_den = sqr(A * c + a) + sqr(B * c + b);
    const T rp = rp_den > T(0) ? (sqr(A * c - a) + sqr(B * c - b)) / rp_den : rs;
    return glm::min(T(0.5) * (rs + rp), T(1));
}

/// Fresnel term type: Schlick's approximation with per-channel f0 (see F_schlick).
template <std::floating_point T>
class schlick {
public:
    using scalar_type = T;

    /// Throws shade::invalid_parameter naming "f0" unless every channel is in [0, 1].
    explicit schlick(const rgb<T>& f0) : f0_(require_in_range("f0", f0, T(0), T(1))) {}

    /// Unchecked: the caller guarantees f0 in [0, 1] per channel.
    constexpr schlick(unchecked_t, const rgb<T>& f0) noexcept : f0_(f0) {}

    /// Schlick's f0 for a dielectric of relative index of refraction eta (see
    /// f0_from_ior). Throws shade::invalid_parameter naming "eta" unless eta is finite and
    /// > 0.
    [[nodiscard]] static schlick from_ior(T eta) {
        return schlick(unchecked, rgb<T>(f0_from_ior(require_positive("eta", eta))));
    }

    /// Reflectance at normal incidence.
    [[nodiscard]] constexpr const rgb<T>& f0() const noexcept { return f0_; }

    /// F(cos_theta) per channel, dimensionless, in [f0, 1]; F(-c) = F(c).
    [[nodiscard]] constexpr rgb<T> F(T cos_theta) const noexcept { return F_schlick(f0_, cos_theta); }

private:
    rgb<T> f0_;
};

/// Fresnel term type: the exact unpolarized dielectric Fresnel reflectance (see
/// F_dielectric), the same in every channel.
template <std::floating_point T>
class dielectric_fresnel {
public:
    using scalar_type = T;

    /// eta = eta_t / eta_i. Throws shade::invalid_parameter naming "eta" unless eta is
    /// finite and > 0.
    explicit dielectric_fresnel(T eta) : eta_(require_positive("eta", eta)) {}

    /// Unchecked: the caller guarantees eta finite and > 0.
    constexpr dielectric_fresnel(unchecked_t, T eta) noexcept : eta_(eta) {}

    /// The relative index of refraction eta_t / eta_i.
    [[nodiscard]] constexpr T eta() const noexcept { return eta_; }

    /// F(cos_theta), dimensionless, in [0, 1], as a grey colour; a negative cos_theta is
    /// light from the side of index ratio 1/eta (see F_dielectric).
    [[nodiscard]] rgb<T> F(T cos_theta) const noexcept { return rgb<T>(F_dielectric(cos_theta, eta_)); }

private:
    T eta_;
};

/// Smallest accepted index of refraction eta = n_inside / n_outside of the dielectrics in
/// shade/bsdf: 1e-4. A refraction scales radiance by up to eta^2 or 1/eta^2 (1e8 at the
/// bounds, finite in float); an eta near 1e-20 would make that weight overflow.
template <std::floating_point T>
inline constexpr T dielectric_eta_min = T(1e-4);

/// Largest accepted index of refraction of the dielectrics in shade/bsdf: 1e4 (see
/// dielectric_eta_min).
template <std::floating_point T>
inline constexpr T dielectric_eta_max = T(1e4);

/// Largest accepted eta and kappa of a conductor: 1e4 (keeps every intermediate of
/// F_conductor, up to (eta^2 + kappa^2)^2 ~ 4e16, finite in float).
template <std::floating_point T>
inline constexpr T conductor_index_max = T(1e4);

/// Smallest accepted eta of a conductor: 1e-4 (eta^2 = 1e-8 stays a normal float, so the
/// reflectance at normal incidence keeps its precision; measured metals in the visible
/// have eta >= 0.03).
template <std::floating_point T>
inline constexpr T conductor_eta_min = T(1e-4);

/// Fresnel term type: the exact unpolarized reflectance of a conductor (see F_conductor)
/// with a complex index of refraction eta + i kappa per RGB channel, relative to the
/// incident medium. shade/brdf/metals.hpp has measured values for a few metals.
template <std::floating_point T>
class conductor_fresnel {
public:
    using scalar_type = T;

    /// Throws shade::invalid_parameter naming "eta" unless every channel of eta lies in
    /// [1e-4, 1e4], or "kappa" unless every channel of kappa lies in [0, 1e4].
    conductor_fresnel(const rgb<T>& eta, const rgb<T>& kappa)
        : eta_(require_in_range("eta", eta, conductor_eta_min<T>, conductor_index_max<T>)),
          kappa_(require_in_range("kappa", kappa, T(0), conductor_index_max<T>)) {}

    /// Unchecked: the caller guarantees eta and kappa in the ranges above.
    constexpr conductor_fresnel(unchecked_t, const rgb<T>& eta, const rgb<T>& kappa) noexcept
        : eta_(eta), kappa_(kappa) {}

    [[nodiscard]] constexpr const rgb<T>& eta() const noexcept { return eta_; }     ///< real part of the index
    [[nodiscard]] constexpr const rgb<T>& kappa() const noexcept { return kappa_; } ///< extinction coefficient

    /// F(cos_theta) per channel, dimensionless, in [0, 1]; F(-c) = F(c).
    [[nodiscard]] rgb<T> F(T cos_theta) const noexcept {
        return rgb<T>(F_conductor(cos_theta, eta_.x, kappa_.x), F_conductor(cos_theta, eta_.y, kappa_.y),
                      F_conductor(cos_theta, eta_.z, kappa_.z));
    }

    /// The reflectance at normal incidence, ((eta - 1)^2 + kappa^2) / ((eta + 1)^2 + kappa^2)
    /// per channel (Schlick's f0 for this conductor).
    [[nodiscard]] rgb<T> f0() const noexcept { return F(T(1)); }

private:
    rgb<T> eta_;
    rgb<T> kappa_;
};

/// X is a Fresnel term over scalar T: `x.F(cos_theta)` returns the reflectance as rgb<T>,
/// each channel in [0, 1].
template <class X, class T>
concept fresnel_term = std::floating_point<T> && requires(const X& x, T c) {
    { x.F(c) } -> std::same_as<rgb<T>>;
};

} // namespace shade
