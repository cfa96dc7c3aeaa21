#include <doctest/doctest.h>

#include <shade/brdf/lambert.hpp>
#include <shade/shading/shader.hpp>

#include "brdf/support.hpp"
#include "brdf/sampling.hpp"

using namespace brdf_test;

static_assert(shade::brdf<shade::lambert<float>>);
static_assert(shade::brdf<shade::lambert<double>>);

TEST_CASE_TEMPLATE("lambert: f = k_d / pi for every pair above the surface", T, float, double) {
    // Lambert's BRDF is the constant k_d / pi; with k_d = (0.5, 0.25, 1):
    // (0.5/pi, 0.25/pi, 1/pi) whatever l and v are, at a flat and a tilted point.
    const rgb<T> k_d(T(0.5), T(0.25), T(1));
    const shade::lambert<T> model(k_d);
    const rgb<T> expected = k_d / shade::pi<T>;
    for (const auto& at : {flat<T>(), tilted<T>()}) {
        CHECK(close(model.f(at.n(), at.n(), at), expected, T(1e-6)));
        CHECK(close(model.f(direction(at, T(1.2), T(0.3)), direction(at, T(0.4), T(2.5)), at),
                    expected, T(1e-6)));
        for (const auto& p : random_pairs(at, 200)) CHECK(close(model.f(p.l, p.v, at), expected, T(1e-6)));
    }
}

TEST_CASE_TEMPLATE("lambert: lit reproduces the classic diffuse term k_d I_d (n.l)", T, float, double) {
    // lit computes pi f I_d (n.l) = pi (k_d/pi) I_d (n.l) = k_d I_d (n.l). With n.l = cos(1)
    // and I_d = 2, k_d = 0.5: 0.5 * 2 * cos(1) = cos(1).
    const auto at = flat<T>();
    const shade::lit shader{shade::lambert<T>(rgb<T>(T(0.5)))};
    shade::light_sample<T> s;
    s.l = direction(at, T(1), T(0));
    s.diffuse = rgb<T>(2);
    const rgb<T> out = shader.shade(at, at.n(), s);
    CHECK(close(out, rgb<T>(std::cos(T(1))), T(1e-6)));
}

TEST_CASE_TEMPLATE("lambert: zero below the surface, finite and non-negative everywhere", T, float, double) {
    const shade::lambert<T> model(rgb<T>(T(0.8)));
    for (const auto& at : {flat<T>(), tilted<T>()}) {
        check_zero_below(model, at);
        check_finite_non_negative(model, at);
    }
}

TEST_CASE_TEMPLATE("lambert: invalid k_d throws naming k_d; unchecked skips validation", T, float, double) {
    check_throws_naming([] { (void)shade::lambert<T>(rgb<T>(T(-0.1), 0, 0)); }, "k_d");
    check_throws_naming([] { (void)shade::lambert<T>(rgb<T>(std::numeric_limits<T>::quiet_NaN())); }, "k_d");
    check_throws_naming([] { (void)shade::lambert<T>(rgb<T>(0, shade::infinity<T>, 0)); }, "k_d");
    CHECK_NOTHROW((void)shade::lambert<T>(shade::unchecked, rgb<T>(-1)));
    CHECK(shade::lambert<T>(rgb<T>(2)).k_d() == rgb<T>(2)); // > 1 allowed (documented)
}

static_assert(shade::sampled_brdf<shade::lambert<float>>);
static_assert(shade::sampled_brdf<shade::lambert<double>>);

TEST_CASE_TEMPLATE("lambert: sample draws the cosine density, agrees with f and pdf, weight k_d", T, float, double) {
    const rgb<T> k_d(T(0.5), T(0.25), T(0.9));
    const shade::lambert<T> model(k_d);
    for (const auto& at : {flat<T>(), tilted<T>()}) check_sampled_model(model, at);
    // pdf = n.l / pi: at 60 deg, 1/(2 pi); the weight f |n.l| / pdf = (k_d/pi)(n.l)/(n.l/pi) = k_d.
    const auto at = flat<T>();
    CHECK(close(model.pdf(direction(at, shade::pi<T> / 3, T(1)), at.n(), at), T(0.5) / shade::pi<T>, T(1e-6)));
    CHECK(model.pdf(-at.n(), at.n(), at) == T(0));
    const auto s = model.sample(at.n(), T(0.7), shade::vec2<T>(T(0.2), T(0.9)), at);
    REQUIRE(s.has_value());
    CHECK(close(s->weight, k_d, T(1e-6)));
}
