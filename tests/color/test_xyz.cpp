#include <cmath>
#include <limits>
#include <type_traits>

#include <doctest/doctest.h>
#include <glm/mat3x3.hpp>

#include <shade/color/xyz.hpp>

namespace {

// Tolerance for relations that hold exactly in real arithmetic (inverse matrices, white
// mapped to white) on values of order 1: 1e-12 for double (a few hundred ulps, far below
// the 1e-6 of the round trips), 1e-6 for float (about 8 ulps at 1).
template <class T>
constexpr T exact_tolerance = std::is_same_v<T, float> ? T(1e-6) : T(1e-12);

template <class T>
bool near(const shade::xyz<T>& c, double X, double Y, double Z, double tol) {
    return std::abs(double(c.X) - X) <= tol && std::abs(double(c.Y) - Y) <= tol &&
           std::abs(double(c.Z) - Z) <= tol;
}

template <class T>
bool near(const shade::xyz<T>& c, const shade::xyz<T>& d, T tol) {
    return std::abs(c.X - d.X) <= tol && std::abs(c.Y - d.Y) <= tol && std::abs(c.Z - d.Z) <= tol;
}

} // namespace

TEST_CASE_TEMPLATE("linear sRGB primaries have the XYZ of IEC 61966-2-1", T, float, double) {
    // IEC 61966-2-1:1999 clause 5.2 prints the matrix to 4 decimals; its columns are the
    // primaries' XYZ: R = (0.4124, 0.2126, 0.0193), G = (0.3576, 0.7152, 0.1192),
    // B = (0.1805, 0.0722, 0.9505). Our matrix is derived from the chromaticities, so it
    // must agree to half a unit in the 4th decimal (5e-5).
    const double tol = 5e-5;
    CHECK(near(shade::linear_srgb_to_xyz(shade::rgb<T>(1, 0, 0)), 0.4124, 0.2126, 0.0193, tol));
    CHECK(near(shade::linear_srgb_to_xyz(shade::rgb<T>(0, 1, 0)), 0.3576, 0.7152, 0.1192, tol));
    CHECK(near(shade::linear_srgb_to_xyz(shade::rgb<T>(0, 0, 1)), 0.1805, 0.0722, 0.9505, tol));
}

TEST_CASE_TEMPLATE("linear sRGB white is the D65 white and black is 0", T, float, double) {
    // SMPTE RP 177: the scale factors are chosen so RGB (1,1,1) maps to the white's XYZ, in
    // particular Y = 1 (the middle row sums to 1).
    const auto w = shade::linear_srgb_to_xyz(shade::rgb<T>(1, 1, 1));
    CHECK(near(w, shade::white_point<T>::d65().tristimulus(), exact_tolerance<T>));
    CHECK(shade::linear_srgb_to_xyz(shade::rgb<T>(0, 0, 0)) == shade::xyz<T>{0, 0, 0});
    // And back: the D65 white is linear sRGB (1, 1, 1).
    const auto back = shade::xyz_to_linear_srgb(shade::white_point<T>::d65().tristimulus());
    CHECK(std::abs(back.x - T(1)) <= exact_tolerance<T>);
    CHECK(std::abs(back.y - T(1)) <= exact_tolerance<T>);
    CHECK(std::abs(back.z - T(1)) <= exact_tolerance<T>);
}

TEST_CASE_TEMPLATE("the sRGB -> XYZ and XYZ -> sRGB matrices are inverse", T, float, double) {
    const glm::mat<3, 3, T> product =
        shade::xyz_to_linear_srgb_matrix<T>() * shade::linear_srgb_to_xyz_matrix<T>();
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            CHECK(std::abs(product[i][j] - (i == j ? T(1) : T(0))) <= T(4) * exact_tolerance<T>);
}

