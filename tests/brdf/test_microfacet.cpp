#include <cmath>

#include <doctest/doctest.h>

#include <shade/brdf/microfacet.hpp>

#include "brdf/support.hpp"

using namespace brdf_test;

static_assert(shade::microfacet_distribution<shade::beckmann<float>>);
static_assert(shade::microfacet_distribution<shade::ggx<double>>);
static_assert(shade::masking_for<shade::v_groove<float>, shade::beckmann<float>>);
static_assert(shade::masking_for<shade::v_groove<double>, shade::ggx<double>>);
static_assert(shade::masking_for<shade::smith_beckmann<float>, shade::beckmann<float>>);
static_assert(shade::masking_for<shade::smith_ggx<double>, shade::ggx<double>>);
// Smith masking is tied to its distribution.
static_assert(!shade::masking_for<shade::smith_ggx<float>, shade::beckmann<float>>);
static_assert(!shade::masking_for<shade::smith_beckmann<double>, shade::ggx<double>>);

namespace {

template <class T>
constexpr T tol = sizeof(T) <= 4 ? T(2e-6) : T(1e-13);

// integral over the hemisphere of D(h) cos(theta_h) dh, by the midpoint rule in
// u = sqrt(theta_h / (pi/2)) (which crowds the nodes near the peak at theta_h = 0).
double projected_area(double (*d)(double, double), double parameter) {
    const int steps = 200000;
    double sum = 0;
    for (int i = 0; i < steps; ++i) {
        const double u0 = double(i) / steps, u1 = double(i + 1) / steps;
        const double t0 = u0 * u0 * shade::pi<double> / 2, t1 = u1 * u1 * shade::pi<double> / 2;
        const double t = 0.5 * (t0 + t1);
        sum += d(std::cos(t), parameter) * std::cos(t) * std::sin(t) * (t1 - t0);
    }
    return 2 * shade::pi<double> * sum;
}

// Walter et al. 2007, eq. 26 (exact Smith G1 for Beckmann):
//   G1 = 2 / (1 + erf(a) + exp(-a^2) / (a sqrt(pi))).
double g1_beckmann_exact(double a) {
    return 2.0 / (1.0 + std::erf(a) + std::exp(-a * a) / (a * std::sqrt(shade::pi<double>)));
}

} // namespace

TEST_CASE_TEMPLATE("D_beckmann: hand values", T, float, double) {
    // At n.h = 1: tan = 0, cos = 1: D = 1/(pi m^2). m = 0.5: 4/pi.
    CHECK(close(shade::D_beckmann(T(1), T(0.5)), T(4) / shade::pi<T>, tol<T>));
    // At theta_h = 45 deg: tan^2 = 1, cos^4 = 1/4: D = 4 exp(-1/m^2)/(pi m^2). m = 0.5:
    // 16 exp(-4)/pi.
    CHECK(close(shade::D_beckmann(std::sqrt(T(0.5)), T(0.5)), T(16) * std::exp(T(-4)) / shade::pi<T>, T(10) * tol<T>));
    // On the horizon: 0; below it, the value of the mirror image (two-sided D).
    CHECK(shade::D_beckmann(T(0), T(0.5)) == T(0));
    CHECK(shade::D_beckmann(T(-0.3), T(0.5)) == shade::D_beckmann(T(0.3), T(0.5)));
    // Narrowest valid lobe: 1/(pi 1e-8) at the peak, 0 (not NaN) far from it.
    CHECK(close(shade::D_beckmann(T(1), T(1e-4)), T(1) / (shade::pi<T> * T(1e-8)), T(1e-5)));
    CHECK(shade::D_beckmann(T(0.9), T(1e-4)) == T(0));
    CHECK(shade::D_beckmann(T(1e-30), T(1e4)) >= T(0));
}

TEST_CASE_TEMPLATE("D_ggx: hand values", T, float, double) {
    // At n.h = 1: D = alpha^2/(pi alpha^4) = 1/(pi alpha^2). alpha = 0.5: 4/pi.
    CHECK(close(shade::D_ggx(T(1), T(0.5)), T(4) / shade::pi<T>, tol<T>));
    // alpha = 1: alpha^2 cos^2 + sin^2 = 1, so D = 1/pi for every h above the surface.
    for (const T c : {T(1), T(0.7), T(0.2), T(1e-6)}) CHECK(close(shade::D_ggx(c, T(1)), T(1) / shade::pi<T>, tol<T>));
    // At cos^2 = 1/2: D = alpha^2/(pi ((alpha^2 + 1)/2)^2) = 4 alpha^2/(pi (alpha^2 + 1)^2).
    // alpha = 0.5: 1/(pi 1.5625) = 0.64/pi.
    CHECK(close(shade::D_ggx(std::sqrt(T(0.5)), T(0.5)), T(0.64) / shade::pi<T>, T(10) * tol<T>));
    // alpha = 1e-4 at n.h = 1: 1/(pi 1e-8), finite (the (alpha^2 - 1)c^2 + 1 form is Inf in float).
    CHECK(close(shade::D_ggx(T(1), T(1e-4)), T(1) / (shade::pi<T> * T(1e-8)), T(1e-5)));
    CHECK(shade::D_ggx(T(0), T(0.5)) == T(0));
}

TEST_CASE("D_beckmann and D_ggx are normalized: integral of D cos(theta_h) = 1") {
    for (const double a : {0.05, 0.3, 1.0}) {
        CAPTURE(a);
        CHECK(projected_area(&shade::D_beckmann<double>, a) == doctest::Approx(1.0).epsilon(1e-6));
        CHECK(projected_area(&shade::D_ggx<double>, a) == doctest::Approx(1.0).epsilon(1e-6));
    }
}

