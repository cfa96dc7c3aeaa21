#include <cmath>
#include <limits>
#include <set>

#include <doctest/doctest.h>

#include <shade/shading/toon.hpp>

#include "shading/local_models.hpp"

using test_models::near;

namespace {

template <class T>
shade::light_sample<T> white_light(const shade::vec3<T>& l) {
    shade::light_sample<T> s;
    s.l = l;
    s.distance = T(1);
    s.diffuse = shade::rgb<T>(1);
    s.specular = shade::rgb<T>(1);
    return s;
}

} // namespace

TEST_CASE_TEMPLATE("quantize: min(floor(x L), L - 1) / (L - 1)", T, float, double) {
    // L = 4: bands [0, 1/4) -> 0, [1/4, 1/2) -> 1/3, [1/2, 3/4) -> 2/3, [3/4, 1] -> 1.
    CHECK(shade::quantize(T(0), 4) == T(0));
    CHECK(shade::quantize(T(0.2499), 4) == T(0));
    CHECK(shade::quantize(T(0.25), 4) == T(1) / T(3));
    CHECK(shade::quantize(T(0.5), 4) == T(2) / T(3));
    CHECK(shade::quantize(T(0.7499), 4) == T(2) / T(3));
    CHECK(shade::quantize(T(0.75), 4) == T(1));
    CHECK(shade::quantize(T(1), 4) == T(1)); // floor(4) = 4 is capped at 3
    // Clamped outside [0, 1].
    CHECK(shade::quantize(T(-2), 4) == T(0));
    CHECK(shade::quantize(T(7), 4) == T(1));
    // L = 3: [0, 1/3) -> 0, [1/3, 2/3) -> 1/2, [2/3, 1] -> 1.
    CHECK(shade::quantize(T(0.3), 3) == T(0));
    CHECK(shade::quantize(T(0.34), 3) == T(0.5));
    CHECK(shade::quantize(T(0.7), 3) == T(1));
}

TEST_CASE_TEMPLATE("toon: a sweep of n.l gives exactly 4 diffuse levels", T, float, double) {
    using v = shade::vec3<T>;
    shade::toon_params<T> p;
    p.diffuse = shade::rgb<T>(1);
    p.specular = shade::rgb<T>(0);
    const shade::toon<T> model(p);
    const auto at = shade::surface_point<T>::at(v(0), v(0, 0, 1));
    std::set<T> levels;
    // l from the normal (theta = 0) past the horizon (theta = 120 degrees).
    for (int i = 0; i <= 1200; ++i) {
        const T theta = T(2) * shade::pi<T> / T(3) * T(i) / T(1200);
        const auto out = model.shade(at, v(0, 0, 1), white_light(v(std::sin(theta), 0, std::cos(theta))));
        levels.insert(out.x);
    }
    REQUIRE(levels.size() == 4);
    auto it = levels.begin();
    CHECK(*it++ == T(0));
    CHECK(*it++ == T(1) / T(3));
    CHECK(*it++ == T(2) / T(3));
    CHECK(*it++ == T(1));
}

TEST_CASE_TEMPLATE("toon: a sweep of n.h gives exactly 3 specular levels", T, float, double) {
    using v = shade::vec3<T>;
    shade::toon_params<T> p;
    p.diffuse = shade::rgb<T>(0);
    p.specular = shade::rgb<T>(1);
    p.shininess = T(8);
    const shade::toon<T> model(p);
    const auto at = shade::surface_point<T>::at(v(0), v(0, 0, 1));
    // l = n and v at angle phi: h at phi/2, (n.h)^8 = cos(phi/2)^8 runs from 1 down to
    // cos(44.5 deg)^8 = 0.067 for phi up to 89 degrees, crossing both band edges 1/3, 2/3.
    std::set<T> levels;
    for (int i = 0; i <= 890; ++i) {
        const T phi = shade::pi<T> / T(180) * T(i) / T(10);
        const auto out = model.shade(at, v(std::sin(phi), 0, std::cos(phi)), white_light(v(0, 0, 1)));
        levels.insert(out.x);
    }
    REQUIRE(levels.size() == 3);
    auto it = levels.begin();
    CHECK(*it++ == T(0));
    CHECK(*it++ == T(0.5));
    CHECK(*it++ == T(1));
}

