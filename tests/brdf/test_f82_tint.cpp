// shade::f82_tint, the F82-tint Fresnel term of metals (Hoffman 2019; Kutz, Hasan,
// Edmondson 2021; OpenPBR Surface 1.1, section "Metal"), alone and inside a compensated
// cook_torrance.

#include <cmath>
#include <string>

#include <doctest/doctest.h>

#include <shade/brdf/cook_torrance.hpp>
#include <shade/brdf/f82_tint.hpp>
#include <shade/brdf/multiple_scattering.hpp>
#include <shade/check/doctest.hpp>
#include <shade/check/properties.hpp>
#include <shade/core/error.hpp>

#include "brdf/properties_support.hpp"
#include "brdf/support.hpp"

using namespace brdf_test;

static_assert(shade::fresnel_term<shade::f82_tint<float>, float>);
static_assert(shade::fresnel_term<shade::f82_tint<double>, double>);

namespace {

template <class T>
constexpr double tol = sizeof(T) <= 4 ? 2e-6 : 1e-14;

// The specification's equations written out in double, independently of the header:
// F_Schlick(mu) = F0 + (1 - F0)(1 - mu)^5, b = (1 - t) F_Schlick(1/7) / ((1/7)(6/7)^6),
// F = w (F_Schlick(mu) - b mu (1 - mu)^6).
double spec_f82(double f0, double t, double w, double mu) {
    const auto schlick = [&](double x) { return f0 + (1 - f0) * std::pow(1 - x, 5); };
    const double mu_bar = 1.0 / 7.0;
    const double b = (1 - t) * schlick(mu_bar) / (mu_bar * std::pow(1 - mu_bar, 6));
    return w * (schlick(mu) - b * mu * std::pow(1 - mu, 6));
}

} // namespace

TEST_CASE_TEMPLATE("f82_tint: F0 at normal incidence, the weight at grazing, the tinted Schlick value at 1/7", T, float,
                   double) {
    const rgb<T> f0(T(0.95), T(0.64), T(0.54)), tint(T(0.99), T(0.7), T(0.6));
    const T w = T(0.8);
    const shade::f82_tint<T> term(f0, tint, w);
    // mu (1 - mu)^6 vanishes at mu = 0 and mu = 1: F = w F_Schlick there, i.e. w F0 and w.
    CHECK(close(term.F(T(1)), w * f0, T(tol<T>)));
    CHECK(close(term.F(T(0)), rgb<T>(w), T(tol<T>)));
    // At mu_bar the correction removes (1 - t) F_Schlick(mu_bar): F = w t F_Schlick(mu_bar).
    const T mu_bar = T(1) / T(7);
    CHECK(close(term.F(mu_bar), w * tint * shade::F_schlick(f0, mu_bar), T(tol<T>)));
}

TEST_CASE_TEMPLATE("f82_tint: a white tint is Schlick's curve", T, float, double) {
    const rgb<T> f0(T(0.04), T(0.5), T(0.9));
    const shade::f82_tint<T> term(f0, rgb<T>(1));
    for (const double mu : {0.0, 0.05, 1.0 / 7.0, 0.3, 0.5, 0.8, 1.0})
        CHECK(close(term.F(T(mu)), shade::F_schlick(f0, T(mu)), T(tol<T>)));
}

TEST_CASE_TEMPLATE("f82_tint: equals the specification's equations", T, float, double) {
    const double f0s[] = {1.0, 0.955, 0.64, 0.5}, tints[] = {1.0, 0.9, 0.6, 0.3}, weights[] = {1.0, 0.7};
    for (const double f0 : f0s)
        for (const double t : tints)
            for (const double w : weights)
                for (int i = 0; i <= 40; ++i) {
                    const double mu = i / 40.0;
                    const double expected = spec_f82(f0, t, w, mu);
                    // These parameters keep F_82 >= 0 (F0 >= 1/2): no clamp involved.
                    REQUIRE(expected >= 0);
                    const shade::f82_tint<T> term{rgb<T>(T(f0)), rgb<T>(T(t)), T(w)};
                    CAPTURE(f0);
                    CAPTURE(t);
                    CAPTURE(mu);
                    CHECK(double(term.F(T(mu)).x) == doctest::Approx(expected).epsilon(tol<T>).scale(1));
                }
}

