#include <cmath>
#include <limits>
#include <type_traits>

#include <doctest/doctest.h>

#include <shade/brdf/lambert.hpp>
#include <shade/brdf/phong.hpp>
#include <shade/shading/gradient.hpp>
#include <shade/shading/shader.hpp>

#include "brdf/sampling.hpp"
#include "shading/local_models.hpp"

using test_models::constant_shader;
using test_models::lambert;
using test_models::near;
using test_models::split_constant;

namespace {

template <class T>
shade::surface_point<T> at_point(T x, T y, T z) {
    return shade::surface_point<T>::at(shade::vec3<T>(x, y, z), shade::vec3<T>(0, 0, 1));
}

} // namespace

TEST_CASE_TEMPLATE("gradient alpha is 1, 0 and 1/2 at the derived points", T, float, double) {
    using v = shade::vec3<T>;
    using S = constant_shader<T>;
    // d = +z (given as (0, 0, 2), normalised), period 4, phase 0:
    //   alpha = (1 + cos(2 pi z / 4)) / 2 = (1 + cos(pi z / 2)) / 2.
    const shade::gradient<S, S> g(S{}, S{}, v(0, 0, 2), T(4));
    CHECK(g.direction() == v(0, 0, 1));
    CHECK(g.alpha(v(0)) == T(1));                                          // cos 0 = 1
    CHECK(g.alpha(v(0, 0, 2)) == doctest::Approx(0.0).epsilon(1e-6));      // cos pi = -1
    CHECK(g.alpha(v(0, 0, 1)) == doctest::Approx(0.5).epsilon(1e-6));      // cos pi/2 = 0
    CHECK(g.alpha(v(0, 0, -1)) == doctest::Approx(0.5).epsilon(1e-6));     // even in z
    CHECK(g.alpha(v(0, 0, 4)) == doctest::Approx(1.0).epsilon(1e-6));      // one period
    CHECK(g.alpha(v(7, -3, 0)) == T(1));                                   // x, y ignored
    // z = 2/3: cos(pi/3) = 1/2, alpha = 3/4.
    CHECK(g.alpha(v(0, 0, T(2) / T(3))) == doctest::Approx(0.75).epsilon(1e-6));
    // Phase pi/2 shifts the pattern: at z = 0, cos(pi/2) = 0, alpha = 1/2; at z = -1,
    // cos(0) = 1.
    const shade::gradient<S, S> shifted(S{}, S{}, v(0, 0, 1), T(4), shade::pi<T> / T(2));
    CHECK(shifted.alpha(v(0)) == doctest::Approx(0.5).epsilon(1e-6));
    CHECK(shifted.alpha(v(0, 0, -1)) == doctest::Approx(1.0).epsilon(1e-6));
}

TEST_CASE_TEMPLATE("gradient alpha stays in [0, 1] far from the origin (regression, found by fuzzing)",
                   T, float, double) {
    using v = shade::vec3<T>;
    using S = constant_shader<T>;
    const shade::gradient<S, S> g(S{}, S{}, v(0, 0, 1), T(4));
    // z = 2^40 (float) / 2^80 (double) is a whole number of periods (period 4 = 2^2), so
    // alpha = (1 + cos(2 pi k)) / 2 = 1 exactly once p.d is reduced modulo the period.
    const T far = std::is_same_v<T, float> ? std::ldexp(T(1), 40) : std::ldexp(T(1), 80);
    CHECK(g.alpha(v(0, 0, far)) == doctest::Approx(1.0).epsilon(1e-6));
    // z = the largest finite value: 2 pi z / 4 used to overflow to inf and cos(inf) = NaN.
    // It is a multiple of 4 as well (a huge float is an even integer times a power of two).
    const T huge = std::numeric_limits<T>::max();
    CHECK(g.alpha(v(0, 0, huge)) == doctest::Approx(1.0).epsilon(1e-6));
    // p.d itself overflows (d = (1, 1, 0)/sqrt 2, p = (max, max, 0): p.d = sqrt 2 max):
    // the mean weight 1/2.
    const shade::gradient<S, S> diagonal(S{}, S{}, v(1, 1, 0), T(4));
    const T a = diagonal.alpha(v(huge, huge, 0));
    CHECK(a == T(0.5));
}

