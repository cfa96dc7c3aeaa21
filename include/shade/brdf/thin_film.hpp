#pragma once
// Thin-film interference (iridescence): the reflectance of a smooth dielectric film a few
// hundred nanometres thick on a dielectric or conductor base, integrated over the visible
// spectrum into RGB by Belcour and Barla's Fourier method. It is the thin film of OpenPBR
// Surface (thin_film_thickness, thin_film_ior) and acts as the Fresnel term of a
// microfacet model, evaluated per microfacet:
//
//   const auto film = thin_film_fresnel<T>::over_conductor(eta, kappa, 1.4, 500);   // 500 nm
//   cook_torrance<ggx<T>, thin_film_fresnel<T>, smith_height_correlated<T>> model(ggx<T>(0.2), film);
//
// Not part of shade/shade.hpp: include this header where it is used.

#include <cmath>
#include <concepts>
#include <numbers>

#include <glm/common.hpp>

#include <shade/brdf/brdf.hpp>
#include <shade/core/error.hpp>
#include <shade/core/types.hpp>

namespace shade {

namespace detail {

/// The few complex operations thin_film_reflectance needs (<complex> alone would take this
/// header past its preprocessed-line budget).
struct film_complex {
    double re = 0, im = 0;

    friend film_complex operator+(film_complex a, film_complex b) noexcept { return {a.re + b.re, a.im + b.im}; }
    friend film_complex operator-(film_complex a, film_complex b) noexcept { return {a.re - b.re, a.im - b.im}; }
    friend film_complex operator*(film_complex a, film_complex b) noexcept {
        return {a.re * b.re - a.im * b.im, a.re * b.im + a.im * b.re};
    }
    friend film_complex operator*(double s, film_complex a) noexcept { return {s * a.re, s * a.im}; }
    friend film_complex operator/(film_complex a, film_complex b) noexcept {
        const double d = b.re * b.re + b.im * b.im;
        return {(a.re * b.re + a.im * b.im) / d, (a.im * b.re - a.re * b.im) / d};
    }
    [[nodiscard]] double norm() const noexcept { return re * re + im * im; } ///< |z|^2
    [[nodiscard]] double arg() const noexcept { return std::atan2(im, re); } ///< in (-pi, pi]
};

/// The principal square root (Re >= 0; Im >= 0 on the negative real axis), in the form that
/// does not cancel: for Re z >= 0, a = sqrt((|z| + Re z) / 2) and b = Im z / (2 a); else
/// b = sqrt((|z| - Re z) / 2) with Im z's sign and a = Im z / (2 b).
inline film_complex film_sqrt(film_complex z) noexcept {
    const double r = std::hypot(z.re, z.im);
    if (r == 0) return {};
    if (z.re >= 0) {
        const double a = std::sqrt(0.5 * (r + z.re));
        return {a, z.im / (2 * a)};
    }
    const double b = std::copysign(std::sqrt(0.5 * (r - z.re)), z.im == 0 ? 1.0 : z.im);
    return {z.im / (2 * b), b};
}

/// Belcour, Barla 2017's Gaussian fit of the Fourier transform of the CIE 1931 colour
/// matching functions (their supplemental code, "evalSensitivity"): with phase = 2 pi opd
/// (opd in metres), S_k(opd, shift) = sum_j a_j sqrt(2 pi v_j) cos(p_j phase + shift)
/// exp(-v_j phase^2), one Gaussian for Y and Z and two for X. Returned per channel (X, Y, Z)
/// divided by its value at opd = 0, shift = 0, so that a flat spectrum keeps its value
/// (their code divides the three by one constant, 1.0685e-7, which the three values at 0
/// match to 0.1 %).
inline glm::dvec3 thin_film_sensitivity(double opd, double shift) noexcept {
    constexpr double two_pi = 2 * std::numbers::pi;
    const double phase = two_pi * opd;
    const auto lobe = [&](double a, double p, double v) {
        return a * std::sqrt(two_pi * v) * std::cos(p * phase + shift) * std::exp(-v * phase * phase);
    };
    const auto at_zero = [&](double a, double v) { return a * std::sqrt(two_pi * v); };
    const double x = lobe(5.4856e-13, 1.6810e+06, 4.3278e+09) + lobe(9.7470e-14, 2.2399e+06, 4.5282e+09);
    const double y = lobe(4.4201e-13, 1.7953e+06, 9.3046e+09);
    const double z = lobe(5.2481e-13, 2.2084e+06, 6.6121e+09);
    return {x / (at_zero(5.4856e-13, 4.3278e+09) + at_zero(9.7470e-14, 4.5282e+09)), y / at_zero(4.4201e-13, 9.3046e+09),
            z / at_zero(5.2481e-13, 6.6121e+09)};
}

/// XYZ to the linear RGB of the CIE 1931 primaries (700, 546.1, 435.8 nm) with the
/// equal-energy white E, the space Belcour and Barla's reference code returns (the matrix
/// of Wyszecki, Stiles 1982, "Color Science", 2nd ed., to 7 digits, each row divided by its
/// sum): every row sums to 1, so X = Y = Z maps to a grey of the same value.
inline glm::dvec3 xyz_to_cie_rgb(const glm::dvec3& c) noexcept {
    const auto row = [&](double x, double y, double z) { return (x * c.x + y * c.y + z * c.z) / (x + y + z); };
    return {row(2.3706743, -0.9000405, -0.4706338), row(-0.5138850, 1.4253036, 0.0885814),
            row(0.0052982, -0.0146949, 1.0093968)};
}

} // namespace detail

/// The reflectance of a thin film: light in a medium of index n_1 (eta_outside) meets a
/// smooth film of index n_2 (film_ior) and thickness d (thickness_nm, in nanometres) over
/// a base of complex index n_3 + i kappa_3 per channel (base_eta, base_kappa; kappa_3 = 0 for
/// a dielectric), at cos_theta = cos(theta_1) of the incident direction with the film's
/// normal.
///
/// Belcour, Barla 2017, "A Practical Extension to Microfacet Theory for the Modeling of
/// Varying Iridescence", ACM ToG 36(4): the Airy reflectance of the film (their eq. 3),
///
///     R(lambda) = |(r_12 + r_23 e^{i delta}) / (1 + r_12 r_23 e^{i delta})|^2,
///     delta = 2 pi OPD / lambda,   OPD = 2 n_2 d cos(theta_2),
///
/// for each polarization (s and p, averaged), written as the Fourier series in delta
/// (their eqs. 6-8: R = C_0 + 2 sum_{m >= 1} C_m cos(m (delta + phi_23 + phi_21))), with
///
///     C_0 = R_12 + T_121^2 R_23 / (1 - R_12 R_23),   C_m = (C_0 - R_12 - T_121) r_123^m,
///     R_ij = |r_ij|^2,  T_121 = 1 - R_12,  r_123 = sqrt(R_12 R_23),
///
/// phi_21 the phase of r_21 = -r_12 (0 or pi) and phi_23 the phase of r_23 (from the complex
/// Fresnel amplitudes; Born, Wolf 1999, "Principles of Optics", 7th ed., sec. 1.5.2 and
/// 14.2), and each cos(m ...) integrated against the CIE 1931 colour matching functions in
/// closed form (their sec. 4.2: the Gaussian fit of detail::thin_film_sensitivity, which
/// also removes the fringes finer than the eye resolves), then XYZ to RGB
/// (detail::xyz_to_cie_rgb). The series is summed until its terms fall below 1e-10 (at
/// most 256 terms). Checked in the tests against the spectral integral of the Airy formula
/// itself.
///
/// A coloured base (a metal's index per RGB channel) has no spectrum here: channel k of the
/// result is channel k of the film over a grey base of channel k's index. Belcour and
/// Barla's code instead pairs the base's k-th index with the k-th XYZ sensitivity, which
/// mixes channels: with no film it does not give back the base's own reflectance (0.02 off
/// for gold at cos 0.2, 1 instead of 0.98 at cos 0.05); this form does, at three times the
/// cost.
///
/// Returns the reflectance (dimensionless) per RGB channel, clamped to [0, 1] (a saturated
/// fringe can map just outside the RGB gamut). d = 0 gives the Fresnel reflectance of the
/// n_1 / n_3 interface; a film far thicker than the coherence of visible light gives the
/// incoherent sum C_0. Light that the film's top interface reflects totally (n_1 > n_2,
/// sin(theta_1) > n_2 / n_1) returns 1. cos_theta is clamped to [0, 1]. The caller
/// guarantees finite indices > 0, kappa >= 0 and d >= 0 (thin_film_fresnel validates them).
template <std::floating_point T>
[[nodiscard]] inline rgb<T> thin_film_reflectance(T cos_theta, T eta_outside, T film_ior, T thickness_nm,
                                                  const rgb<T>& base_eta, const rgb<T>& base_kappa) noexcept {
    using complex = detail::film_complex;
    const double n1 = double(eta_outside), n2 = double(film_ior), d = double(thickness_nm) * 1e-9;
    const double cos1 = glm::clamp(double(cos_theta), 0.0, 1.0);
    const double sin1_sq = (1 - cos1) * (1 + cos1);
    const double sin2_sq = (n1 / n2) * (n1 / n2) * sin1_sq;
    if (sin2_sq >= 1) return rgb<T>(1);
    const double cos2 = std::sqrt(1 - sin2_sq);
    // Top interface (real amplitudes; p in the convention (n_t cos_i - n_i cos_t) / (...)).
    const double r12[2] = {(n1 * cos1 - n2 * cos2) / (n1 * cos1 + n2 * cos2),
                           (n2 * cos1 - n1 * cos2) / (n2 * cos1 + n1 * cos2)};
    const double opd = 2 * n2 * d * cos2;
    // The film over a grey base of channel k's index, in RGB (channel k of the result is
    // channel k of this; see the function's comment).
    const auto film_over = [&](int k) {
        // Bottom interface: n_3 cos(theta_3) = sqrt(n_3^2 - n_2^2 sin^2(theta_2)) on the
        // principal branch (Im >= 0: a wave that decays into an absorbing base, or the
        // evanescent wave past the film/base critical angle).
        const complex n3{double(base_eta[k]), double(base_kappa[k])};
        const complex n3_cos3 = detail::film_sqrt(n3 * n3 - complex{n2 * n2 * sin2_sq, 0});
        const complex n2_cos2{n2 * cos2, 0};
        const complex r23s[2] = {(n2_cos2 - n3_cos3) / (n2_cos2 + n3_cos3),
                                 (cos2 * (n3 * n3) - n2 * n3_cos3) / (cos2 * (n3 * n3) + n2 * n3_cos3)};
        glm::dvec3 xyz(0);
        for (int pol = 0; pol < 2; ++pol) {
            const double a = r12[pol];
            const double r12_sq = a * a, t121 = 1 - r12_sq;
            const complex r23 = r23s[pol];
            const double r23_sq = r23.norm();
            const double denominator = 1 - r12_sq * r23_sq;
            if (t121 <= 0 || denominator <= 0) {
                xyz += glm::dvec3(0.5); // grazing: the top interface reflects everything
                continue;
            }
            const double c0 = r12_sq + t121 * t121 * r23_sq / denominator;
            const double r123 = std::sqrt(r12_sq * r23_sq);
            const double shift = r23.arg() + (a > 0 ? std::numbers::pi : 0.0); // phi_23 + phi_21
            double c = c0 - r12_sq - t121;
            glm::dvec3 sum(c0);
            for (int m = 1; m <= 256; ++m) {
                c *= r123;
                // Stop when the term is negligible, or when the sensitivity's slowest-decaying
                // Gaussian (variance 4.3278e9) has taken it below that: exp(-v (2 pi m OPD)^2) |c| < 1e-10.
                const double phase = 2 * std::numbers::pi * m * opd;
                if (std::abs(c) < 1e-10 || 4.3278e9 * phase * phase > std::log(std::abs(c) * 1e10)) break;
                sum += 2 * c * detail::thin_film_sensitivity(m * opd, m * shift);
            }
            xyz += 0.5 * sum;
        }
        return detail::xyz_to_cie_rgb(xyz);
    };
    glm::dvec3 result;
    if (base_eta[1] == base_eta[0] && base_eta[2] == base_eta[0] && base_kappa[1] == base_kappa[0] &&
        base_kappa[2] == base_kappa[0])
        result = film_over(0);
    else
        result = {film_over(0).x, film_over(1).y, film_over(2).z};
    const glm::dvec3 rgb_value = glm::clamp(result, glm::dvec3(0), glm::dvec3(1));
    return rgb<T>(rgb_value);
}

/// Fresnel term type: a thin film over a dielectric or a conductor (see
/// thin_film_reflectance), for shade::cook_torrance and the other models that take a
/// Fresnel term. Indices are absolute (or all relative to the same medium): the outside
/// medium's (1 for air), the film's and the base's.
template <std::floating_point T>
class thin_film_fresnel {
public:
    using scalar_type = T;