TEST_CASE_TEMPLATE("toon: shade = k_a I_a + k_d I_d q_d + k_s I_s q_s", T, float, double) {
    using v = shade::vec3<T>;
    using c = shade::rgb<T>;
    shade::toon_params<T> p;
    p.ambient = c(T(0.5));
    p.diffuse = c(T(0.3));
    p.specular = c(T(0.25));
    const shade::toon<T> model(p);
    const auto at = shade::surface_point<T>::at(v(0), v(0, 0, 1));
    // l = (0.8, 0, 0.6): n.l = 0.6, band floor(2.4) = 2 -> 2/3. v the mirror of l, so
    // h = n and n.h = 1 -> 1. Light: I_a = 0.2, I_d = 1, I_s = 2.
    //   0.5 x 0.2 + 0.3 x 1 x 2/3 + 0.25 x 2 x 1 = 0.1 + 0.2 + 0.5 = 0.8.
    shade::light_sample<T> s = white_light(v(T(0.8), 0, T(0.6)));
    s.ambient = c(T(0.2));
    s.specular = c(2);
    CHECK(near(model.shade(at, v(T(-0.8), 0, T(0.6)), s), c(T(0.8)), T(1e-6)));
    // Degenerate: l = -v (no half vector) and l below the surface: no NaN, no highlight.
    const auto opposite = model.shade(at, v(0, 0, -1), white_light(v(0, 0, 1)));
    CHECK(shade::is_finite(opposite));
    CHECK(model.specular_factor(v(0, 0, 1), v(0, 0, 1), v(0, 0, -1)) == T(0));
    CHECK(model.specular_factor(v(0, 0, 1), v(0, 0, -1), v(0, 0, 1)) == T(0));
    CHECK(model.diffuse_factor(v(0, 0, 1), v(0, 0, -1)) == T(0));
}

TEST_CASE_TEMPLATE("toon: an overflowing k_d I_d in a dark band is 0, not NaN (regression, found by fuzzing)",
                   T, float, double) {
    using v = shade::vec3<T>;
    using c = shade::rgb<T>;
    // k_d = k_s = the largest finite value (valid: finite, >= 0) under a light of colour 4:
    // k_d I_d overflows to inf. With l below the surface both bands are 0, so the terms
    // are k_d (I_d x 0) = 0 and k_s (I_s x 0) = 0; (k_d I_d) x 0 was inf x 0 = NaN.
    shade::toon_params<T> p;
    p.diffuse = c(std::numeric_limits<T>::max());
    p.specular = c(std::numeric_limits<T>::max());
    const shade::toon<T> model(p);
    const auto at = shade::surface_point<T>::at(v(0), v(0, 0, 1));
    shade::light_sample<T> s = white_light(v(0, 0, -1));
    s.diffuse = c(4);
    s.specular = c(4);
    CHECK(model.shade(at, v(0, 0, 1), s) == c(0));
}

TEST_CASE_TEMPLATE("toon rejects bad parameters by name", T, float, double) {
    const T nan = std::numeric_limits<T>::quiet_NaN();
    auto make = [](auto change) {
        shade::toon_params<T> p;
        change(p);
        return shade::toon<T>(p);
    };
    CHECK_THROWS_WITH_AS(make([](auto& p) { p.diffuse_levels = 1; }), doctest::Contains("'diffuse_levels'"),
                         shade::invalid_parameter);
    CHECK_THROWS_WITH_AS(make([](auto& p) { p.specular_levels = 0; }), doctest::Contains("'specular_levels'"),
                         shade::invalid_parameter);
    CHECK_THROWS_WITH_AS(make([](auto& p) { p.shininess = T(0); }), doctest::Contains("'shininess'"),
                         shade::invalid_parameter);
    CHECK_THROWS_WITH_AS(make([](auto& p) { p.diffuse = shade::rgb<T>(-1); }), doctest::Contains("'diffuse'"),
                         shade::invalid_parameter);
    CHECK_THROWS_WITH_AS(make([&](auto& p) { p.specular = shade::rgb<T>(nan); }), doctest::Contains("'specular'"),
                         shade::invalid_parameter);
    CHECK_THROWS_WITH_AS(make([](auto& p) { p.ambient = shade::rgb<T>(0, 0, -1); }), doctest::Contains("'ambient'"),
                         shade::invalid_parameter);
}
