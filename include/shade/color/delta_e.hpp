#pragma once
// Colour differences between two CIE L*a*b* colours: Delta E*ab (CIE 1976), Delta E*94
// (CIE94) and Delta E00 (CIEDE2000). All three return a dimensionless difference in
// L*a*b* units (about 1 = a just-noticeable difference for Delta E00).
//
// References:
//   - CIE 15:2004, "Colorimetry", 3rd edition, section 8.2.1 (Delta E*ab).
//   - CIE 116-1995, "Industrial colour-difference evaluation" (CIE94).
//   - CIE 142-2001, "Improvement to industrial colour-difference evaluation" (CIEDE2000),
//     implemented after G. Sharma, W. Wu, E. N. Dalal, 2005, "The CIEDE2000 Color-Difference
//     Formula: Implementation Notes, Supplementary Test Data, and Mathematical
//     Observations", Color Research and Application 30(1), 21-30, eqs. (1)-(22).
//
// The two colours must be relative to the same white point. Non-finite input: every
// function is noexcept and propagates NaN; for finite input the result is finite.

#include <cmath>
#include <concepts>

#include <glm/common.hpp>

#include <shade/color/lab.hpp>
#include <shade/core/error.hpp>
#include <shade/core/math.hpp>

namespace shade {

// CIE 15:2004 section 8.2.1: Delta E*ab = sqrt((Delta L*)^2 + (Delta a*)^2 + (Delta b*)^2).
/// Returns the CIE 1976 colour difference Delta E*ab: the Euclidean distance in L*a*b*.
/// Symmetric.
template <std::floating_point T>
[[nodiscard]] inline T delta_e_76(const lab<T>& c1, const lab<T>& c2) noexcept {
    return std::hypot(c1.L - c2.L, c1.a - c2.a, c1.b - c2.b);
}

/// The application-dependent constants of CIE94: k_L (lightness weight, in the denominator)
/// and K_1, K_2 (chroma and hue weighting slopes of S_C = 1 + K_1 C*_1, S_H = 1 + K_2 C*_1).
/// k_C = k_H = 1 as for CIE 116-1995's reference conditions.
template <std::floating_point T>
class cie94_parameters {
public:
    /// Graphic arts, the default (CIE 116-1995): k_L = 1, K_1 = 0.045, K_2 = 0.015.
    [[nodiscard]] static cie94_parameters graphic_arts() noexcept {
        return cie94_parameters(T(1), T(0.045), T(0.015), unchecked{});
    }

    /// Textiles: k_L = 2, K_1 = 0.048, K_2 = 0.014 (the constants tabulated for textile
    /// use of CIE94, where lightness differences are tolerated twice as much).
    [[nodiscard]] static cie94_parameters textiles() noexcept {
        return cie94_parameters(T(2), T(0.048), T(0.014), unchecked{});
    }

    /// Custom constants. Throws shade::invalid_parameter naming "k_L" unless it is finite
    /// and > 0, or "K_1"/"K_2" unless finite and >= 0.
    cie94_parameters(T lightness_weight, T chroma_slope, T hue_slope)
        : k_L_(require_positive("k_L", lightness_weight)),
          K_1_(require_non_negative("K_1", chroma_slope)),
          K_2_(require_non_negative("K_2", hue_slope)) {}

    [[nodiscard]] T k_L() const noexcept { return k_L_; } ///< lightness weight k_L
    [[nodiscard]] T K_1() const noexcept { return K_1_; } ///< chroma slope K_1
    [[nodiscard]] T K_2() const noexcept { return K_2_; } ///< hue slope K_2

private:
    struct unchecked {};
    cie94_parameters(T lightness_weight, T chroma_slope, T hue_slope, unchecked) noexcept
        : k_L_(lightness_weight), K_1_(chroma_slope), K_2_(hue_slope) {}

    T k_L_;
    T K_1_;
    T K_2_;
};

// CIE 116-1995:
//   Delta E*94 = sqrt((Delta L*/(k_L S_L))^2 + (Delta C*_ab/(k_C S_C))^2 + (Delta H*_ab/(k_H S_H))^2)
//   S_L = 1, S_C = 1 + K_1 C*_1, S_H = 1 + K_2 C*_1, k_C = k_H = 1,
//   (Delta H*_ab)^2 = (Delta a*)^2 + (Delta b*)^2 - (Delta C*_ab)^2.
/// Returns the CIE94 colour difference of `sample` from `reference`. NOT symmetric: S_C and
/// S_H use the chroma C*_1 of `reference` (CIE 116-1995 uses the standard's chroma), so
/// put the reference (measured, target) colour first. Default constants: graphic arts.
template <std::floating_point T>
[[nodiscard]] inline T delta_e_94(
    const lab<T>& reference, const lab<T>& sample,
    const cie94_parameters<T>& parameters = cie94_parameters<T>::graphic_arts()) noexcept {
    const T delta_L = reference.L - sample.L;
    const T C_1 = std::hypot(reference.a, reference.b);
    const T C_2 = std::hypot(sample.a, sample.b);
    const T delta_C = C_1 - C_2;
    // (Delta H)^2 >= 0 in exact arithmetic (it is 2 (C_1 C_2 - a_1 a_2 - b_1 b_2)); for two
    // colours of equal hue rounding can make it a tiny negative, which the clamp removes.
    const T delta_a = reference.a - sample.a;
    const T delta_b = reference.b - sample.b;
    const T delta_H_sq = glm::max(T(0), delta_a * delta_a + delta_b * delta_b - delta_C * delta_C);
    const T S_C = T(1) + parameters.K_1() * C_1;
    const T S_H = T(1) + parameters.K_2() * C_1;
    const T term_L = delta_L / parameters.k_L();
    const T term_C = delta_C / S_C;
    return std::sqrt(term_L * term_L + term_C * term_C + delta_H_sq / (S_H * S_H));
}

/// The parametric factors k_L, k_C, k_H of CIEDE2000 (divisors of the lightness, chroma
/// and hue terms). All 1 under the CIE 142-2001 reference conditions (the default).
template <std::floating_point T>
class ciede2000_weights {
public:
    /// k_L = k_C = k_H = 1.
    ciede2000_weights() noexcept = default;