TEST_CASE_TEMPLATE("gradient: a child that overflowed to inf with weight 0 gives no NaN (regression, found by fuzzing)",
                   T, float, double) {
    using v = shade::vec3<T>;
    using S = constant_shader<T>;
    // d = +z, period 4: alpha(z = 2) = (1 + cos pi) / 2 = 0 (cos of pi rounded to T rounds
    // to -1, checked by the REQUIRE), so the result must be the second child alone;
    // 0 x inf was NaN. (Children's radiance can overflow for large valid parameters.)
    const T inf = std::numeric_limits<T>::infinity();
    const shade::gradient<S, S> g(S{shade::rgb<T>(inf)}, S{shade::rgb<T>(T(0.25))}, v(0, 0, 1), T(4));
    const auto at = at_point(T(0), T(0), T(2));
    REQUIRE(g.alpha(at.p) == T(0));
    CHECK(g.shade(at, v(0, 0, 1), shade::light_sample<T>{}) == shade::rgb<T>(T(0.25)));
}

TEST_CASE_TEMPLATE("gradient blends: alpha first + (1 - alpha) second, as a shader and as a BRDF", T, float, double) {
    using v = shade::vec3<T>;
    using c = shade::rgb<T>;
    using S = constant_shader<T>;
    using L = lambert<T>;
    using P = split_constant<T>;
    static_assert(shade::shader<shade::gradient<S, S>>);
    static_assert(shade::shader<shade::gradient<S, L>>);
    static_assert(!shade::brdf<shade::gradient<S, L>>);
    static_assert(shade::brdf<shade::gradient<L, L>>);
    static_assert(!shade::shader<shade::gradient<L, L>>);
    static_assert(shade::split_brdf<shade::gradient<P, P>>);
    shade::light_sample<T> s;
    s.l = v(0, 0, 1);
    s.diffuse = c(1);
    s.specular = c(1);
    const shade::gradient g(S{c(1, 0, 0)}, S{c(0, 0, 1)}, v(1, 0, 0), T(2));
    // x = 0: alpha 1 -> first; x = 1: alpha 0 -> second; x = 1/2: halfway.
    CHECK(near(g.shade(at_point(T(0), T(0), T(0)), v(0, 0, 1), s), c(1, 0, 0), T(1e-6)));
    CHECK(near(g.shade(at_point(T(1), T(0), T(0)), v(0, 0, 1), s), c(0, 0, 1), T(1e-6)));
    CHECK(near(g.shade(at_point(T(0.5), T(0), T(0)), v(0, 0, 1), s), c(T(0.5), 0, T(0.5)), T(1e-6)));
    // BRDFs: f = alpha k0/pi + (1 - alpha) k1/pi; at x = 1/2, (0.2 + 0.6)/2 / pi = 0.4/pi.
    const shade::gradient gb(L{c(T(0.2))}, L{c(T(0.6))}, v(1, 0, 0), T(2));
    const v l(0, 0, 1);
    CHECK(near(gb.f(l, l, at_point(T(0.5), T(0), T(0))), c(T(0.4) / shade::pi<T>), T(1e-6)));
    // Split parts blend the same way: at x = 1/2, specular (0.1 + 0.3)/2 = 0.2.
    const shade::gradient gp(P{c(0), c(T(0.1))}, P{c(0), c(T(0.3))}, v(1, 0, 0), T(2));
    CHECK(near(gp.f_specular(l, l, at_point(T(0.5), T(0), T(0))), c(T(0.2)), T(1e-6)));
    CHECK(near(gp.f_diffuse(l, l, at_point(T(0.5), T(0), T(0))), c(0), T(1e-6)));
    // Mixed: a Lambert child lit without ambient (0.6 facing a white light) and a constant.
    const shade::gradient gm(S{c(1)}, L{c(T(0.6))}, v(1, 0, 0), T(2));
    CHECK(near(gm.shade(at_point(T(1), T(0), T(0)), v(0, 0, 1), s), c(T(0.6)), T(1e-6)));
}

TEST_CASE_TEMPLATE("gradient rejects bad parameters by name", T, float, double) {
    using v = shade::vec3<T>;
    using S = constant_shader<T>;
    using gradient = shade::gradient<S, S>;
    const T nan = std::numeric_limits<T>::quiet_NaN();
    CHECK_THROWS_WITH_AS(gradient(S{}, S{}, v(0), T(1)), doctest::Contains("'direction'"),
                         shade::invalid_parameter);
    CHECK_THROWS_WITH_AS(gradient(S{}, S{}, v(1, 0, 0), T(0)), doctest::Contains("'period'"),
                         shade::invalid_parameter);
    CHECK_THROWS_WITH_AS(gradient(S{}, S{}, v(1, 0, 0), T(-2)), doctest::Contains("'period'"),
                         shade::invalid_parameter);
    CHECK_THROWS_WITH_AS(gradient(S{}, S{}, v(1, 0, 0), T(1), nan), doctest::Contains("'phase'"),
                         shade::invalid_parameter);
}