TEST_CASE_TEMPLATE("G1_smith_ggx and G1_smith_beckmann: hand values", T, float, double) {
    // GGX: G1 = 2c/(c + sqrt(c^2 + alpha^2 (1 - c^2))). c = 1: 1. alpha = 1: 2c/(c + 1);
    // c = 0.5: 2/3. c -> 0: 0.
    CHECK(close(shade::G1_smith_ggx(T(1), T(0.7)), T(1), tol<T>));
    CHECK(close(shade::G1_smith_ggx(T(0.5), T(1)), T(2) / T(3), tol<T>));
    CHECK(shade::G1_smith_ggx(T(0), T(0.5)) == T(0));
    CHECK(shade::G1_smith_ggx(T(1e-30), T(0.5)) >= T(0));
    // Beckmann: a = c/(m s). c = 1 (s = 0): 1. a >= 1.6: exactly 1.
    CHECK(shade::G1_smith_beckmann(T(1), T(0.5)) == T(1));
    // c = 0.8, s = 0.6, m = 0.5: a = 0.8/0.3 = 2.67 >= 1.6: 1.
    CHECK(shade::G1_smith_beckmann(T(0.8), T(0.5)) == T(1));
    // a = 1 (c = 0.6, s = 0.8, m = 0.75): (3.535 + 2.181)/(1 + 2.276 + 2.577) = 5.716/5.853.
    CHECK(close(shade::G1_smith_beckmann(T(0.6), T(0.75)), T(5.716) / T(5.853), T(10) * tol<T>));
    CHECK(shade::G1_smith_beckmann(T(0), T(0.5)) == T(0));
}

TEST_CASE("G1_smith_beckmann: the rational approximation is within 0.5% of the erf form") {
    // Walter et al. 2007 give eq. 27 as an approximation of eq. 26; over a in (0, 1.6) the
    // two agree to well under 1%.
    for (int i = 1; i < 400; ++i) {
        const double a = 1.6 * i / 400.0;
        // pick c, m with c/(m s) = a: m = 0.5, c = a m / sqrt(1 + a^2 m^2).
        const double m = 0.5;
        const double c = a * m / std::sqrt(1 + a * a * m * m);
        CAPTURE(a);
        CHECK(shade::G1_smith_beckmann(c, m) == doctest::Approx(g1_beckmann_exact(a)).epsilon(5e-3));
    }
}

TEST_CASE_TEMPLATE("G_v_groove: hand values", T, float, double) {
    // l = v = n: n.h = v.h = 1: min(1, 2, 2) = 1.
    CHECK(shade::G_v_groove(T(1), T(1), T(1), T(1)) == T(1));
    // l = v at 60 deg: h = l, n.h = 1/2, v.h = 1: 2 (1/2)(1/2)/1 = 1/2.
    CHECK(close(shade::G_v_groove(T(0.5), T(0.5), T(0.5), T(1)), T(0.5), tol<T>));
    // Mirror pair at theta: h = n, n.h = 1, v.h = cos(theta) = n.v: 2 n.v / v.h = 2 -> 1.
    CHECK(shade::G_v_groove(T(0.3), T(0.3), T(1), T(0.3)) == T(1));
    // Below the horizon: 0.
    CHECK(shade::G_v_groove(T(0), T(0.5), T(0.5), T(0.5)) == T(0));
}

TEST_CASE_TEMPLATE("distribution peaks bound D", T, float, double) {
    for (const T a : {T(1e-4), T(0.3), T(0.7), T(1), T(2), T(1e4)}) {
        CAPTURE(a);
        const shade::beckmann<T> b(a);
        const shade::ggx<T> g(a);
        T max_b = 0, max_g = 0;
        for (int i = 0; i <= 20000; ++i) {
            const T c = T(i) / T(20000);
            max_b = std::max(max_b, b.D(c));
            max_g = std::max(max_g, g.D(c));
        }
        CHECK(max_b <= b.peak() * T(1 + 1e-5));
        CHECK(max_g <= g.peak() * T(1 + 1e-5));
        CHECK(std::isfinite(b.peak()));
        CHECK(std::isfinite(g.peak()));
    }
    // m = 0.3 (m^2 <= 1/2): peak at h = n, 1/(pi 0.09).
    CHECK(close(shade::beckmann<T>(T(0.3)).peak(), T(1) / (shade::pi<T> * T(0.09)), tol<T>));
}

TEST_CASE_TEMPLATE("microfacet terms: invalid parameters throw naming the parameter", T, float, double) {
    check_throws_naming([] { (void)shade::beckmann<T>(T(0)); }, "m");
    check_throws_naming([] { (void)shade::beckmann<T>(T(-0.2)); }, "m");
    check_throws_naming([] { (void)shade::beckmann<T>(T(1e-5)); }, "m");
    check_throws_naming([] { (void)shade::ggx<T>(T(0)); }, "alpha");
    check_throws_naming([] { (void)shade::ggx<T>(std::numeric_limits<T>::quiet_NaN()); }, "alpha");
    check_throws_naming([] { (void)shade::ggx<T>(shade::infinity<T>); }, "alpha");
    CHECK_NOTHROW((void)shade::ggx<T>(T(1e-4)));
    CHECK_NOTHROW((void)shade::beckmann<T>(T(1e4)));
    CHECK_NOTHROW((void)shade::ggx<T>(shade::unchecked, T(-1)));
}
