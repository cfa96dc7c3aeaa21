#include <cmath>
#include <limits>

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/shading/gooch.hpp>

#include "shading/local_models.hpp"

using test_models::near;

namespace {

template <class T>
shade::light_sample<T> light_from(const shade::vec3<T>& l, T colour = T(1)) {
    shade::light_sample<T> s;
    s.l = l;
    s.distance = T(1);
    s.diffuse = shade::rgb<T>(colour);
    s.specular = shade::rgb<T>(colour);
    return s;
}

} // namespace

TEST_CASE_TEMPLATE("gooch endpoints: l = n is warm, l = -n is cool, l perpendicular is the mean", T, float, double) {
    using v = shade::vec3<T>;
    using c = shade::rgb<T>;
    static_assert(shade::shader<shade::gooch<T>>);
    // Defaults: k_d = 0.75, b = y = 0.4, alpha = 0.2, beta = 0.6:
    //   k_cool = (0, 0, 0.4) + 0.2 x 0.75 = (0.15, 0.15, 0.55)
    //   k_warm = (0.4, 0.4, 0) + 0.6 x 0.75 = (0.85, 0.85, 0.45)
    const shade::gooch<T> model;
    const c warm(T(0.85), T(0.85), T(0.45));
    const c cool(T(0.15), T(0.15), T(0.55));
    CHECK(near(model.warm(), warm, T(1e-6)));
    CHECK(near(model.cool(), cool, T(1e-6)));
    const auto at = shade::surface_point<T>::at(v(0), v(0, 0, 1));
    const v view(0, 0, 1);
    CHECK(near(model.shade(at, view, light_from(v(0, 0, 1))), warm, T(1e-6)));
    CHECK(near(model.shade(at, view, light_from(v(0, 0, -1))), cool, T(1e-6)));
    // n.l = 0: t = 1/2, the mean (0.5, 0.5, 0.5).
    CHECK(near(model.shade(at, view, light_from(v(1, 0, 0))), c(T(0.5)), T(1e-6)));
    // n.l = 1/2: t = 3/4: 0.75 warm + 0.25 cool = (0.675, 0.675, 0.475).
    CHECK(near(model.shade(at, view, light_from(v(std::sqrt(T(0.75)), 0, T(0.5)))),
               c(T(0.675), T(0.675), T(0.475)), T(1e-6)));
    // The light's diffuse colour scales the tone.
    CHECK(near(model.shade(at, view, light_from(v(0, 0, 1), T(2))), T(2) * warm, T(1e-6)));
}

TEST_CASE_TEMPLATE("gooch highlight: Phong (r.v)^s on the lit side only", T, float, double) {
    using v = shade::vec3<T>;
    using c = shade::rgb<T>;
    shade::gooch_params<T> p;
    p.highlight = c(1);
    p.shininess = T(10);
    const shade::gooch<T> model(p);
    const auto at = shade::surface_point<T>::at(v(0), v(0, 0, 1));
    // l = v = n: r = n, r.v = 1: warm + 1.
    CHECK(near(model.shade(at, v(0, 0, 1), light_from(v(0, 0, 1))), model.warm() + c(1), T(1e-6)));
    // l = (0.6, 0, 0.8): r = 2 x 0.8 n - l = (-0.6, 0, 0.8); v = r: full highlight 1 on top
    // of the tone at t = 0.9.
    const c tone = model.tone(v(0, 0, 1), v(T(0.6), 0, T(0.8)));
    CHECK(near(model.shade(at, v(T(-0.6), 0, T(0.8)), light_from(v(T(0.6), 0, T(0.8)))), tone + c(1), T(1e-5)));
    // Light from behind: cool tone, no highlight even with v = r-like directions.
    CHECK(near(model.shade(at, v(0, 0, 1), light_from(v(0, 0, -1))), model.cool(), T(1e-6)));
    // Without a highlight colour the default shader adds nothing.
    const shade::gooch<T> plain;
    CHECK(near(plain.shade(at, v(0, 0, 1), light_from(v(0, 0, 1))), plain.warm(), T(1e-6)));
}

TEST_CASE("gooch: a huge shininess with r.v rounding past 1 gives no NaN (regression, found by fuzzing)") {
    // n = l = v = (1, 1, 1)/sqrt 3 in double: r = 2 (n.l) n - l, and r.v rounds to
    // 1 + 2^-52, whose 1e200-th power overflowed to inf; times a specular light colour of
    // 0 that was NaN. With r.v clamped to 1 the highlight is k_s I_s 1 = 0, and the result
    // is the warm tone (t = (1 + n.l)/2 = 1) times I_d = 0: exactly 0.
    using v = shade::vec3<double>;
    shade::gooch_params<double> p;
    p.highlight = shade::rgb<double>(0, 0, 1);
    p.shininess = 1e200;
    const shade::gooch<double> g(p);
    const v n = glm::normalize(v(1, 1, 1));
    const auto at = shade::surface_point<double>::at(v(0), n);
    shade::light_sample<double> s;
    s.l = n;
    REQUIRE(glm::dot(2 * glm::dot(n, n) * n - n, n) > 1.0); // the rounding that triggered it
    CHECK(g.shade(at, n, s) == shade::rgb<double>(0));
}

TEST_CASE_TEMPLATE("gooch rejects bad parameters by name", T, float, double) {
    const T nan = std::numeric_limits<T>::quiet_NaN();
    auto make = [](auto change) {
        shade::gooch_params<T> p;
        change(p);
        return shade::gooch<T>(p);
    };
    CHECK_THROWS_WITH_AS(make([](auto& p) { p.alpha = T(-0.1); }), doctest::Contains("'alpha'"),
                         shade::invalid_parameter);
    CHECK_THROWS_WITH_AS(make([&](auto& p) { p.beta = nan; }), doctest::Contains("'beta'"),
                         shade::invalid_parameter);
    CHECK_THROWS_WITH_AS(make([](auto& p) { p.blue = shade::rgb<T>(0, 0, -1); }), doctest::Contains("'blue'"),
                         shade::invalid_parameter);
    CHECK_THROWS_WITH_AS(make([](auto& p) { p.yellow = shade::rgb<T>(-1); }), doctest::Contains("'yellow'"),
                         shade::invalid_parameter);
    CHECK_THROWS_WITH_AS(make([](auto& p) { p.diffuse = shade::rgb<T>(-1); }), doctest::Contains("'diffuse'"),
                         shade::invalid_parameter);
    CHECK_THROWS_WITH_AS(make([](auto& p) { p.highlight = shade::rgb<T>(-1); }), doctest::Contains("'highlight'"),
                         shade::invalid_parameter);
    CHECK_THROWS_WITH_AS(make([](auto& p) { p.shininess = T(0); }), doctest::Contains("'shininess'"),
                         shade::invalid_parameter);
    // Regression, found by fuzzing: every member finite, but k_warm = yellow + beta k_d
    // (or k_cool = blue + alpha k_d) overflows to inf, and shade() then computed
    // 0 x inf = NaN where t = 0. Rejected, naming the weight.
    const T big = std::numeric_limits<T>::max();
    CHECK_THROWS_WITH_AS(make([&](auto& p) { p.beta = big; p.diffuse = shade::rgb<T>(2); }),
                         doctest::Contains("'beta'"), shade::invalid_parameter);
    CHECK_THROWS_WITH_AS(make([&](auto& p) { p.alpha = big; p.diffuse = shade::rgb<T>(2); }),
                         doctest::Contains("'alpha'"), shade::invalid_parameter);
}
