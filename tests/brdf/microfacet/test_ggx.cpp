#include <cmath>

#include <doctest/doctest.h>

#include <shade/brdf/microfacet/ggx.hpp>

#include "brdf/microfacet/quadrature.hpp"
#include "brdf/support.hpp"

using namespace brdf_test;
using namespace microfacet_test;

static_assert(shade::sampled_microfacet_distribution<shade::ggx<float>>);
static_assert(shade::sampled_microfacet_distribution<shade::ggx<double>>);

namespace {

template <class T>
constexpr T tol = sizeof(T) <= 4 ? T(2e-6) : T(1e-13);

// The anisotropic GGX D in long double, the reference for the precision tests.
long double D_reference(long double x, long double y, long double z, long double ax, long double ay) {
    const long double k = (x / ax) * (x / ax) + (y / ay) * (y / ay) + z * z;
    return 1.0L / (3.14159265358979323846264338327950288L * ax * ay * k * k);
}

} // namespace

TEST_CASE_TEMPLATE("ggx: anisotropic D hand values", T, float, double) {
    const shade::ggx<T> d(T(0.2), T(0.5));
    // m = n: the quadratic form is 1, D = 1/(pi ax ay) = 1/(pi 0.1) = 10/pi.
    CHECK(close(d.D(vec3<T>(0, 0, 1)), T(10) / shade::pi<T>, tol<T>));
    // m in the t-n plane at theta: D = 1/(pi ax ay (s^2/ax^2 + c^2)^2); the isotropic D with
    // alpha = ax is 1/(pi ax^2 (s^2/ax^2 + c^2)^2), so D = (ax/ay) D_ggx(c, ax).
    const T theta = T(0.4);
    CHECK(close(d.D(local(theta, T(0))), T(0.4) * shade::D_ggx(std::cos(theta), T(0.2)), T(10) * tol<T>));
    // ... and in the b-n plane, D = (ay/ax) D_ggx(c, ay).
    CHECK(close(d.D(local(theta, shade::pi<T> / 2)), T(2.5) * shade::D_ggx(std::cos(theta), T(0.5)), T(10) * tol<T>));
    // On the horizon: 0. Below the surface: the value of the mirror image (two-sided D).
    CHECK(d.D(vec3<T>(1, 0, 0)) == T(0));
    const vec3<T> below = local(T(2), T(1));
    CHECK(below.z < T(0));
    CHECK(d.D(below) == d.D(vec3<T>(below.x, below.y, -below.z)));
    CHECK(d.D(below) > T(0));
}

TEST_CASE_TEMPLATE("ggx: the isotropic local D equals D_ggx of the cosine", T, float, double) {
    for (const T alpha : {T(0.05), T(0.3), T(1), T(3)}) {
        const shade::ggx<T> d(alpha);
        for (const T theta : {T(0.01), T(0.3), T(0.9), T(1.5)}) {
            CAPTURE(alpha);
            CAPTURE(theta);
            // in double both are accurate; in float the cosine form loses up to
            // 6e-8/sin^2(theta) near the peak, so compare where sin^2 >= 1e-4 at 1e-3.
            CHECK(close(d.D(local(theta, T(0.7))), shade::D_ggx(std::cos(theta), alpha),
                        sizeof(T) <= 4 ? T(1e-3) : T(1e-11)));
        }
    }
}

TEST_CASE("ggx: D in float near the peak within 1e-4 of the exact value (alpha = 0.01, theta_h = 1e-3)") {
    // The reference is the same formula in long double at the same (float) m.
    const float theta = 1e-3f;
    const shade::vec3<float> m = local(theta, 0.3f);
    const long double exact = D_reference(m.x, m.y, m.z, 0.01L, 0.01L);
    const float local_form = shade::ggx<float>(0.01f).D(m);
    CHECK(std::abs(local_form - exact) / exact < 1e-4L);
    // The cosine form at the same m: sin^2 = (1 - c)(1 + c) from the rounded cosine is far
    // off, which is what the test would catch (1.4e-3 here).
    const float cosine_form = shade::D_ggx(m.z, 0.01f);
    CHECK(std::abs(cosine_form - exact) / exact > 1e-4L);
}

