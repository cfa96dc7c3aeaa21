#include <cmath>

#include <doctest/doctest.h>

#include <shade/brdf/microfacet/beckmann.hpp>

#include "brdf/microfacet/quadrature.hpp"
#include "brdf/support.hpp"

using namespace brdf_test;
using namespace microfacet_test;

static_assert(shade::sampled_microfacet_distribution<shade::beckmann<float>>);
static_assert(shade::sampled_microfacet_distribution<shade::beckmann<double>>);

namespace {

template <class T>
constexpr T tol = sizeof(T) <= 4 ? T(2e-6) : T(1e-13);

constexpr long double pi_l = 3.14159265358979323846264338327950288L;

// Beckmann Lambda of a = 1/(m_w tan(theta)) in long double: (erf(a) - 1)/2 +
// exp(-a^2)/(2 a sqrt(pi)) (the form of Heitz 2014 / Walter et al. 2007, eq. 26).
long double lambda_reference(long double a) {
    return (std::erf(a) - 1.0L) / 2.0L + std::exp(-a * a) / (2.0L * a * std::sqrt(pi_l));
}

} // namespace

TEST_CASE_TEMPLATE("beckmann: anisotropic D hand values", T, float, double) {
    const shade::beckmann<T> d(T(0.2), T(0.5));
    // m = n: D = 1/(pi m_x m_y) = 10/pi.
    CHECK(close(d.D(vec3<T>(0, 0, 1)), T(10) / shade::pi<T>, tol<T>));
    // m in the t-n plane: exp(-tan^2/m_x^2)/(pi m_x m_y c^4) = (m_x/m_y) D_beckmann(c, m_x);
    // in the b-n plane (m_y/m_x) D_beckmann(c, m_y).
    const T theta = T(0.3);
    CHECK(close(d.D(local(theta, T(0))), T(0.4) * shade::D_beckmann(std::cos(theta), T(0.2)), T(20) * tol<T>));
    CHECK(close(d.D(local(theta, shade::pi<T> / 2)), T(2.5) * shade::D_beckmann(std::cos(theta), T(0.5)), T(20) * tol<T>));
    // theta = 45 deg, azimuth 45 deg: m = (1/2, 1/2, 1/sqrt2), exponent
    // -(1/4)(1/0.04 + 1/0.25)/(1/2) = -(25 + 4)/2 = -14.5, c^4 = 1/4:
    // D = 4 exp(-14.5)/(pi 0.1) = 40 exp(-14.5)/pi.
    CHECK(close(d.D(vec3<T>(T(0.5), T(0.5), std::sqrt(T(0.5)))), T(40) * std::exp(T(-14.5)) / shade::pi<T>, T(50) * tol<T>));
    CHECK(d.D(vec3<T>(1, 0, 0)) == T(0));
    // Far from a narrow lobe: 0, not NaN.
    CHECK(shade::beckmann<T>(T(1e-4), T(1e-3)).D(local(T(0.5), T(0.3))) == T(0));
}

TEST_CASE_TEMPLATE("beckmann: the isotropic local D equals D_beckmann of the cosine", T, float, double) {
    for (const T m : {T(0.05), T(0.3), T(1), T(3)}) {
        const shade::beckmann<T> d(m);
        for (const T theta : {T(0.01), T(0.3), T(0.9), T(1.3)}) {
            CAPTURE(m);
            CAPTURE(theta);
            CHECK(close(d.D(local(theta, T(0.7))), shade::D_beckmann(std::cos(theta), m),
                        sizeof(T) <= 4 ? T(1e-3) : T(1e-11)));
        }
    }
}