TEST_CASE_TEMPLATE("gradient of two sampled BRDFs samples the blend: child by uc, blend pdf", T, float, double) {
    using D = shade::lambert<T>;
    using P = shade::normalized_phong<T>;
    using G = shade::gradient<D, P>;
    static_assert(shade::sampled_brdf<G>);
    static_assert(shade::sampled_brdf<shade::gradient<G, D>>); // nests
    const G g(D(shade::rgb<T>(T(0.6))), P(shade::rgb<T>(T(0.1)), shade::rgb<T>(T(0.7)), T(50)),
              shade::vec3<T>(1, 0, 0), T(1));
    // alpha(x) = (1 + cos(2 pi x))/2 = 0.3 at cos(2 pi x) = -0.4.
    const T x = std::acos(T(-0.4)) / (T(2) * shade::pi<T>);
    const auto at = at_point(x, T(0), T(0));
    REQUIRE(g.alpha(at.p) == doctest::Approx(0.3).epsilon(1e-5));
    const T a = g.alpha(at.p);
    // The blend samples correctly (agreement, integral, chi-square) at alpha = 0.3, 1 and 0,
    // with the rounding allowance of a cos^50 lobe.
    const double rounding = brdf_test::pdf_rounding(T(50));
    brdf_test::check_sampled_model(g, at, rounding);
    brdf_test::check_sampled_model(g, at_point(T(0), T(0), T(0)), rounding);   // alpha = 1: Lambert only
    brdf_test::check_sampled_model(g, at_point(T(0.5), T(0), T(0)), rounding); // alpha = 0: Phong only
    // pdf = alpha pdf_0 + (1 - alpha) pdf_1, and uc is reused: uc < alpha draws the first
    // child with uc / alpha, uc >= alpha the second with (uc - alpha) / (1 - alpha).
    const shade::vec3<T> v = glm::normalize(shade::vec3<T>(T(0.3), T(-0.2), 1));
    const shade::vec2<T> u(T(0.35), T(0.8));
    for (const T uc : {T(0.1), T(0.29), T(0.31), T(0.9)}) {
        CAPTURE(uc);
        const auto s = g.sample(v, uc, u, at);
        REQUIRE(s.has_value());
        const auto child = uc < a ? g.first().sample(v, uc / a, u, at)
                                  : g.second().sample(v, (uc - a) / (1 - a), u, at);
        REQUIRE(child.has_value());
        CHECK(glm::length(s->l - child->l) <= T(1e-6));
        const T expected = a * g.first().pdf(s->l, v, at) + (1 - a) * g.second().pdf(s->l, v, at);
        CHECK(s->pdf == doctest::Approx(double(expected)).epsilon(1e-5));
        CHECK(g.pdf(s->l, v, at) == doctest::Approx(double(expected)).epsilon(1e-5));
    }
}

TEST_CASE_TEMPLATE("gradient: a user BRDF with f only still makes a BRDF (not a sampled one) that shades", T, float, double) {
    using U = lambert<T>; // tests/shading/local_models.hpp: f only
    using G = shade::gradient<U, shade::lambert<T>>;
    static_assert(shade::brdf<U> && !shade::sampled_brdf<U>);
    static_assert(shade::brdf<G> && !shade::sampled_brdf<G>);
    // Both children are k_d / pi with k_d = 1 and 0.5; alpha = 1/2 at x = 1/4:
    // f = (1/2)(1/pi) + (1/2)(0.5/pi) = 0.75 / pi.
    const G g(U{}, shade::lambert<T>(shade::rgb<T>(T(0.5))), shade::vec3<T>(1, 0, 0), T(1));
    const auto at = at_point(T(0.25), T(0), T(0));
    const shade::vec3<T> n(0, 0, 1);
    CHECK(near(g.f(n, n, at), shade::rgb<T>(T(0.75) / shade::pi<T>), T(1e-5)));
    shade::light_sample<T> s;
    s.l = n;
    s.diffuse = shade::rgb<T>(1);
    CHECK(near(shade::lit{g}.shade(at, n, s), shade::rgb<T>(T(0.75)), T(1e-5)));
}
