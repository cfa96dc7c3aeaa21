#include <cmath>
#include <limits>

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/geometry/hit.hpp>

TEST_CASE_TEMPLATE("hit: facing_normal flips the normal toward a back-face ray's origin", T, float, double) {
    shade::hit<T> h;
    h.n = {0, 1, 0};
    h.front_face = true;
    CHECK(h.facing_normal() == shade::vec3<T>(0, 1, 0));
    h.front_face = false;
    CHECK(h.facing_normal() == shade::vec3<T>(0, -1, 0));
    CHECK(h.n == shade::vec3<T>(0, 1, 0)); // the stored normal stays the surface's own
}

TEST_CASE_TEMPLATE("triangle_hit: u and v are the weights of v1 and v2", T, float, double) {
    shade::triangle_hit<T> h;
    h.barycentric = {T(0.5), T(0.125), T(0.375)};
    CHECK(h.u() == T(0.125));
    CHECK(h.v() == T(0.375));
}

TEST_CASE_TEMPLATE("detail::normalize_or_zero: unit for tiny and huge vectors, zero for bad ones", T, float, double) {
    using v = shade::vec3<T>;
    const T nan = std::numeric_limits<T>::quiet_NaN();
    // (3, 0, 4) / 5 = (0.6, 0, 0.8) at every scale; squaring 1e-30 (float: underflow) or
    // 1e30 (float: overflow) directly would lose it. (3, 0, 4) times the smallest
    // denormal is exact (3 and 4 denormal units), so it too gives (0.6, 0, 0.8).
    for (const T s : {T(1), T(1e-30), T(1e30), std::numeric_limits<T>::denorm_min()}) {
        CAPTURE(s);
        const v n = shade::detail::normalize_or_zero(v(3, 0, 4) * s);
        CHECK(std::abs(n.x - T(0.6)) <= 4 * std::numeric_limits<T>::epsilon());
        CHECK(n.y == T(0));
        CHECK(std::abs(n.z - T(0.8)) <= 4 * std::numeric_limits<T>::epsilon());
        CHECK(shade::detail::is_unit_normal(n));
    }
    CHECK(shade::detail::normalize_or_zero(v(0, 0, 0)) == v(0, 0, 0));
    CHECK(shade::detail::normalize_or_zero(v(nan, 1, 0)) == v(0, 0, 0));
    CHECK_FALSE(shade::detail::is_unit_normal(v(0, 0, 0)));
}

TEST_CASE_TEMPLATE("detail::normalize_expected_length: unit with a good scale, and with a bad one", T, float, double) {
    using v = shade::vec3<T>;
    const T inf = std::numeric_limits<T>::infinity();
    const T tol = 4 * std::numeric_limits<T>::epsilon();
    const auto is_0_6_0_0_8 = [&](const v& n) {
        return std::abs(n.x - T(0.6)) <= tol && n.y == T(0) && std::abs(n.z - T(0.8)) <= tol;
    };
    // |(3, 0, 4)| = 5, and 5 * 2^-3 = 0.625 lies in [0.5, 1): the scaled path, and the
    // same answer as normalize_or_zero.
    CHECK(is_0_6_0_0_8(shade::detail::normalize_expected_length(v(3, 0, 4), T(0.125))));
    // A scale far off: (3, 0, 4) 1e18 with scale 1 would square to 2.5e37 (fine) but
    // 1e30 to 2.5e61, infinite in float and finite in double; either way the fallback
    // (|w| > 4) gives the unit vector. A tiny scale (|w| < 1/4) and an infinite one
    // (2^k not a T) fall back too.
    CHECK(is_0_6_0_0_8(shade::detail::normalize_expected_length(v(3, 0, 4) * T(1e30), T(1))));
    CHECK(is_0_6_0_0_8(shade::detail::normalize_expected_length(v(3, 0, 4), std::ldexp(T(1), -40))));
    CHECK(is_0_6_0_0_8(shade::detail::normalize_expected_length(v(3, 0, 4), inf)));
    // Zero and NaN stay "no normal".
    CHECK_FALSE(shade::detail::is_unit_normal(shade::detail::normalize_expected_length(v(0, 0, 0), T(1))));
    CHECK_FALSE(shade::detail::is_unit_normal(
        shade::detail::normalize_expected_length(v(std::numeric_limits<T>::quiet_NaN(), 1, 0), T(1))));
}

TEST_CASE_TEMPLATE("detail::in_interval: closed, finite, NaN-proof", T, float, double) {
    const T inf = std::numeric_limits<T>::infinity();
    const T nan = std::numeric_limits<T>::quiet_NaN();
    CHECK(shade::detail::in_interval(T(0), T(0), T(1)));
    CHECK(shade::detail::in_interval(T(1), T(0), T(1)));
    CHECK_FALSE(shade::detail::in_interval(T(1.5), T(0), T(1)));
    CHECK_FALSE(shade::detail::in_interval(T(-0.5), T(0), T(1)));
    CHECK_FALSE(shade::detail::in_interval(nan, T(0), inf));
    CHECK_FALSE(shade::detail::in_interval(inf, T(0), inf)); // a hit must be a point
}