TEST_CASE_TEMPLATE("beckmann: D, Lambda and G1 agree with a long double reference (1e-4 float, 1e-9 double)", T, float, double) {
    const T rel = sizeof(T) <= 4 ? T(1e-4) : T(1e-9);
    for (const auto& parameters : {std::pair{T(1e-4), T(1e-4)}, std::pair{T(0.01), T(0.01)}, std::pair{T(0.05), T(0.5)},
                                 std::pair{T(1), T(1)}, std::pair{T(3), T(0.2)}, std::pair{T(1e4), T(1e4)}}) {
        const auto mx = parameters.first;
        const auto my = parameters.second;
        const shade::beckmann<T> d(mx, my);
        for (const T theta : {T(1e-5), T(1e-3), T(0.05), T(0.5), T(1.2), T(1.55), T(1.5706)}) {
            for (const T phi : {T(0), T(0.6), T(2.5)}) {
                const vec3<T> m = local(theta, phi);
                CAPTURE(mx);
                CAPTURE(my);
                CAPTURE(theta);
                CAPTURE(phi);
                const long double x = m.x, y = m.y, z = m.z, lmx = mx, lmy = my;
                const long double exponent = ((x / lmx) * (x / lmx) + (y / lmy) * (y / lmy)) / (z * z);
                const long double d_ref = std::exp(-exponent) / (pi_l * lmx * lmy * z * z * z * z);
                // The exponent is ill-conditioned where it is large (its relative rounding
                // error is multiplied by its size); compare where it is below 10.
                if (exponent < 10) CHECK(std::abs(d.D(m) - d_ref) <= rel * d_ref);
                const long double a = z / std::sqrt(lmx * lmx * x * x + lmy * lmy * y * y);
                const long double lambda_ref = lambda_reference(a);
                // Lambda is a difference of two nearly equal terms for large a: compare it
                // (relative) where a <= 2, and G1 = 1/(1 + Lambda) everywhere.
                if (a <= 2) CHECK(std::abs(d.Lambda(m) - lambda_ref) <= rel * lambda_ref);
                const long double g1_ref = 1.0L / (1.0L + lambda_ref);
                CHECK(std::abs(d.G1(m) - g1_ref) <= rel * g1_ref);
            }
        }
    }
}

TEST_CASE_TEMPLATE("beckmann: Lambda and the exact G1, hand values", T, float, double) {
    // a = 1: Lambda = (erf(1) - 1)/2 + exp(-1)/(2 sqrt(pi)); erf(1) = 0.8427007929497149,
    // exp(-1)/(2 sqrt(pi)) = 0.10377687435514868: Lambda = 0.02512727083000614.
    // a = 1/(m tan(theta)): m = 1, theta = 45 deg.
    const shade::beckmann<T> d(T(1));
    const vec3<T> w = local(shade::pi<T> / 4, T(0.3));
    CHECK(close(d.Lambda(w), T(0.02512727083000614), sizeof(T) <= 4 ? T(1e-4) : T(1e-12)));
    CHECK(close(d.G1(w), T(1) / T(1.02512727083000614), T(10) * tol<T>));
    // a = 0.5 (m = 2, theta = 45 deg): Lambda = 0.1996412283742457.
    CHECK(close(shade::beckmann<T>(T(2)).Lambda(w), T(0.1996412283742457), sizeof(T) <= 4 ? T(1e-4) : T(1e-12)));
    // The free isotropic form agrees: G1_smith_beckmann_exact(cos 45, 1).
    CHECK(close(shade::G1_smith_beckmann_exact(std::cos(shade::pi<T> / 4), T(1)), T(1) / T(1.02512727083000614), T(10) * tol<T>));
    // Anisotropic (1, 2): along t, a = 1; along b, a = 0.5.
    const shade::beckmann<T> aniso(T(1), T(2));
    CHECK(close(aniso.Lambda(local(shade::pi<T> / 4, T(0))), T(0.02512727083000614), sizeof(T) <= 4 ? T(1e-4) : T(1e-12)));
    CHECK(close(aniso.Lambda(local(shade::pi<T> / 4, shade::pi<T> / 2)), T(0.1996412283742457), sizeof(T) <= 4 ? T(1e-4) : T(1e-12)));
    // Limits: Lambda(n) = 0, G1(n) = 1; grazing: Lambda = inf, G1 = 0 (below: the mirror
    // image's, tests/brdf/microfacet/test_two_sided.cpp).
    CHECK(d.Lambda(vec3<T>(0, 0, 1)) == T(0));
    CHECK(d.G1(vec3<T>(0, 0, 1)) == T(1));
    CHECK(d.Lambda(vec3<T>(1, 0, 0)) == shade::infinity<T>);
    CHECK(d.G1(vec3<T>(1, 0, 0)) == T(0));
    CHECK(shade::G1_smith_beckmann_exact(T(0), T(0.5)) == T(0));
    CHECK(shade::G1_smith_beckmann_exact(T(1), T(0.5)) == T(1));
}