TEST_CASE_TEMPLATE("linear sRGB <-> XYZ round trip", T, float, double) {
    // 1e-6 in double (far below the 1/255 step of 8-bit sRGB); in float 4e-6 (the inverse
    // matrix has entries up to 3.24, so a few float ulps of intermediate sums of size ~3
    // add up to this).
    const T tol = std::is_same_v<T, float> ? T(4e-6) : T(1e-6);
    for (int r = -2; r <= 12; ++r)
        for (int g = -2; g <= 12; ++g)
            for (int b = -2; b <= 12; ++b) {
                const shade::rgb<T> c(T(r) / T(10), T(g) / T(10), T(b) / T(10));
                const auto back = shade::xyz_to_linear_srgb(shade::linear_srgb_to_xyz(c));
                CHECK(std::abs(back.x - c.x) <= tol);
                CHECK(std::abs(back.y - c.y) <= tol);
                CHECK(std::abs(back.z - c.z) <= tol);
            }
}

TEST_CASE_TEMPLATE("white points: published values and validation", T, float, double) {
    // D65 from x = 0.3127, y = 0.3290: X = 0.3127/0.3290 = 0.9504559, Z = 0.3583/0.3290
    // = 1.0890578.
    const auto d65 = shade::white_point<T>::d65().tristimulus();
    CHECK(near(d65, 0.9504559, 1.0, 1.0890578, 1e-6));
    CHECK(near(shade::white_point<T>::d50().tristimulus(), 0.9642, 1.0, 0.8249, 1e-7));
    CHECK(near(shade::white_point<T>::from_chromaticity(T(0.3127), T(0.3290)).tristimulus(), d65,
               exact_tolerance<T>));
    // from_xyz rescales to Y = 1: (96.42, 100, 82.49) is D50 in the 0..100 convention.
    CHECK(near(shade::white_point<T>::from_xyz({T(96.42), T(100), T(82.49)}).tristimulus(),
               0.9642, 1.0, 0.8249, 1e-6));
    const T nan = std::numeric_limits<T>::quiet_NaN();
    CHECK_THROWS_AS((void)shade::white_point<T>::from_chromaticity(T(0), T(0.3)), shade::invalid_parameter);
    CHECK_THROWS_AS((void)shade::white_point<T>::from_chromaticity(T(0.3), T(0)), shade::invalid_parameter);
    CHECK_THROWS_AS((void)shade::white_point<T>::from_chromaticity(T(0.6), T(0.4)), shade::invalid_parameter);
    CHECK_THROWS_AS((void)shade::white_point<T>::from_chromaticity(nan, T(0.3)), shade::invalid_parameter);
    CHECK_THROWS_AS((void)shade::white_point<T>::from_xyz({T(1), T(0), T(1)}), shade::invalid_parameter);
    CHECK_THROWS_AS((void)shade::white_point<T>::from_xyz({T(1), T(1), nan}), shade::invalid_parameter);
}

TEST_CASE_TEMPLATE("white points: ratios that overflow are rejected (regression, found by fuzzing)",
                   T, float, double) {
    // x = 0.5 and y = the smallest subnormal pass x > 0, y > 0, x + y < 1, but X = x/y is
    // 0.5 / 2^-149 = 2^148 in float (2^1073 in double), beyond the largest finite value.
    // Likewise from_xyz with X = the largest finite value and Y = 0.5 gives X/Y = 2 max.
    // Both must throw rather than build a white with an infinite component, and name the
    // divisor.
    using limits = std::numeric_limits<T>;
    try {
        (void)shade::white_point<T>::from_chromaticity(T(0.5), limits::denorm_min());
        FAIL("from_chromaticity accepted an overflowing y");
    } catch (const shade::invalid_parameter& e) {
        CHECK(e.parameter() == "y");
    }
    try {
        (void)shade::white_point<T>::from_xyz({limits::max(), T(0.5), T(1)});
        FAIL("from_xyz accepted an overflowing X/Y");
    } catch (const shade::invalid_parameter& e) {
        CHECK(e.parameter() == "white.Y");
    }
    // A huge Y underflows Z/Y: Z = the smallest subnormal, Y = 4 gives 2^-151 -> 0.
    CHECK_THROWS_AS((void)shade::white_point<T>::from_xyz({T(1), T(4), limits::denorm_min()}),
                    shade::invalid_parameter);
}