    /// A film on a conductor of complex index eta + i kappa per channel. Throws
    /// shade::invalid_parameter naming "eta" or "kappa" (as conductor_fresnel's ranges),
    /// "film_ior" or "outside_ior" unless finite and in [1e-4, 1e4], or "thickness_nm" unless
    /// finite and in [0, 1e5].
    [[nodiscard]] static thin_film_fresnel over_conductor(const rgb<T>& eta, const rgb<T>& kappa, T film_ior,
                                                          T thickness_nm, T outside_ior = T(1)) {
        return thin_film_fresnel(require_in_range("eta", eta, T(1e-4), T(1e4)),
                                 require_in_range("kappa", kappa, T(0), T(1e4)), film_ior, thickness_nm, outside_ior);
    }

    /// A film on a dielectric of index base_ior (the same in every channel). Throws
    /// shade::invalid_parameter naming "base_ior" unless finite and in [1e-4, 1e4], and as
    /// over_conductor for the rest.
    [[nodiscard]] static thin_film_fresnel over_dielectric(T base_ior, T film_ior, T thickness_nm,
                                                           T outside_ior = T(1)) {
        return thin_film_fresnel(rgb<T>(require_in_range("base_ior", base_ior, T(1e-4), T(1e4))), rgb<T>(0), film_ior,
                                 thickness_nm, outside_ior);
    }

