#include <cmath>
#include <limits>

#include <doctest/doctest.h>

#include <shade/light/emission.hpp>

TEST_CASE_TEMPLATE("emission defaults are a white light of intensity 1 without ambient", T, float, double) {
    const shade::emission<T> e;
    CHECK(e.intensity == T(1));
    CHECK(e.ambient == shade::rgb<T>(0));
    CHECK(e.diffuse == shade::rgb<T>(1));
    CHECK(e.specular == shade::rgb<T>(1));
    CHECK_NOTHROW((void)shade::validated(e));
}

TEST_CASE_TEMPLATE("validated(emission) names the bad member", T, float, double) {
    using c = shade::rgb<T>;
    const T nan = std::numeric_limits<T>::quiet_NaN();
    const T inf = std::numeric_limits<T>::infinity();
    auto with = [](auto change) {
        shade::emission<T> e;
        change(e);
        return e;
    };
    CHECK_THROWS_WITH_AS((void)shade::validated(with([](auto& e) { e.intensity = T(-1); })),
                         doctest::Contains("'intensity'"), shade::invalid_parameter);
    CHECK_THROWS_WITH_AS((void)shade::validated(with([&](auto& e) { e.intensity = inf; })),
                         doctest::Contains("'intensity'"), shade::invalid_parameter);
    CHECK_THROWS_WITH_AS((void)shade::validated(with([](auto& e) { e.ambient = c(0, T(-0.1), 0); })),
                         doctest::Contains("'ambient'"), shade::invalid_parameter);
    CHECK_THROWS_WITH_AS((void)shade::validated(with([&](auto& e) { e.diffuse = c(nan, 0, 0); })),
                         doctest::Contains("'diffuse'"), shade::invalid_parameter);
    CHECK_THROWS_WITH_AS((void)shade::validated(with([&](auto& e) { e.specular = c(0, 0, inf); })),
                         doctest::Contains("'specular'"), shade::invalid_parameter);
    // Each is finite alone, but intensity x ambient overflows to +inf.
    const T big = std::numeric_limits<T>::max() / T(4);
    CHECK_THROWS_WITH_AS((void)shade::validated(with([&](auto& e) {
                             e.intensity = big;
                             e.ambient = c(big);
                         })),
                         doctest::Contains("'intensity'"), shade::invalid_parameter);
    // Each is finite alone, but the physical quantity pi x intensity x diffuse overflows.
    CHECK_THROWS_WITH_AS((void)shade::validated(with([&](auto& e) {
                             e.intensity = big;
                             e.diffuse = c(0, 0, 2);
                         })),
                         doctest::Contains("'intensity'"), shade::invalid_parameter);
}

TEST_CASE_TEMPLATE("physical() is 0 in a channel whose colour is 0, whatever the intensity", T, float, double) {
    // pi x max() overflows to +inf, and inf x 0 would be NaN: the product intensity x
    // colour comes first.
    shade::emission<T> e;
    e.intensity = std::numeric_limits<T>::max();
    e.diffuse = shade::rgb<T>(0, T(0.25), 0);
    e.specular = shade::rgb<T>(0);
    const shade::rgb<T> q = shade::validated(e).physical();
    CHECK(q.x == T(0));
    CHECK(q.z == T(0));
    // pi x max / 4 ~ 0.785 max: finite.
    CHECK(std::isfinite(q.y));
    CHECK(q.y > std::numeric_limits<T>::max() / T(2));
}

TEST_CASE_TEMPLATE("make_sample scales diffuse and specular, ambient by intensity only", T, float, double) {
    shade::emission<T> e;
    e.intensity = T(2);
    e.ambient = {T(0.5), 0, T(0.25)};
    e.diffuse = {1, T(0.5), 0};
    e.specular = {0, 1, T(0.75)};
    const shade::vec3<T> l(0, 1, 0);
    // Attenuation 1/4 with intensity 2: scale 1/2 for diffuse and specular; ambient x 2.
    const auto s = shade::detail::make_sample(e, l, T(3), T(0.25));
    CHECK(s.l == l);
    CHECK(s.distance == T(3));
    CHECK(s.ambient == shade::rgb<T>(1, 0, T(0.5)));
    CHECK(s.diffuse == shade::rgb<T>(T(0.5), T(0.25), 0));
    CHECK(s.specular == shade::rgb<T>(0, T(0.5), T(0.375)));
}

TEST_CASE_TEMPLATE("make_sample drops the directional part when it would be Inf or NaN", T, float, double) {
    shade::emission<T> e;
    e.ambient = shade::rgb<T>(T(0.1));
    const T inf = std::numeric_limits<T>::infinity();
    const T nan = std::numeric_limits<T>::quiet_NaN();
    for (const T attenuation : {inf, nan, T(0), std::numeric_limits<T>::max()}) {
        e.intensity = T(4); // with max(), 4 x max overflows
        const auto s = shade::detail::make_sample(e, shade::vec3<T>(1, 0, 0), T(1), attenuation);
        CHECK(s.diffuse == shade::rgb<T>(0));
        CHECK(s.specular == shade::rgb<T>(0));
        CHECK(s.ambient == shade::rgb<T>(T(0.4)));
        CHECK(shade::is_finite(s.l));
    }
}

TEST_CASE_TEMPLATE("split_direction is exact for tiny and huge vectors and safe for zero", T, float, double) {
    // (3, 4, 0) has length 5 (3-4-5 triangle), so the unit vector is (0.6, 0.8, 0); scaling
    // by 1e-30 or 1e30 must not change the direction and must scale the length. In float
    // 1e-30^2 underflows to 0, so a naive length would give 0 (or a division by zero).
    for (const T scale : {T(1), T(1e-30), T(1e30)}) {
        const auto [l, r] = shade::detail::split_direction(shade::vec3<T>(3, 4, 0) * scale);
        CHECK(l.x == doctest::Approx(0.6).epsilon(1e-6));
        CHECK(l.y == doctest::Approx(0.8).epsilon(1e-6));
        CHECK(l.z == T(0));
        CHECK(r == doctest::Approx(5 * double(scale)).epsilon(1e-6));
    }
    const auto zero = shade::detail::split_direction(shade::vec3<T>(0));
    CHECK(zero.length == T(0));
    CHECK(shade::is_finite(zero.direction));
    const T nan = std::numeric_limits<T>::quiet_NaN();
    CHECK(shade::detail::split_direction(shade::vec3<T>(nan, 0, 0)).length == T(0));
    // A NaN next to a larger component (which a max by comparisons could skip) and an
    // infinite component also give length 0 and a finite direction.
    for (const auto& d : {shade::vec3<T>(nan, 1, 0), shade::vec3<T>(2, 1, nan),
                          shade::vec3<T>(0, std::numeric_limits<T>::infinity(), 1)}) {
        const auto s = shade::detail::split_direction(d);
        CHECK(s.length == T(0));
        CHECK(shade::is_finite(s.direction));
    }
}
