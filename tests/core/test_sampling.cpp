#include <cmath>
#include <limits>

#include <doctest/doctest.h>

#include <shade/core/sampling.hpp>

TEST_CASE_TEMPLATE("stratified_u places samples in their strata", T, float, double) {
    // n = 4, stratum (1, 2) at its centre: ((1 + 0.5)/4, (2 + 0.5)/4) = (0.375, 0.625).
    const auto u = shade::stratified_u<T>(1, 2, 4, shade::cell_centre<T>{}(1, 2));
    CHECK(u == shade::vec2<T>(T(0.375), T(0.625)));
    CHECK(shade::stratified_u<T>(0, 0, 4, shade::vec2<T>(0)) == shade::vec2<T>(0));
    CHECK(shade::stratified_u<T>(3, 3, 4, shade::vec2<T>(T(0.5), 0)) == shade::vec2<T>(T(0.875), T(0.75)));
}

TEST_CASE_TEMPLATE("sin_cos_quarter_pi: within 2 ulp of std::sin and std::cos on [-pi/4, pi/4]", T, float, double) {
    // The Taylor remainders are below half an ulp (see the header); Horner's rule adds about
    // one rounding per step, which the alternating series keeps near 1 ulp.
    const T ulp2 = 2 * std::numeric_limits<T>::epsilon();
    for (int i = -1000; i <= 1000; ++i) {
        const T x = shade::pi<T> / 4 * T(i) / T(1000);
        CAPTURE(x);
        const auto sc = shade::detail::sin_cos_quarter_pi(x);
        CHECK(std::abs(sc.sin - std::sin(x)) <= ulp2 * std::abs(std::sin(x)));
        CHECK(std::abs(sc.cos - std::cos(x)) <= ulp2 * std::cos(x));
    }
}

TEST_CASE_TEMPLATE("square_to_concentric_disk: known points and the unit disk", T, float, double) {
    using v2 = shade::vec2<T>;
    // u = (3/4, 1/2): a = 1/2, b = 0, phi = 0: (1/2, 0). u = (1/2, 1): a = 0, b = 1,
    // phi = pi/2: (0, 1). u = (1, 1) (the corner, as a limit): a = b = 1, phi = pi/4:
    // (cos, sin)(pi/4) = (1/sqrt 2, 1/sqrt 2). u = (1/2, 1/2): the centre.
    const T tol = 4 * std::numeric_limits<T>::epsilon();
    const v2 p1 = shade::square_to_concentric_disk(v2(T(0.75), T(0.5)));
    CHECK(std::abs(p1.x - T(0.5)) <= tol);
    CHECK(std::abs(p1.y) <= tol);
    const v2 p2 = shade::square_to_concentric_disk(v2(T(0.5), T(1)));
    CHECK(std::abs(p2.x) <= tol);
    CHECK(std::abs(p2.y - T(1)) <= tol);
    const v2 p3 = shade::square_to_concentric_disk(v2(T(1), T(1)));
    CHECK(std::abs(p3.x - std::sqrt(T(0.5))) <= tol);
    CHECK(std::abs(p3.y - std::sqrt(T(0.5))) <= tol);
    CHECK(shade::square_to_concentric_disk(v2(T(0.5), T(0.5))) == v2(0, 0));
    // The boundary of the square maps to the unit circle: radius max(|a|, |b|).
    for (int i = 0; i <= 100; ++i) {
        const T t = T(i) / T(100);
        for (const v2 u : {v2(t, 1), v2(1, t), v2(t, 0), v2(0, t)}) {
            const v2 p = shade::square_to_concentric_disk(u);
            CHECK(std::abs(std::hypot(p.x, p.y) - T(1)) <= tol);
        }
    }
}

TEST_CASE_TEMPLATE("sin_cos_two_pi: within a few ulp of std::sin and std::cos of 2 pi u, every quadrant", T, float, double) {
    // Absolute error against 1: the angle 2 pi u itself rounds (std::sin(2 pi u) is computed
    // from the rounded angle), and near a zero of sin or cos only the absolute error is small.
    const T tol = 8 * std::numeric_limits<T>::epsilon();
    for (int i = 0; i < 4000; ++i) {
        const T u = T(i) / T(4000);
        CAPTURE(u);
        const auto sc = shade::detail::sin_cos_two_pi(u);
        const double angle = 2 * 3.14159265358979323846 * double(u);
        CHECK(std::abs(double(sc.sin) - std::sin(angle)) <= double(tol));
        CHECK(std::abs(double(sc.cos) - std::cos(angle)) <= double(tol));
    }
}