    /// Custom weights. Throws shade::invalid_parameter naming "k_L", "k_C" or "k_H" unless
    /// it is finite and > 0.
    ciede2000_weights(T lightness, T chroma, T hue)
        : k_L_(require_positive("k_L", lightness)),
          k_C_(require_positive("k_C", chroma)),
          k_H_(require_positive("k_H", hue)) {}

    [[nodiscard]] T k_L() const noexcept { return k_L_; } ///< lightness weight k_L
    [[nodiscard]] T k_C() const noexcept { return k_C_; } ///< chroma weight k_C
    [[nodiscard]] T k_H() const noexcept { return k_H_; } ///< hue weight k_H

private:
    T k_L_ = T(1);
    T k_C_ = T(1);
    T k_H_ = T(1);
};

namespace detail {

// C^7 / (C^7 + 25^7) written as 1 / (1 + (25/C)^7): the same value, but it cannot overflow
// to inf/inf = NaN for large C, and C = 0 gives 1/(1 + inf) = 0 without a division by zero
// producing NaN.
template <std::floating_point T>
[[nodiscard]] inline T chroma_7_ratio(T C) noexcept {
    if (!(C > T(0))) return T(0);
    const T q = T(25) / C;
    const T q2 = q * q;
    return T(1) / (T(1) + q2 * q2 * q2 * q);
}

} // namespace detail

// CIEDE2000 after Sharma, Wu & Dalal 2005, eqs. (1)-(22):
//  Step 1  C*_i = sqrt(a*_i^2 + b*_i^2), C-bar = (C*_1 + C*_2)/2            (2), (3)
//          G = 0.5 (1 - sqrt(C-bar^7 / (C-bar^7 + 25^7)))                   (4)
//          a'_i = (1 + G) a*_i, C'_i = sqrt(a'_i^2 + b*_i^2)                (5), (6)
//          h'_i = atan2(b*_i, a'_i) in [0, 360), and 0 when a'_i = b*_i = 0 (7)
//  Step 2  Delta L' = L*_2 - L*_1, Delta C' = C'_2 - C'_1                   (8), (9)
//          Delta h' = 0 if C'_1 C'_2 = 0; else h'_2 - h'_1 brought into
//          [-180, 180] by adding or subtracting 360                         (10)
//          Delta H' = 2 sqrt(C'_1 C'_2) sin(Delta h'/2)                     (11)
//  Step 3  L-bar' and C-bar' the arithmetic means                           (12), (13)
//          h-bar' = h'_1 + h'_2 if C'_1 C'_2 = 0; (h'_1 + h'_2)/2 if |h'_1 - h'_2| <= 180;
//          else (h'_1 + h'_2 +- 360)/2, + when h'_1 + h'_2 < 360            (14)
//          T = 1 - 0.17 cos(h-bar' - 30) + 0.24 cos(2 h-bar')
//                + 0.32 cos(3 h-bar' + 6) - 0.20 cos(4 h-bar' - 63)         (15)
//          Delta theta = 30 exp(-((h-bar' - 275)/25)^2)                     (16)
//          R_C = 2 sqrt(C-bar'^7 / (C-bar'^7 + 25^7))                       (17)
//          S_L = 1 + 0.015 (L-bar' - 50)^2 / sqrt(20 + (L-bar' - 50)^2)      (18)
//          S_C = 1 + 0.045 C-bar', S_H = 1 + 0.015 C-bar' T                 (19), (20)
//          R_T = -sin(2 Delta theta) R_C                                    (21)
//          Delta E00 = sqrt((dL/(k_L S_L))^2 + (dC/(k_C S_C))^2 + (dH/(k_H S_H))^2
//                           + R_T (dC/(k_C S_C)) (dH/(k_H S_H)))            (22)
// The case distinctions in (7), (10) and (14) make Delta E00 discontinuous where the hue
// difference crosses 180 degrees (Sharma et al. 2005, section "Mathematical Observations");
// the published test pairs 9-16 sit on both sides of such jumps.
/// Returns the CIEDE2000 colour difference Delta E00 between c1 and c2. Symmetric, 0 for
/// equal colours, and equal to |Delta L*| / S_L for two achromatic colours.
template <std::floating_point T>
[[nodiscard]] inline T delta_e_2000(const lab<T>& c1, const lab<T>& c2,
                                    const ciede2000_weights<T>& weights = {}) noexcept {
    // Step 1.
    const T C_star_bar = (std::hypot(c1.a, c1.b) + std::hypot(c2.a, c2.b)) / T(2);
    const T G = T(0.5) * (T(1) - std::sqrt(detail::chroma_7_ratio(C_star_bar)));
    const T a1_prime = (T(1) + G) * c1.a;
    const T a2_prime = (T(1) + G) * c2.a;
    const T C1_prime = std::hypot(a1_prime, c1.b);
    const T C2_prime = std::hypot(a2_prime, c2.b);
    const T h1_prime = detail::hue_degrees(a1_prime, c1.b);
    const T h2_prime = detail::hue_degrees(a2_prime, c2.b);

    // Step 2.
    const T delta_L_prime = c2.L - c1.L;
    const T delta_C_prime = C2_prime - C1_prime;
    const T C_product = C1_prime * C2_prime;
    const bool achromatic = C_product == T(0);
    // Whether |h'_1 - h'_2| > 180, the case split of eqs. (10) and (14). When (a'_1, b*_1)
    // and (a'_2, b*_2) point in exactly opposite directions (cross product exactly 0, dot
    // product < 0) the true hue difference is exactly 180 degrees, which eqs. (10) and (14)
    // put in the "<= 180" branch (Table 1 pairs 10 and 14). The rounded atan2 values may
    // differ by 180 plus or minus an ulp there, so that case is decided geometrically.
    const bool opposite = !achromatic && a1_prime * c2.b == c1.b * a2_prime &&
                          a1_prime * a2_prime + c1.b * c2.b < T(0);
    const T h_difference = h2_prime - h1_prime;
    const bool wraps = !opposite && std::abs(h_difference) > T(180);
    T delta_h_prime = T(0);
    if (!achromatic) {
        if (opposite)
            delta_h_prime = h_difference < T(0) ? T(-180) : T(180);
        else if (!wraps)
            delta_h_prime = h_difference;
        else
            delta_h_prime = h_difference > T(0) ? h_difference - T(360) : h_difference + T(360);
    }
    const T delta_H_prime =
        T(2) * std::sqrt(C_product) * std::sin(delta_h_prime * (pi<T> / T(360)));

    // Step 3.
    const T L_bar_prime = (c1.L + c2.L) / T(2);
    const T C_bar_prime = (C1_prime + C2_prime) / T(2);
    const T h_sum = h1_prime + h2_prime;
    T h_bar_prime = h_sum;
    if (!achromatic) {
        if (!wraps)
            h_bar_prime = h_sum / T(2);
        else if (h_sum < T(360))
            h_bar_prime = (h_sum + T(360)) / T(2);
        else
            h_bar_prime = (h_sum - T(360)) / T(2);
    }
    const T deg = pi<T> / T(180);
    const T T_hue = T(1) - T(0.17) * std::cos((h_bar_prime - T(30)) * deg) +
                    T(0.24) * std::cos(T(2) * h_bar_prime * deg) +
                    T(0.32) * std::cos((T(3) * h_bar_prime + T(6)) * deg) -
                    T(0.20) * std::cos((T(4) * h_bar_prime - T(63)) * deg);
    const T theta_arg = (h_bar_prime - T(275)) / T(25);
    const T delta_theta = T(30) * std::exp(-theta_arg * theta_arg);
    const T R_C = T(2) * std::sqrt(detail::chroma_7_ratio(C_bar_prime));
    const T L_offset_sq = (L_bar_prime - T(50)) * (L_bar_prime - T(50));
    const T S_L = T(1) + T(0.015) * L_offset_sq / std::sqrt(T(20) + L_offset_sq);
    const T S_C = T(1) + T(0.045) * C_bar_prime;
    const T S_H = T(1) + T(0.015) * C_bar_prime * T_hue;
    const T R_T = -std::sin(T(2) * delta_theta * deg) * R_C;

    const T term_L = delta_L_prime / (weights.k_L() * S_L);
    const T term_C = delta_C_prime / (weights.k_C() * S_C);
    const T term_H = delta_H_prime / (weights.k_H() * S_H);
    const T sum = term_L * term_L + term_C * term_C + term_H * term_H + R_T * term_C * term_H;
    // The quadratic form is positive semi-definite because |R_T| <= 2; the clamp absorbs a
    // rounding residue below zero when all terms nearly vanish (sqrt would return NaN).
    // Written so that a NaN sum stays NaN (safe_sqrt would turn it into 0).
    return std::sqrt(sum < T(0) ? T(0) : sum);
}

} // namespace shade