TEST_CASE_TEMPLATE("Bradford adaptation maps white to white and inverts", T, float, double) {
    const auto d65 = shade::white_point<T>::d65();
    const auto d50 = shade::white_point<T>::d50();
    const shade::bradford_adaptation<T> to_d50(d65, d50);
    const shade::bradford_adaptation<T> to_d65(d50, d65);
    // M^-1 diag(rho_d/rho_s) M W_s = M^-1 diag(rho_d/rho_s) rho_s = M^-1 rho_d = W_d.
    CHECK(near(to_d50(d65.tristimulus()), d50.tristimulus(), exact_tolerance<T>));
    CHECK(near(to_d65(d50.tristimulus()), d65.tristimulus(), exact_tolerance<T>));
    // The two directions are inverse matrices, and equal whites give the identity.
    const shade::bradford_adaptation<T> same(d65, d65);
    for (const shade::xyz<T> c : {shade::xyz<T>{T(0.2), T(0.3), T(0.4)}, shade::xyz<T>{T(0.9), T(0.1), T(0.05)},
                                  shade::xyz<T>{T(0.05), T(0.02), T(0.7)}}) {
        CHECK(near(to_d65(to_d50(c)), c, exact_tolerance<T>));
        CHECK(near(same(c), c, exact_tolerance<T>));
    }
}

TEST_CASE_TEMPLATE("Bradford D65 -> D50 keeps sRGB's neutral axis neutral", T, float, double) {
    // Adaptation is linear and maps the D65 white to the D50 white, so the adapted sRGB
    // primaries R + G + B sum to the D50 white, and a grey g (1,1,1) maps to g * D50.
    const shade::bradford_adaptation<T> to_d50(shade::white_point<T>::d65(), shade::white_point<T>::d50());
    const auto r = to_d50(shade::linear_srgb_to_xyz(shade::rgb<T>(1, 0, 0)));
    const auto g = to_d50(shade::linear_srgb_to_xyz(shade::rgb<T>(0, 1, 0)));
    const auto b = to_d50(shade::linear_srgb_to_xyz(shade::rgb<T>(0, 0, 1)));
    CHECK(near(shade::xyz<T>{r.X + g.X + b.X, r.Y + g.Y + b.Y, r.Z + g.Z + b.Z},
               shade::white_point<T>::d50().tristimulus(), T(4) * exact_tolerance<T>));
    const auto grey = to_d50(shade::linear_srgb_to_xyz(shade::rgb<T>(T(0.18))));
    CHECK(near(grey, 0.18 * 0.9642, 0.18, 0.18 * 0.8249, double(T(4) * exact_tolerance<T>)));
}

TEST_CASE_TEMPLATE("Bradford rejects whites with non-positive cone responses", T, float, double) {
    // x = 0.7, y = 0.29: X = 2.414, Z = 0.034; the second cone response
    // -0.7502*2.414 + 1.7135 + 0.0367*0.034 = -0.095 < 0.
    const auto odd = shade::white_point<T>::from_chromaticity(T(0.7), T(0.29));
    CHECK_THROWS_AS((void)shade::bradford_adaptation<T>(odd, shade::white_point<T>::d65()), shade::invalid_parameter);
    CHECK_THROWS_AS((void)shade::bradford_adaptation<T>(shade::white_point<T>::d65(), odd), shade::invalid_parameter);
}

TEST_CASE_TEMPLATE("XYZ conversions propagate NaN", T, float, double) {
    const T nan = std::numeric_limits<T>::quiet_NaN();
    CHECK(!shade::is_finite(shade::linear_srgb_to_xyz(shade::rgb<T>(nan, 0, 0))));
    CHECK(std::isnan(shade::xyz_to_linear_srgb(shade::xyz<T>{0, nan, 0}).x));
}