TEST_CASE_TEMPLATE("ggx: D, Lambda and G1 agree with a long double reference (1e-4 float, 1e-9 double)", T, float, double) {
    const T rel = sizeof(T) <= 4 ? T(1e-4) : T(1e-9);
    for (const auto& parameters : {std::pair{T(1e-4), T(1e-4)}, std::pair{T(0.01), T(0.01)}, std::pair{T(0.05), T(0.5)},
                                 std::pair{T(1), T(1)}, std::pair{T(3), T(0.2)}, std::pair{T(1e4), T(1e4)}}) {
        const auto ax = parameters.first;
        const auto ay = parameters.second;
        const shade::ggx<T> d(ax, ay);
        for (const T theta : {T(1e-5), T(1e-3), T(0.05), T(0.5), T(1.2), T(1.55), T(1.5706)}) {
            for (const T phi : {T(0), T(0.6), T(2.5)}) {
                const vec3<T> m = local(theta, phi);
                CAPTURE(ax);
                CAPTURE(ay);
                CAPTURE(theta);
                CAPTURE(phi);
                const long double x = m.x, y = m.y, z = m.z, lax = ax, lay = ay;
                const long double d_ref = D_reference(x, y, z, lax, lay);
                CHECK(std::abs(d.D(m) - d_ref) <= rel * d_ref);
                // Lambda = (-1 + sqrt(1 + q/z^2))/2 (Heitz 2014, eq. 86), long double, in the
                // algebraically equal form q / (2 z (z + sqrt(z^2 + q))), which does not
                // cancel; the textbook form is checked against it where it is accurate.
                const long double q = lax * lax * x * x + lay * lay * y * y;
                const long double lambda_ref = q / (2.0L * z * (z + std::sqrt(z * z + q)));
                if (q / (z * z) > 1e-6L)
                    CHECK(std::abs((-1.0L + std::sqrt(1.0L + q / (z * z))) / 2.0L - lambda_ref) <= 1e-11L * lambda_ref);
                const T lambda = d.Lambda(m);
                CHECK(std::abs(lambda - lambda_ref) <= rel * lambda_ref);
                const long double g1_ref = 1.0L / (1.0L + lambda_ref);
                CHECK(std::abs(d.G1(m) - g1_ref) <= rel * g1_ref);
            }
        }
    }
}

TEST_CASE_TEMPLATE("ggx: Lambda and G1 hand values", T, float, double) {
    // alpha = 1, theta = 60 deg: tan^2 = 3, Lambda = (-1 + sqrt(4))/2 = 1/2, G1 = 2/3.
    const shade::ggx<T> iso(T(1));
    const vec3<T> w = local(shade::pi<T> / 3, T(0.4));
    CHECK(close(iso.Lambda(w), T(0.5), T(10) * tol<T>));
    CHECK(close(iso.G1(w), T(2) / T(3), T(10) * tol<T>));
    // Anisotropic (1, 0.1): along t the projected roughness is 1 (Lambda 1/2), along b it is
    // 0.1: Lambda = (-1 + sqrt(1 + 0.01 * 3))/2 = (sqrt(1.03) - 1)/2.
    const shade::ggx<T> aniso(T(1), T(0.1));
    CHECK(close(aniso.Lambda(local(shade::pi<T> / 3, T(0))), T(0.5), T(10) * tol<T>));
    CHECK(close(aniso.Lambda(local(shade::pi<T> / 3, shade::pi<T> / 2)), (std::sqrt(T(1.03)) - T(1)) / T(2), T(100) * tol<T>));
    // G1 = 1/(1 + Lambda) everywhere; Lambda(n) = 0, G1(n) = 1; on the horizon: Lambda = inf,
    // G1 = 0; below: the value of the mirror image (two-sided).
    for (const T theta : {T(0.1), T(0.8), T(1.4), T(1.57)})
        CHECK(close(aniso.G1(local(theta, T(1))), T(1) / (T(1) + aniso.Lambda(local(theta, T(1)))), T(10) * tol<T>));
    CHECK(aniso.Lambda(vec3<T>(0, 0, 1)) == T(0));
    CHECK(aniso.G1(vec3<T>(0, 0, 1)) == T(1));
    CHECK(aniso.Lambda(vec3<T>(1, 0, 0)) == shade::infinity<T>);
    CHECK(aniso.G1(vec3<T>(1, 0, 0)) == T(0));
    CHECK(aniso.G1(vec3<T>(0, T(-0.6), T(-0.8))) == aniso.G1(vec3<T>(0, T(-0.6), T(0.8))));
    // Lambda_and_G1: the two numbers of Lambda and G1 (the same arithmetic; to rounding, for
    // a compiler that fuses a multiply-add in one inlined copy only), the horizon included.
    const T rel = sizeof(T) <= 4 ? T(1e-6) : T(1e-13);
    for (const T theta : {T(0), T(0.1), T(0.8), T(1.4), T(1.57), T(2.0), T(3.0)})
        for (const T phi : {T(0), T(1), T(2.5)}) {
            const vec3<T> dir = local(theta, phi);
            const shade::smith_lambda_g1<T> both = aniso.Lambda_and_G1(dir);
            CHECK(close(both.lambda, aniso.Lambda(dir), rel));
            CHECK(close(both.g1, aniso.G1(dir), rel));
        }
    CHECK(aniso.Lambda_and_G1(vec3<T>(1, 0, 0)).lambda == shade::infinity<T>);
    CHECK(aniso.Lambda_and_G1(vec3<T>(1, 0, 0)).g1 == T(0));
}

