#include <cmath>
#include <limits>
#include <type_traits>

#include <doctest/doctest.h>

#include <shade/light/point.hpp>

TEST_CASE_TEMPLATE("falloff_factor: 1, 1/r, 1/r^2 with reference distance 1", T, float, double) {
    using shade::falloff;
    // At the reference distance r = 1 every law gives 1.
    CHECK(shade::falloff_factor(falloff::none, T(1)) == T(1));
    CHECK(shade::falloff_factor(falloff::inverse_linear, T(1)) == T(1));
    CHECK(shade::falloff_factor(falloff::inverse_square, T(1)) == T(1));
    // r = 2: 1, 1/2, 1/4 (exact in binary floating point).
    CHECK(shade::falloff_factor(falloff::none, T(2)) == T(1));
    CHECK(shade::falloff_factor(falloff::inverse_linear, T(2)) == T(0.5));
    CHECK(shade::falloff_factor(falloff::inverse_square, T(2)) == T(0.25));
    // r = 1/2: 1, 2, 4 (closer than the reference distance means brighter).
    CHECK(shade::falloff_factor(falloff::inverse_linear, T(0.5)) == T(2));
    CHECK(shade::falloff_factor(falloff::inverse_square, T(0.5)) == T(4));
}

TEST_CASE_TEMPLATE("point_light direction, distance and falloff", T, float, double) {
    using v = shade::vec3<T>;
    shade::emission<T> e;
    e.intensity = T(3);
    e.ambient = shade::rgb<T>(T(0.5));
    e.diffuse = {1, T(0.5), 0};
    e.specular = {0, 0, 1};
    // Light at (3, 4, 0) seen from the origin: r = 5 (3-4-5 triangle), l = (0.6, 0.8, 0).
    const v light_position(3, 4, 0);
    const T r = T(5);
    struct expected_t {
        shade::falloff law;
        T factor;
    };
    for (const auto& [law, factor] : {expected_t{shade::falloff::none, T(1)},
                                       expected_t{shade::falloff::inverse_linear, T(1) / T(5)},
                                       expected_t{shade::falloff::inverse_square, T(1) / T(25)}}) {
        const shade::point_light<T> light(light_position, e, law);
        const auto s = light.sample(v(0));
        CHECK(s.l.x == doctest::Approx(0.6).epsilon(1e-6));
        CHECK(s.l.y == doctest::Approx(0.8).epsilon(1e-6));
        CHECK(s.l.z == T(0));
        CHECK(s.distance == doctest::Approx(double(r)).epsilon(1e-6));
        // diffuse = intensity x factor x colour; ambient = intensity x ambient colour only.
        CHECK(s.diffuse.x == doctest::Approx(double(3 * factor)).epsilon(1e-6));
        CHECK(s.diffuse.y == doctest::Approx(double(T(1.5) * factor)).epsilon(1e-6));
        CHECK(s.diffuse.z == T(0));
        CHECK(s.specular.z == doctest::Approx(double(3 * factor)).epsilon(1e-6));
        CHECK(s.ambient == shade::rgb<T>(T(1.5)));
    }
}

TEST_CASE_TEMPLATE("point_light at r = 2 with 1/r^2 gives a quarter of the intensity", T, float, double) {
    using v = shade::vec3<T>;
    const shade::point_light<T> light(v(0, 0, 2));
    const auto s = light.sample(v(0), shade::vec2<T>(T(0.3), T(0.7))); // u is ignored
    CHECK(s.l == v(0, 0, 1));
    CHECK(s.distance == T(2));
    CHECK(s.diffuse == shade::rgb<T>(T(0.25)));
    CHECK(s.specular == shade::rgb<T>(T(0.25)));
    CHECK(shade::point_light<T>::is_delta());
}

TEST_CASE_TEMPLATE("point_light at the shaded point gives an ambient-only sample, never Inf/NaN", T, float, double) {
    using v = shade::vec3<T>;
    shade::emission<T> e;
    e.ambient = shade::rgb<T>(T(0.25));
    for (const auto law : {shade::falloff::none, shade::falloff::inverse_linear,
                           shade::falloff::inverse_square}) {
        const shade::point_light<T> light(v(1, 2, 3), e, law);
        const auto at_light = light.sample(v(1, 2, 3));
        CHECK(at_light.diffuse == shade::rgb<T>(0));
        CHECK(at_light.specular == shade::rgb<T>(0));
        CHECK(at_light.ambient == shade::rgb<T>(T(0.25)));
        CHECK(shade::is_finite(at_light.l));
    }
    // A hair away from a light at the origin: r = 1e-30, and in float 1/r^2 = 1e60
    // overflows. The sample must stay finite (dropped to ambient-only in float, the huge
    // but finite value in double).
    for (const auto law : {shade::falloff::inverse_linear, shade::falloff::inverse_square}) {
        const shade::point_light<T> light(v(0), e, law);
        const auto near_light = light.sample(v(T(1e-30), 0, 0));
        CHECK(shade::is_finite(near_light.diffuse));
        CHECK(shade::is_finite(near_light.specular));
        CHECK(shade::is_finite(near_light.l));
        // In float r^2 = 1e-60 underflows to 0, so 1/r^2 = +inf and the directional part
        // must have been dropped.
        if (std::is_same_v<T, float> && law == shade::falloff::inverse_square)
            CHECK(near_light.diffuse == shade::rgb<T>(0));
    }
}

TEST_CASE_TEMPLATE("point_light rejects bad parameters by name", T, float, double) {
    using v = shade::vec3<T>;
    const T inf = std::numeric_limits<T>::infinity();
    CHECK_THROWS_WITH_AS(shade::point_light<T>(v(inf, 0, 0)), doctest::Contains("'position'"),
                         shade::invalid_parameter);
    CHECK_THROWS_WITH_AS(shade::point_light<T>(v(0), {}, static_cast<shade::falloff>(7)),
                         doctest::Contains("'falloff'"), shade::invalid_parameter);
    shade::emission<T> e;
    e.diffuse = {T(-1), 0, 0};
    CHECK_THROWS_WITH_AS(shade::point_light<T>(v(0), e), doctest::Contains("'diffuse'"),
                         shade::invalid_parameter);
}
