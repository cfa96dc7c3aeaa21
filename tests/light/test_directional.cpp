#include <cmath>
#include <limits>

#include <doctest/doctest.h>

#include <shade/light/directional.hpp>

TEST_CASE_TEMPLATE("directional_light normalises its direction and has infinite distance", T, float, double) {
    using v = shade::vec3<T>;
    const shade::directional_light<T> sun(v(0, 0, 2));
    CHECK(sun.direction() == v(0, 0, 1));
    // (1, 1, 0) / sqrt(2).
    const shade::directional_light<T> diagonal(v(1, 1, 0));
    CHECK(diagonal.direction().x == doctest::Approx(std::sqrt(0.5)).epsilon(1e-6));
    CHECK(diagonal.direction().y == doctest::Approx(std::sqrt(0.5)).epsilon(1e-6));
    CHECK(diagonal.direction().z == T(0));
    const auto s = diagonal.sample(v(5, -7, 100));
    CHECK(s.l == diagonal.direction());
    CHECK(std::isinf(s.distance));
    CHECK(s.distance > T(0));
    CHECK(shade::directional_light<T>::is_delta());
}

TEST_CASE_TEMPLATE("directional_light colours are scaled by the intensity only, the same everywhere", T, float, double) {
    using v = shade::vec3<T>;
    shade::emission<T> e;
    e.intensity = T(2);
    e.ambient = {T(0.125), T(0.25), T(0.5)};
    e.diffuse = {T(0.5), 1, T(0.25)};
    e.specular = {1, 0, T(0.5)};
    const shade::directional_light<T> sun(v(0, 1, 0), e);
    for (const v p : {v(0), v(1e3, -2e3, 5), v(-1, -1, -1)}) {
        const auto s = sun.sample(p, shade::vec2<T>(T(0.9), T(0.1)));
        // No falloff: intensity x colour, i.e. 2 x each channel.
        CHECK(s.ambient == shade::rgb<T>(T(0.25), T(0.5), 1));
        CHECK(s.diffuse == shade::rgb<T>(1, 2, T(0.5)));
        CHECK(s.specular == shade::rgb<T>(2, 0, 1));
    }
}

TEST_CASE_TEMPLATE("directional_light rejects bad directions and emissions by name", T, float, double) {
    using v = shade::vec3<T>;
    const T nan = std::numeric_limits<T>::quiet_NaN();
    CHECK_THROWS_WITH_AS(shade::directional_light<T>(v(0)), doctest::Contains("'direction'"),
                         shade::invalid_parameter);
    CHECK_THROWS_WITH_AS(shade::directional_light<T>(v(0, nan, 1)), doctest::Contains("'direction'"),
                         shade::invalid_parameter);
    shade::emission<T> e;
    e.intensity = T(-0.5);
    CHECK_THROWS_WITH_AS(shade::directional_light<T>(v(0, 0, 1), e), doctest::Contains("'intensity'"),
                         shade::invalid_parameter);
    e = {};
    e.specular = {0, T(-1), 0};
    CHECK_THROWS_WITH_AS(shade::directional_light<T>(v(0, 0, 1), e), doctest::Contains("'specular'"),
                         shade::invalid_parameter);
}
