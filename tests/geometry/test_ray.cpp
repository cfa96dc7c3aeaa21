#include <limits>

#include <doctest/doctest.h>

#include <shade/geometry/ray.hpp>

TEST_CASE_TEMPLATE("ray: defaults are origin 0, direction +z, t in [0, +inf]", T, float, double) {
    const shade::ray<T> r;
    CHECK(r.origin == shade::vec3<T>(0, 0, 0));
    CHECK(r.direction == shade::vec3<T>(0, 0, 1));
    CHECK(r.t_min == T(0));
    CHECK(r.t_max == std::numeric_limits<T>::infinity());
    CHECK(r.valid());
}

TEST_CASE_TEMPLATE("ray: at(t) walks t units of the (non-unit) direction", T, float, double) {
    // origin (1,2,3) + t (2,0,-1): t = 0.5 gives (1+1, 2, 3-0.5) = (2, 2, 2.5);
    // t = -2 gives (1-4, 2, 3+2) = (-3, 2, 5). All exact in binary.
    const shade::ray<T> r{{1, 2, 3}, {2, 0, -1}};
    CHECK(r.at(T(0.5)) == shade::vec3<T>(2, 2, T(2.5)));
    CHECK(r.at(T(-2)) == shade::vec3<T>(-3, 2, 5));
    CHECK(r.at(T(0)) == r.origin);
}

TEST_CASE_TEMPLATE("ray: valid() rejects every kind of unusable ray", T, float, double) {
    using v = shade::vec3<T>;
    const T nan = std::numeric_limits<T>::quiet_NaN();
    const T inf = std::numeric_limits<T>::infinity();
    const T tiny = std::numeric_limits<T>::denorm_min();
    CHECK(shade::ray<T>{{0, 0, 0}, {0, 0, tiny}}.valid()); // any non-zero length works
    CHECK(shade::ray<T>{{0, 0, 0}, {0, 0, -1}, 2, 2}.valid()); // a single point interval
    CHECK_FALSE(shade::ray<T>{{0, 0, 0}, {0, 0, 0}}.valid());
    CHECK_FALSE(shade::ray<T>{{0, 0, 0}, {0, nan, 1}}.valid());
    CHECK_FALSE(shade::ray<T>{{0, 0, 0}, {inf, 0, 0}}.valid());
    CHECK_FALSE(shade::ray<T>{{inf, 0, 0}, {0, 0, 1}}.valid());
    CHECK_FALSE(shade::ray<T>{{0, nan, 0}, {0, 0, 1}}.valid());
    CHECK_FALSE(shade::ray<T>{v(0), {0, 0, 1}, T(-1), inf}.valid()); // behind the origin
    CHECK_FALSE(shade::ray<T>{v(0), {0, 0, 1}, nan, inf}.valid());
    CHECK_FALSE(shade::ray<T>{v(0), {0, 0, 1}, 0, nan}.valid());
    CHECK_FALSE(shade::ray<T>{v(0), {0, 0, 1}, 3, 2}.valid());
}

TEST_CASE_TEMPLATE("ray::checked keeps the direction and throws naming the parameter", T, float, double) {
    using v = shade::vec3<T>;
    const T nan = std::numeric_limits<T>::quiet_NaN();
    const auto r = shade::ray<T>::checked(v(1, 2, 3), v(0, 0, 4), T(1), T(10));
    CHECK(r.direction == v(0, 0, 4)); // not normalised: t keeps the caller's units
    CHECK(r.t_min == T(1));
    CHECK(r.t_max == T(10));
    CHECK_THROWS_WITH_AS((void)shade::ray<T>::checked(v(nan, 0, 0), v(0, 0, 1)),
                         doctest::Contains("'origin'"), shade::invalid_parameter);
    CHECK_THROWS_WITH_AS((void)shade::ray<T>::checked(v(0, 0, 0), v(0, 0, 0)),
                         doctest::Contains("'direction'"), shade::invalid_parameter);
    CHECK_THROWS_WITH_AS((void)shade::ray<T>::checked(v(0, 0, 0), v(0, 0, 1), T(-1)),
                         doctest::Contains("'t_min'"), shade::invalid_parameter);
    CHECK_THROWS_WITH_AS((void)shade::ray<T>::checked(v(0, 0, 0), v(0, 0, 1), T(2), T(1)),
                         doctest::Contains("'t_max'"), shade::invalid_parameter);
    CHECK_THROWS_WITH_AS((void)shade::ray<T>::checked(v(0, 0, 0), v(0, 0, 1), T(0), nan),
                         doctest::Contains("'t_max'"), shade::invalid_parameter);
}
