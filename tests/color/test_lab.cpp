#include <cmath>
#include <limits>
#include <type_traits>

#include <doctest/doctest.h>

#include <shade/color/lab.hpp>

namespace {

// Tolerance in L*a*b* units (values up to ~100-200): 1e-6 for double (a millionth of the
// just-noticeable Delta E of 1); for float 1e-4, i.e. about 8 float ulps at magnitude 100
// (L* = 116 f - 16 and a* = 500 (f_x - f_y) scale a relative float error of 6e-8 in f by up
// to 500).
template <class T>
constexpr T lab_tolerance = std::is_same_v<T, float> ? T(1e-4) : T(1e-6);

// Tolerance in XYZ units (white Y = 1): 1e-6 for double, 1e-6 for float (~8 ulps at 1).
template <class T>
constexpr T xyz_tolerance = T(1e-6);

template <class T>
bool near(const shade::lab<T>& c, double L, double a, double b, double tol) {
    return std::abs(double(c.L) - L) <= tol && std::abs(double(c.a) - a) <= tol &&
           std::abs(double(c.b) - b) <= tol;
}

} // namespace

TEST_CASE_TEMPLATE("L*a*b*: the white is (100, 0, 0) and black is (0, 0, 0) for any white", T, float, double) {
    // X/X_n = Y/Y_n = Z/Z_n = 1: f = 1, L* = 116 - 16 = 100, a* = b* = 0. Black: all ratios
    // 0, f = 16/116, L* = 116 * 16/116 - 16 = 0, a* = b* = 0.
    for (const auto& w : {shade::white_point<T>::d65(), shade::white_point<T>::d50(),
                          shade::white_point<T>::from_chromaticity(T(0.4476), T(0.4074))}) {
        CHECK(near(shade::xyz_to_lab(w.tristimulus(), w), 100, 0, 0, lab_tolerance<T>));
        CHECK(near(shade::xyz_to_lab(shade::xyz<T>{0, 0, 0}, w), 0, 0, 0, lab_tolerance<T>));
    }
}

TEST_CASE_TEMPLATE("L*a*b*: hand-evaluated values on both branches of f", T, float, double) {
    const auto w = shade::white_point<T>::d65();
    const auto& n = w.tristimulus();
    // Cube-root branch with exact cubes: X/X_n = 0.216 (f = 0.6), Y = 0.125 (f = 0.5),
    // Z/Z_n = 0.064 (f = 0.4): L* = 116*0.5 - 16 = 42, a* = 500*0.1 = 50, b* = 200*0.1 = 20.
    CHECK(near(shade::xyz_to_lab(shade::xyz<T>{T(0.216) * n.X, T(0.125), T(0.064) * n.Z}, w), 42, 50, 20,
               lab_tolerance<T>));
    // 18% grey: L* = 116 * 0.18^(1/3) - 16 = 116 * 0.5646216 - 16 = 49.496107.
    CHECK(near(shade::xyz_to_lab(shade::xyz<T>{T(0.18) * n.X, T(0.18), T(0.18) * n.Z}, w), 49.496107, 0, 0,
               std::is_same_v<T, float> ? 1e-4 : 1e-6));
    // Linear branch: Y = 0.001 < (24/116)^3 = 0.008856: L* = 116 (841/108) 0.001
    // = 903.2963 * 0.001 = 0.9032963.
    CHECK(near(shade::xyz_to_lab(shade::xyz<T>{T(0.001) * n.X, T(0.001), T(0.001) * n.Z}, w), 0.9032963, 0, 0,
               1e-6));
    // At the join Y = (6/29)^3 both branches give f = 6/29 and L* = 116*6/29 - 16 = 8.
    const T join = T(216.0 / 24389.0);
    CHECK(near(shade::xyz_to_lab(shade::xyz<T>{join * n.X, join, join * n.Z}, w), 8, 0, 0, lab_tolerance<T>));
}

