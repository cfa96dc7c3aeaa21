#include <cmath>
#include <limits>

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/brdf/detail/directions.hpp>

#include "brdf/support.hpp"

using namespace brdf_test;

TEST_CASE_TEMPLATE("half_vector: normalize(l + v), also for nearly opposite grazing pairs", T, float, double) {
    // l = v: h = l. l = (1,0,0)-ish and v mirrored about z: h = +z.
    const vec3<T> l = glm::normalize(vec3<T>(1, 2, 2));
    CHECK(glm::length(shade::detail::half_vector(l, l) - l) < T(1e-6));
    const vec3<T> a = glm::normalize(vec3<T>(1, 0, 1)), b = glm::normalize(vec3<T>(-1, 0, 1));
    CHECK(glm::length(shade::detail::half_vector(a, b) - vec3<T>(0, 0, 1)) < T(1e-6));
    // l + v = (0, 0, 2e-30): squaring inside glm::normalize would underflow to 0 in float
    // (NaN); the scaled version returns +z.
    const vec3<T> g1(1, 0, T(1e-30)), g2(-1, 0, T(1e-30));
    const auto h = shade::detail::half_vector(g1, g2);
    CHECK(h == vec3<T>(0, 0, 1));
    const auto [h2, cos_d] = shade::detail::half_vector_and_cos(g1, g2);
    CHECK(h2 == vec3<T>(0, 0, 1));
    CHECK(close(cos_d, T(1e-30), T(1e-6))); // |l + v|/2 = 1e-30
}

TEST_CASE_TEMPLATE("half_vector_and_cos: the same unit vector and |l + v| on both sides of its direct floor", T, float,
                   double) {
    // l = v = s/2 (exact halving), s = 2^e (0.3, 0.5, 0.7), for e from far above to far below
    // the floor 2^(min_exponent / 2) of s.s (the direct path above it, the rescaled path
    // below): h and 2 cos_theta_d = |s| as computed in long double from the same components,
    // each within a few ulps, so nothing is lost to underflow (the components' squares lose
    // bits once they are subnormal).
    const T eps = std::numeric_limits<T>::epsilon();
    const int floor_exponent = std::numeric_limits<T>::min_exponent / 2; // of s.s
    const vec3<T> direction(T(0.3), T(0.5), T(0.7));
    const long double x = direction.x, y = direction.y, z = direction.z;
    const long double norm = std::sqrt(x * x + y * y + z * z);
    // Down to where the squares are below the smallest subnormal (so all would be 0).
    const int last = (std::numeric_limits<T>::min_exponent - std::numeric_limits<T>::digits) / 2 - 4;
    for (int e = floor_exponent / 2 + 8; e >= last; --e) {
        const T scale = std::ldexp(T(1), e);
        const vec3<T> half = direction * (scale / T(2));
        const auto [h, cos_d] = shade::detail::half_vector_and_cos(half, half);
        CAPTURE(e);
        CHECK(std::abs(static_cast<long double>(h.x) - x / norm) <= 4 * eps);
        CHECK(std::abs(static_cast<long double>(h.y) - y / norm) <= 4 * eps);
        CHECK(std::abs(static_cast<long double>(h.z) - z / norm) <= 4 * eps);
        CHECK(std::abs(2 * static_cast<long double>(cos_d) / static_cast<long double>(scale) / norm - 1) <= 4 * eps);
    }
    CHECK(shade::detail::direct_normalization_floor<T> == std::ldexp(T(1), floor_exponent));
    // The rescaled path alone: zero and NaN give (0, 0).
    CHECK(shade::detail::rescaled_unit_and_length(vec3<T>(0)).length == T(0));
    CHECK(shade::detail::rescaled_unit_and_length(vec3<T>(std::numeric_limits<T>::quiet_NaN())).unit == vec3<T>(0));
}

TEST_CASE_TEMPLATE("half_vector_and_cos: cos_theta_d = |l + v|/2 = (l.h + v.h)/2, symmetric in l and v", T, float, double) {
    // (l + v).h = |l + v| for h = (l + v)/|l + v|, so (l.h + v.h)/2 = |l + v|/2 for any l, v
    // (and = l.h = v.h when both are exactly unit). Rounded unit vectors make l.h and v.h
    // differ by (|v|^2 - |l|^2)/(2|l + v|), large when l ~ -v; their mean does not.
    const auto at = tilted<T>();
    for (const auto& p : random_pairs(at, 500)) {
        const auto [h, c] = shade::detail::half_vector_and_cos(p.l, p.v);
        const auto [h_swapped, c_swapped] = shade::detail::half_vector_and_cos(p.v, p.l);
        CHECK(h == h_swapped);
        CHECK(c == c_swapped);
        CHECK(std::abs(c - (glm::dot(p.l, h) + glm::dot(p.v, h)) / T(2)) <= T(8) * std::numeric_limits<T>::epsilon());
        CHECK(std::abs(glm::length(h) - T(1)) <= T(4) * std::numeric_limits<T>::epsilon());
    }
}

TEST_CASE_TEMPLATE("floored_cos and require_finite_peak", T, float, double) {
    const T eps = std::numeric_limits<T>::epsilon();
    CHECK(shade::detail::floored_cos(T(0.5)) == T(0.5));
    CHECK(shade::detail::floored_cos(T(0)) == eps);
    CHECK(shade::detail::floored_cos(T(-1)) == eps);
    CHECK(shade::detail::max_channel(rgb<T>(1, 3, 2)) == T(3));
    check_throws_naming([] { shade::detail::require_finite_peak("k_s", shade::infinity<T>); }, "k_s");
    CHECK_NOTHROW(shade::detail::require_finite_peak("k_s", std::numeric_limits<T>::max()));
}
