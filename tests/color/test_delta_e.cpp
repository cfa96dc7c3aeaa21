#include <cmath>
#include <limits>

#include <doctest/doctest.h>

#include <shade/color/delta_e.hpp>

namespace {

// Sharma, G., Wu, W., Dalal, E. N., 2005, "The CIEDE2000 Color-Difference Formula:
// Implementation Notes, Supplementary Test Data, and Mathematical Observations", Color
// Research and Application 30(1), 21-30, Table 1 (CIEDE2000 total colour difference test
// data): the 34 published pairs, typed in from the table as
// L*_1, a*_1, b*_1, L*_2, a*_2, b*_2, Delta E00 (printed to 4 decimals).
struct sharma_pair {
    double L1, a1, b1, L2, a2, b2, delta_e_00;
};

constexpr sharma_pair sharma_table_1[34] = {
    {50.0000, 2.6772, -79.7751, 50.0000, 0.0000, -82.7485, 2.0425},  // 1
    {50.0000, 3.1571, -77.2803, 50.0000, 0.0000, -82.7485, 2.8615},  // 2
    {50.0000, 2.8361, -74.0200, 50.0000, 0.0000, -82.7485, 3.4412},  // 3
    {50.0000, -1.3802, -84.2814, 50.0000, 0.0000, -82.7485, 1.0000}, // 4
    {50.0000, -1.1848, -84.8006, 50.0000, 0.0000, -82.7485, 1.0000}, // 5
    {50.0000, -0.9009, -85.5211, 50.0000, 0.0000, -82.7485, 1.0000}, // 6
    {50.0000, 0.0000, 0.0000, 50.0000, -1.0000, 2.0000, 2.3669},     // 7: one colour achromatic
    {50.0000, -1.0000, 2.0000, 50.0000, 0.0000, 0.0000, 2.3669},     // 8: 7 swapped
    {50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0009, 7.1792},    // 9: |dh| just < 180
    {50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0010, 7.1792},    // 10: |dh| = 180
    {50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0011, 7.2195},    // 11: |dh| just > 180
    {50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0012, 7.2195},    // 12
    {50.0000, -0.0010, 2.4900, 50.0000, 0.0009, -2.4900, 4.8045},    // 13
    {50.0000, -0.0010, 2.4900, 50.0000, 0.0010, -2.4900, 4.8045},    // 14
    {50.0000, -0.0010, 2.4900, 50.0000, 0.0011, -2.4900, 4.7461},    // 15
    {50.0000, 2.5000, 0.0000, 50.0000, 0.0000, -2.5000, 4.3065},     // 16
    {50.0000, 2.5000, 0.0000, 73.0000, 25.0000, -18.0000, 27.1492},  // 17
    {50.0000, 2.5000, 0.0000, 61.0000, -5.0000, 29.0000, 22.8977},   // 18
    {50.0000, 2.5000, 0.0000, 56.0000, -27.0000, -3.0000, 31.9030},  // 19
    {50.0000, 2.5000, 0.0000, 58.0000, 24.0000, 15.0000, 19.4535},   // 20
    {50.0000, 2.5000, 0.0000, 50.0000, 3.1736, 0.5854, 1.0000},      // 21
    {50.0000, 2.5000, 0.0000, 50.0000, 3.2972, 0.0000, 1.0000},      // 22
    {50.0000, 2.5000, 0.0000, 50.0000, 1.8634, 0.5757, 1.0000},      // 23
    {50.0000, 2.5000, 0.0000, 50.0000, 3.2592, 0.3350, 1.0000},      // 24
    {60.2574, -34.0099, 36.2677, 60.4626, -34.1751, 39.4387, 1.2644}, // 25
    {63.0109, -31.0961, -5.8663, 62.8187, -29.7946, -4.0864, 1.2630}, // 26
    {61.2901, 3.7196, -5.3901, 61.4292, 2.2480, -4.9620, 1.8731},     // 27
    {35.0831, -44.1164, 3.7933, 35.0232, -40.0716, 1.5901, 1.8645},   // 28
    {22.7233, 20.0904, -46.6940, 23.0331, 14.9730, -42.5619, 2.0373}, // 29
    {36.4612, 47.8580, 18.3852, 36.2715, 50.5065, 21.2231, 1.4146},   // 30
    {90.8027, -2.0831, 1.4410, 91.1528, -1.6435, 0.0447, 1.4441},     // 31
    {90.9257, -0.5406, -0.9208, 88.6381, -0.8985, -0.7239, 1.5381},   // 32
    {6.7747, -0.2908, -2.4247, 5.8714, -0.0985, -2.2286, 0.6377},     // 33
    {2.0776, 0.0795, -1.1350, 0.9033, -0.0636, -0.5514, 0.9082},      // 34
};

template <class T>
shade::lab<T> lab1(const sharma_pair& p) {
    return {T(p.L1), T(p.a1), T(p.b1)};
}

template <class T>
shade::lab<T> lab2(const sharma_pair& p) {
    return {T(p.L2), T(p.a2), T(p.b2)};
}

} // namespace