TEST_CASE_TEMPLATE("L*a*b*: round trips through XYZ, D65 and D50", T, float, double) {
    for (const auto& w : {shade::white_point<T>::d65(), shade::white_point<T>::d50()}) {
        // Lab -> XYZ -> Lab over L* 0..100, a*, b* -120..120 (both branches of f occur).
        for (int L = 0; L <= 100; L += 5)
            for (int a = -120; a <= 120; a += 15)
                for (int b = -120; b <= 120; b += 15) {
                    const shade::lab<T> c{T(L), T(a), T(b)};
                    const auto back = shade::xyz_to_lab(shade::lab_to_xyz(c, w), w);
                    CHECK(near(back, double(c.L), double(c.a), double(c.b), lab_tolerance<T>));
                }
        // XYZ -> Lab -> XYZ.
        for (int i = 0; i <= 10; ++i)
            for (int j = 0; j <= 10; ++j)
                for (int k = 0; k <= 10; ++k) {
                    const shade::xyz<T> c{T(i) / T(10), T(j) / T(10), T(k) / T(10)};
                    const auto back = shade::lab_to_xyz(shade::xyz_to_lab(c, w), w);
                    CHECK(std::abs(back.X - c.X) <= xyz_tolerance<T>);
                    CHECK(std::abs(back.Y - c.Y) <= xyz_tolerance<T>);
                    CHECK(std::abs(back.Z - c.Z) <= xyz_tolerance<T>);
                }
    }
}

TEST_CASE_TEMPLATE("L*C*h: chroma, hue quadrants and the achromatic convention", T, float, double) {
    using lab = shade::lab<T>;
    const T tol = lab_tolerance<T>;
    // (3, 4): C = 5, h = atan2(4, 3) = 53.130102 degrees.
    auto c = shade::lab_to_lch(lab{50, 3, 4});
    CHECK(c.L == T(50));
    CHECK(std::abs(c.C - T(5)) <= tol);
    CHECK(std::abs(c.h - T(53.130102)) <= tol);
    // Quadrants map into [0, 360): (0, -1) -> 270; (-1, -0) -> atan2(-0, -1) = -180 -> 180.
    CHECK(std::abs(shade::lab_to_lch(lab{50, 0, -1}).h - T(270)) <= tol);
    CHECK(std::abs(shade::lab_to_lch(lab{50, -1, T(-0.0)}).h - T(180)) <= tol);
    CHECK(std::abs(shade::lab_to_lch(lab{50, -1, -1}).h - T(225)) <= tol);
    // Achromatic: h = 0 by convention, also for a* = -0 (atan2(0, -0) would give 180).
    CHECK(shade::lab_to_lch(lab{50, 0, 0}).h == T(0));
    CHECK(shade::lab_to_lch(lab{50, T(-0.0), 0}).h == T(0));
    // A tiny negative angle must not round up to 360.
    const T h_tiny = shade::lab_to_lch(lab{50, 1, -std::numeric_limits<T>::denorm_min()}).h;
    CHECK(h_tiny >= T(0));
    CHECK(h_tiny < T(360));
    // Round trip.
    for (int a = -100; a <= 100; a += 10)
        for (int b = -100; b <= 100; b += 10) {
            const lab in{T(40), T(a), T(b)};
            CHECK(near(shade::lch_to_lab(shade::lab_to_lch(in)), 40, a, b, tol));
        }
}

TEST_CASE_TEMPLATE("L*a*b*: NaN propagates and require_finite rejects it", T, float, double) {
    const T nan = std::numeric_limits<T>::quiet_NaN();
    const auto w = shade::white_point<T>::d65();
    const auto c = shade::xyz_to_lab(shade::xyz<T>{nan, T(0.5), T(0.5)}, w);
    CHECK(std::isnan(c.a));
    CHECK(!shade::is_finite(c));
    CHECK(std::isnan(shade::lab_to_xyz(shade::lab<T>{nan, 0, 0}, w).Y));
    CHECK(shade::require_finite("measured", shade::lab<T>{50, 1, 2}) == shade::lab<T>{50, 1, 2});
    CHECK_THROWS_AS((void)shade::require_finite("measured", shade::lab<T>{50, nan, 2}), shade::invalid_parameter);
    CHECK_THROWS_AS((void)shade::require_finite("measured", shade::lab<T>{50, 1, std::numeric_limits<T>::infinity()}),
                    shade::invalid_parameter);
}