    [[nodiscard]] constexpr const rgb<T>& base_eta() const noexcept { return base_eta_; }     ///< n_3 per channel
    [[nodiscard]] constexpr const rgb<T>& base_kappa() const noexcept { return base_kappa_; } ///< kappa_3 per channel
    [[nodiscard]] constexpr T film_ior() const noexcept { return film_ior_; }                 ///< n_2
    [[nodiscard]] constexpr T thickness_nm() const noexcept { return thickness_nm_; }         ///< d, nanometres
    [[nodiscard]] constexpr T outside_ior() const noexcept { return outside_ior_; }           ///< n_1

    /// The film's reflectance at cos_theta per channel, dimensionless, in [0, 1].
    [[nodiscard]] rgb<T> F(T cos_theta) const noexcept {
        return thin_film_reflectance(cos_theta, outside_ior_, film_ior_, thickness_nm_, base_eta_, base_kappa_);
    }

private:
    thin_film_fresnel(const rgb<T>& eta, const rgb<T>& kappa, T film_ior, T thickness_nm, T outside_ior)
        : base_eta_(eta), base_kappa_(kappa), film_ior_(require_in_range("film_ior", film_ior, T(1e-4), T(1e4))),
          thickness_nm_(require_in_range("thickness_nm", thickness_nm, T(0), T(1e5))),
          outside_ior_(require_in_range("outside_ior", outside_ior, T(1e-4), T(1e4))) {}

    rgb<T> base_eta_;
    rgb<T> base_kappa_;
    T film_ior_;
    T thickness_nm_;
    T outside_ior_;
};

} // namespace shade