TEST_CASE_TEMPLATE("delta_e_2000 reproduces the 34 pairs of Sharma et al. 2005 Table 1", T, float, double) {
    // The table prints Delta E00 to 4 decimals, so an exact implementation is within 5e-5;
    // 1e-4 leaves room for float rounding of the inputs themselves.
    int index = 0;
    for (const auto& p : sharma_table_1) {
        ++index;
        CAPTURE(index);
        const T d = shade::delta_e_2000(lab1<T>(p), lab2<T>(p));
        CHECK(std::abs(double(d) - p.delta_e_00) <= 1e-4);
    }
}

TEST_CASE_TEMPLATE("delta_e_2000 is symmetric on the published pairs and on hue-edge cases", T, float, double) {
    // Every case distinction of eqs. (7), (10) and (14) is symmetric in the two colours
    // (|h1 - h2|, h1 + h2 and C'1 C'2 are), and Delta L', Delta C', Delta H' only change
    // sign, which the squares and the product R_T dC dH do not see. So swapping is exact up
    // to rounding of h2 - h1 vs h1 - h2 (which is exact) and the order of sums.
    const T tol = T(8) * std::numeric_limits<T>::epsilon() * T(100);
    for (const auto& p : sharma_table_1) {
        const T forward = shade::delta_e_2000(lab1<T>(p), lab2<T>(p));
        const T backward = shade::delta_e_2000(lab2<T>(p), lab1<T>(p));
        CHECK(std::abs(forward - backward) <= tol);
    }
}

TEST_CASE_TEMPLATE("delta_e_2000 is zero for equal colours, including achromatic and signed zeros", T, float, double) {
    using lab = shade::lab<T>;
    for (const lab c : {lab{50, 0, 0}, lab{0, 0, 0}, lab{100, 0, 0}, lab{T(37.2), T(12.4), T(-8.9)},
                        lab{50, T(-0.0), T(0.0)}, lab{T(60.2574), T(-34.0099), T(36.2677)}}) {
        CHECK(shade::delta_e_2000(c, c) == T(0));
    }
    // a* = -0 against a* = +0: both achromatic, hue 0 by definition (eq. (7)); without that
    // rule atan2(0, -0) = 180 degrees would enter the mean hue.
    CHECK(shade::delta_e_2000(lab{50, T(-0.0), 0}, lab{50, T(0.0), 0}) == T(0));
}

TEST_CASE_TEMPLATE("delta_e_2000 of black and white is 100", T, float, double) {
    // Both achromatic: G = 1/2 (irrelevant, a* = 0), C' = 0, Delta C' = Delta H' = 0.
    // L-bar' = 50, so S_L = 1 + 0.015 * 0 / sqrt(20) = 1 and Delta E00 = |Delta L'| = 100.
    const T d = shade::delta_e_2000(shade::lab<T>{0, 0, 0}, shade::lab<T>{100, 0, 0});
    CHECK(d == doctest::Approx(100).epsilon(1e-6));
}

TEST_CASE_TEMPLATE("delta_e_2000 of two greys follows S_L", T, float, double) {
    // L* 40 vs 70: L-bar' = 55, (L-bar' - 50)^2 = 25, S_L = 1 + 0.015*25/sqrt(45)
    // = 1 + 0.375/6.708204 = 1.0559017, so Delta E00 = 30/1.0559017 = 28.411735.
    const T d = shade::delta_e_2000(shade::lab<T>{40, 0, 0}, shade::lab<T>{70, 0, 0});
    CHECK(d == doctest::Approx(28.411735).epsilon(1e-6));
}

TEST_CASE_TEMPLATE("delta_e_2000 weights divide their term", T, float, double) {
    // For two greys only the lightness term is non-zero, so k_L = 2 halves Delta E00
    // (black/white: 100 -> 50), and k_C, k_H change nothing.
    const shade::lab<T> black{0, 0, 0}, white{100, 0, 0};
    CHECK(shade::delta_e_2000(black, white, shade::ciede2000_weights<T>(2, 1, 1)) ==
          doctest::Approx(50).epsilon(1e-6));
    CHECK(shade::delta_e_2000(black, white, shade::ciede2000_weights<T>(1, 3, 7)) ==
          doctest::Approx(100).epsilon(1e-6));
    CHECK_THROWS_AS((void)shade::ciede2000_weights<T>(0, 1, 1), shade::invalid_parameter);
    CHECK_THROWS_AS((void)shade::ciede2000_weights<T>(1, T(-1), 1), shade::invalid_parameter);
    CHECK_THROWS_AS((void)shade::ciede2000_weights<T>(1, 1, std::numeric_limits<T>::quiet_NaN()),
                    shade::invalid_parameter);
}