TEST_CASE_TEMPLATE("ggx: peak bounds D, anisotropic included", T, float, double) {
    for (const auto& parameters : {std::pair{T(1e-4), T(1e-4)}, std::pair{T(0.05), T(0.5)}, std::pair{T(0.7), T(2)},
                                 std::pair{T(3), T(0.3)}, std::pair{T(1e4), T(1e4)}}) {
        const auto ax = parameters.first;
        const auto ay = parameters.second;
        const shade::ggx<T> d(ax, ay);
        T largest = 0;
        for (int i = 0; i <= 400; ++i)
            for (int j = 0; j < 16; ++j) largest = std::max(largest, d.D(local(T(i) / T(400) * T(1.5707963), T(j) * T(0.3926991))));
        CAPTURE(ax);
        CAPTURE(ay);
        CHECK(largest <= d.peak() * T(1 + 1e-5));
        CHECK(std::isfinite(d.peak()));
    }
    // Hand values: (0.2, 0.5): 1/(pi 0.1) at m = n; (2, 0.5): max(2, 1)^4/(pi 1) = 16/pi.
    CHECK(close(shade::ggx<T>(T(0.2), T(0.5)).peak(), T(10) / shade::pi<T>, tol<T>));
    CHECK(close(shade::ggx<T>(T(2), T(0.5)).peak(), T(16) / shade::pi<T>, tol<T>));
    // The isotropic values of before: 1/(pi alpha^2) for alpha <= 1, alpha^2/pi above.
    CHECK(close(shade::ggx<T>(T(0.3)).peak(), T(1) / (shade::pi<T> * T(0.09)), tol<T>));
    CHECK(close(shade::ggx<T>(T(3)).peak(), T(9) / shade::pi<T>, tol<T>));
}

TEST_CASE_TEMPLATE("ggx: constructors, accessors and errors", T, float, double) {
    const shade::ggx<T> iso(T(0.3));
    CHECK(iso.alpha() == T(0.3));
    CHECK(iso.alpha_x() == T(0.3));
    CHECK(iso.alpha_y() == T(0.3));
    CHECK(iso.isotropic());
    CHECK(iso.peak_parameter() == "alpha");
    const shade::ggx<T> aniso(T(0.05), T(0.5));
    CHECK(aniso.alpha_x() == T(0.05));
    CHECK(aniso.alpha_y() == T(0.5));
    CHECK(!aniso.isotropic());
    CHECK(aniso.peak_parameter() == "alpha_x");
    CHECK(shade::ggx<T>(T(0.5), T(0.05)).peak_parameter() == "alpha_y");
    check_throws_naming([] { (void)shade::ggx<T>(T(0), T(0.5)); }, "alpha_x");
    check_throws_naming([] { (void)shade::ggx<T>(T(0.5), T(2e4)); }, "alpha_y");
    check_throws_naming([] { (void)shade::ggx<T>(T(0.5), std::numeric_limits<T>::quiet_NaN()); }, "alpha_y");
    CHECK_NOTHROW((void)shade::ggx<T>(shade::unchecked, T(-1), T(0)));
}

TEST_CASE("ggx: sampled visible normals at 89.9 degrees: the share reflected below the horizon is the D_v mass of those normals") {
    // sample_visible_normal draws m with density D_v(m); the mirror direction of v about m
    // is below the horizon for a set of normals whose D_v mass is computed here by
    // quadrature over m (where even the sharpest lobe is smooth). The share of draws
    // landing in that set must agree with it (binomial standard deviation, 5 sigma).
    const double theta = 89.9 * shade::pi<double> / 180;
    const vec3<double> v(std::sin(theta) * std::cos(0.4), std::sin(theta) * std::sin(0.4), std::cos(theta));
    for (const double r : {0.01, 0.5}) {
        const shade::ggx<double> d(r, 2 * r);
        const auto below = [&](const vec3<double>& m) { return (2 * glm::dot(v, m) * m - v).z <= 0; };
        const double mass = hemisphere_integral([&](const vec3<double>& m) { return below(m) ? shade::D_visible(d, v, m) : 0.0; }, 4000, 800);
        shade::rng random(21);
        const int count = 400000;
        int hits = 0;
        for (int i = 0; i < count; ++i)
            hits += below(d.sample_visible_normal(v, shade::vec2<double>(random.uniform<double>(), random.uniform<double>()))) ? 1 : 0;
        const double share = double(hits) / count;
        CAPTURE(r);
        CAPTURE(mass);
        CHECK(std::abs(share - mass) <= 5 * std::sqrt(mass * (1 - mass) / count) + 1e-5);
        // and the whole D_v integrates to 1 (Heitz 2014, eq. 2 divided by n.v).
        CHECK(hemisphere_integral([&](const vec3<double>& m) { return shade::D_visible(d, v, m); }, 4000, 800) == doctest::Approx(1.0).epsilon(1e-3));
    }
}