TEST_CASE_TEMPLATE("f82_tint: clamped at 0 where the correction would exceed Schlick's curve", T, float, double) {
    // F0 = 0, t = 0: b = (6/7)^5 / ((1/7)(6/7)^6) = 49/6 and F_82(1/2) = 1/32 - (49/6)(1/2)(1/64)
    // = -25/768 < 0; the term returns 0 there, and stays >= 0 everywhere.
    CHECK(spec_f82(0, 0, 1, 0.5) == doctest::Approx(-25.0 / 768.0));
    const shade::f82_tint<T> term(rgb<T>(0), rgb<T>(0));
    CHECK(term.F(T(0.5)).x == T(0));
    for (int i = 0; i <= 100; ++i) {
        const rgb<T> f = term.F(T(i) / T(100));
        CHECK(f.x >= T(0));
        CHECK(f.x <= T(1));
    }
}

TEST_CASE_TEMPLATE("f82_tint: F_avg is w (F0 + (1 - F0)/21 - b/126)", T, float, double) {
    // 2 integral_0^1 mu (1 - mu)^5 dmu = 2 B(2, 6) = 1/21 and 2 integral_0^1 mu^2 (1 - mu)^6 dmu
    // = 2 B(3, 7) = 2 * 2! 6! / 9! = 1/126; F_82 >= 0 here, so no clamp changes the integral.
    const double f0[] = {0.95, 0.64, 0.54}, t[] = {0.99, 0.7, 0.6};
    const double w = 0.9;
    const shade::f82_tint<T> term{rgb<T>(T(f0[0]), T(f0[1]), T(f0[2])), rgb<T>(T(t[0]), T(t[1]), T(t[2])), T(w)};
    const rgb<T> f_avg = shade::detail::fresnel_average<T>(term);
    for (int c = 0; c < 3; ++c) {
        const double mu_bar = 1.0 / 7.0;
        const double schlick_bar = f0[c] + (1 - f0[c]) * std::pow(1 - mu_bar, 5);
        const double b = (1 - t[c]) * schlick_bar / (mu_bar * std::pow(1 - mu_bar, 6));
        const double expected = w * (f0[c] + (1 - f0[c]) / 21 - b / 126);
        CHECK(double(f_avg[c]) == doctest::Approx(expected).epsilon(sizeof(T) <= 4 ? 1e-6 : 1e-12));
    }
}

TEST_CASE_TEMPLATE("f82_tint: rejects parameters outside [0, 1], naming them", T, float, double) {
    const rgb<T> ok(T(0.5));
    CHECK_THROWS_WITH_AS(shade::f82_tint<T>(rgb<T>(T(1.1)), ok), doctest::Contains("'f0'"), shade::invalid_parameter);
    CHECK_THROWS_WITH_AS(shade::f82_tint<T>(ok, rgb<T>(T(-0.1))), doctest::Contains("'tint'"), shade::invalid_parameter);
    CHECK_THROWS_WITH_AS(shade::f82_tint<T>(ok, ok, T(2)), doctest::Contains("'weight'"), shade::invalid_parameter);
    CHECK_THROWS_AS(shade::f82_tint<T>(ok, rgb<T>(T(std::nan("")))), shade::invalid_parameter);
}

TEST_CASE_TEMPLATE("f82_tint: a compensated GGX metal passes every property check", T, float, double) {
    using metal = shade::cook_torrance<shade::ggx<T>, shade::f82_tint<T>, shade::smith_height_correlated<T>,
                                       shade::cook_torrance_form::walter, shade::kulla_conty>;
    // Copper-like: F0 and the edge tint of a measured copper curve (a dip at the edge).
    const shade::f82_tint<T> copper(rgb<T>(T(0.955), T(0.638), T(0.538)), rgb<T>(T(0.97), T(0.8), T(0.75)));
    expect_every_property(metal(shade::ggx<T>(T(0.3)), copper), "compensated GGX alpha 0.3, F82-tint copper", 36);
    expect_every_property(metal(shade::ggx<T>(T(0.1), T(0.4)), copper), "compensated GGX 0.1 x 0.4, F82-tint copper",
                          36);
}

TEST_CASE_TEMPLATE("f82_tint: two-sided as Schlick, F(-c) = F(c)", T, float, double) {
    const rgb<T> f0(T(0.9), T(0.6), T(0.3));
    const rgb<T> tint(T(0.8), T(0.9), T(0.5));
    for (int i = 0; i <= 50; ++i) {
        const T c = T(i) / T(50);
        CHECK(shade::F_f82_tint(f0, tint, T(0.9), -c) == shade::F_f82_tint(f0, tint, T(0.9), c));
    }
}