TEST_CASE_TEMPLATE("delta_e_2000 propagates NaN and stays finite for huge chroma", T, float, double) {
    const T nan = std::numeric_limits<T>::quiet_NaN();
    const shade::lab<T> c{50, 10, 10};
    CHECK(std::isnan(shade::delta_e_2000(shade::lab<T>{nan, 10, 10}, c)));
    CHECK(std::isnan(shade::delta_e_2000(c, shade::lab<T>{50, nan, 10})));
    CHECK(std::isnan(shade::delta_e_2000(c, shade::lab<T>{50, 10, nan})));
    // C-bar^7 overflows T for C ~ 1e6 (float) / 1e44 (double); the ratio form must not
    // produce inf/inf.
    const T big = T(1e6);
    CHECK(std::isfinite(shade::delta_e_2000(shade::lab<T>{50, big, 0}, shade::lab<T>{50, big, 1})));
}

TEST_CASE_TEMPLATE("delta_e_76 is the Euclidean distance", T, float, double) {
    // (50, 3, 4) vs (50, 0, 0): sqrt(0 + 9 + 16) = 5; (10, 1, 2) vs (12, 4, 8): sqrt(4+9+36) = 7.
    CHECK(shade::delta_e_76(shade::lab<T>{50, 3, 4}, shade::lab<T>{50, 0, 0}) == doctest::Approx(5));
    CHECK(shade::delta_e_76(shade::lab<T>{10, 1, 2}, shade::lab<T>{12, 4, 8}) == doctest::Approx(7));
    CHECK(shade::delta_e_76(shade::lab<T>{12, 4, 8}, shade::lab<T>{10, 1, 2}) == doctest::Approx(7));
}

TEST_CASE_TEMPLATE("delta_e_94 against hand-derived values", T, float, double) {
    using lab = shade::lab<T>;
    const auto arts = shade::cie94_parameters<T>::graphic_arts();
    const auto textiles = shade::cie94_parameters<T>::textiles();
    // Pure lightness difference 5: S_L = 1, so 5/k_L: 5 (graphic arts), 2.5 (textiles).
    CHECK(shade::delta_e_94(lab{50, 30, 40}, lab{55, 30, 40}) == doctest::Approx(5));
    CHECK(shade::delta_e_94(lab{50, 30, 40}, lab{55, 30, 40}, textiles) == doctest::Approx(2.5));
    // Achromatic reference (C*_1 = 0): S_C = S_H = 1. Sample (50, 3, 4) has C* = 5, so
    // Delta C = -5 and (Delta H)^2 = 9 + 16 - 25 = 0: Delta E94 = 5.
    CHECK(shade::delta_e_94(lab{50, 0, 0}, lab{50, 3, 4}) == doctest::Approx(5));
    // Swapped: C*_1 = 5, S_C = 1 + 0.045*5 = 1.225, Delta E94 = 5/1.225 = 4.0816327. Not
    // symmetric, as CIE 116-1995 intends.
    CHECK(shade::delta_e_94(lab{50, 3, 4}, lab{50, 0, 0}) == doctest::Approx(4.0816327).epsilon(1e-6));
    // Pure hue difference: (50, 50, 0) vs (50, 0, 50), C* = 50 for both, Delta C = 0,
    // (Delta H)^2 = 2500 + 2500 = 5000, S_H = 1 + 0.015*50 = 1.75:
    // Delta E94 = sqrt(5000)/1.75 = 70.710678/1.75 = 40.406102.
    CHECK(shade::delta_e_94(lab{50, 50, 0}, lab{50, 0, 50}) == doctest::Approx(40.406102).epsilon(1e-6));
    // Textiles: S_H = 1 + 0.014*50 = 1.7 -> 70.710678/1.7 = 41.594517.
    CHECK(shade::delta_e_94(lab{50, 50, 0}, lab{50, 0, 50}, textiles) ==
          doctest::Approx(41.594517).epsilon(1e-6));
    // Same hue, different chroma: (Delta H)^2 is 0 in exact arithmetic and must not become a
    // NaN from a rounded negative: (50, 30, 40) vs (50, 36, 48), C* 50 vs 60, S_C = 3.25,
    // Delta E94 = 10/3.25 = 3.0769231.
    CHECK(shade::delta_e_94(lab{50, 30, 40}, lab{50, 36, 48}, arts) ==
          doctest::Approx(3.0769231).epsilon(1e-6));
    CHECK(shade::delta_e_94(lab{T(37.1), T(12.3), T(-8.7)}, lab{T(37.1), T(12.3), T(-8.7)}) == T(0));
    CHECK_THROWS_AS((void)shade::cie94_parameters<T>(0, 1, 1), shade::invalid_parameter);
    CHECK_THROWS_AS((void)shade::cie94_parameters<T>(1, -1, 1), shade::invalid_parameter);
}