TEST_CASE("beckmann: the rational G1 is within 0.5% of the exact one, and they differ") {
    // Walter et al. 2007 give eq. 27 as an approximation of eq. 26 over a in (0, 1.6).
    double largest = 0;
    for (int i = 1; i < 400; ++i) {
        const double a = 1.6 * i / 400.0;
        const double m = 0.5;
        const double c = a * m / std::sqrt(1 + a * a * m * m); // c/(m s) = a
        const double exact = shade::G1_smith_beckmann_exact(c, m);
        CAPTURE(a);
        CHECK(exact == doctest::Approx(1.0 / (1.0 + static_cast<double>(lambda_reference(a)))).epsilon(1e-12));
        CHECK(shade::G1_smith_beckmann(c, m) == doctest::Approx(exact).epsilon(5e-3));
        largest = std::max(largest, std::abs(shade::G1_smith_beckmann(c, m) - exact));
    }
    CHECK(largest > 1e-4); // two different functions, not one under two names
}

TEST_CASE_TEMPLATE("beckmann: peak bounds D, anisotropic included", T, float, double) {
    for (const auto& parameters : {std::pair{T(1e-4), T(1e-4)}, std::pair{T(0.05), T(0.5)}, std::pair{T(0.7), T(2)},
                                 std::pair{T(3), T(0.3)}, std::pair{T(1e4), T(1e4)}}) {
        const auto mx = parameters.first;
        const auto my = parameters.second;
        const shade::beckmann<T> d(mx, my);
        T largest = 0;
        for (int i = 0; i <= 2000; ++i)
            for (int j = 0; j < 32; ++j) largest = std::max(largest, d.D(local(T(i) / T(2000) * T(1.5707963), T(j) * T(0.19634954))));
        CAPTURE(mx);
        CAPTURE(my);
        CHECK(largest <= d.peak() * T(1 + 1e-5));
        CHECK(std::isfinite(d.peak()));
    }
    // m_x = 0.2, m_y = 0.5 (max^2 <= 1/2): 1/(pi 0.1) at m = n.
    CHECK(close(shade::beckmann<T>(T(0.2), T(0.5)).peak(), T(10) / shade::pi<T>, tol<T>));
    // Isotropic m = 0.3: 1/(pi 0.09) as before; m = 1: 4 exp(-1)/pi.
    CHECK(close(shade::beckmann<T>(T(0.3)).peak(), T(1) / (shade::pi<T> * T(0.09)), tol<T>));
    CHECK(close(shade::beckmann<T>(T(1)).peak(), T(4) * std::exp(T(-1)) / shade::pi<T>, T(10) * tol<T>));
}

TEST_CASE_TEMPLATE("beckmann: constructors, accessors and errors", T, float, double) {
    const shade::beckmann<T> iso(T(0.3));
    CHECK(iso.m() == T(0.3));
    CHECK(iso.m_y() == T(0.3));
    CHECK(iso.isotropic());
    CHECK(iso.peak_parameter() == "m");
    const shade::beckmann<T> aniso(T(0.5), T(0.05));
    CHECK(aniso.m_x() == T(0.5));
    CHECK(aniso.m_y() == T(0.05));
    CHECK(aniso.peak_parameter() == "m_y");
    check_throws_naming([] { (void)shade::beckmann<T>(T(-1), T(0.5)); }, "m_x");
    check_throws_naming([] { (void)shade::beckmann<T>(T(0.5), shade::infinity<T>); }, "m_y");
}

TEST_CASE("beckmann: sampled visible normals at 89.9 degrees: the share reflected below the horizon is the D_v mass of those normals") {
    // sample_visible_normal draws m with density D_v(m); the mirror direction of v about m
    // is below the horizon for a set of normals whose D_v mass is computed here by
    // quadrature over m (where even the sharpest lobe is smooth). The share of draws
    // landing in that set must agree with it (binomial standard deviation, 5 sigma).
    const double theta = 89.9 * shade::pi<double> / 180;
    const vec3<double> v(std::sin(theta) * std::cos(0.4), std::sin(theta) * std::sin(0.4), std::cos(theta));
    for (const double r : {0.01, 0.5}) {
        const shade::beckmann<double> d(r, 2 * r);
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
