#include <cmath>
#include <limits>

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/core/frame.hpp>

namespace {

template <class T>
void check_orthonormal(const shade::frame<T>& f, const shade::vec3<T>& n) {
    const T eps = std::numeric_limits<T>::epsilon() * T(16);
    CHECK(std::abs(glm::length(f.t) - T(1)) <= eps);
    CHECK(std::abs(glm::length(f.b) - T(1)) <= eps);
    CHECK(std::abs(glm::dot(f.t, f.b)) <= eps);
    CHECK(std::abs(glm::dot(f.t, f.n)) <= eps);
    CHECK(std::abs(glm::dot(f.b, f.n)) <= eps);
    // Right-handed: t x b = n.
    CHECK(glm::length(glm::cross(f.t, f.b) - n) <= eps);
}

} // namespace

TEST_CASE_TEMPLATE("frame::from_normal is orthonormal for the axes, including -z", T, float, double) {
    using v = shade::vec3<T>;
    for (const v n : {v(0, 0, 1), v(0, 0, -1), v(1, 0, 0), v(-1, 0, 0), v(0, 1, 0), v(0, -1, 0)}) {
        CAPTURE(n.x); CAPTURE(n.y); CAPTURE(n.z);
        const auto f = shade::frame<T>::from_normal(n);
        check_orthonormal(f, n);
    }
}

TEST_CASE_TEMPLATE("frame::from_normal for n = +z is the identity frame", T, float, double) {
    // With sign = 1, a = -1/2 and c = 0 the formulas give t = (1,0,0), b = (0,1,0).
    const auto f = shade::frame<T>::from_normal({0, 0, 1});
    CHECK(f.t == shade::vec3<T>(1, 0, 0));
    CHECK(f.b == shade::vec3<T>(0, 1, 0));
}

TEST_CASE_TEMPLATE("frame::from_normal is orthonormal near the -z singularity of the one-chart formula", T, float, double) {
    using v = shade::vec3<T>;
    // Normals a hair away from -z, where Frisvad's 2012 single-chart method loses all
    // precision; the two-chart form must stay orthonormal.
    for (const T e : {T(1e-3), T(1e-5), T(1e-7), T(1e-12), T(0)}) {
        const v n = glm::normalize(v(e, e, T(-1)));
        check_orthonormal(shade::frame<T>::from_normal(n), n);
    }
}

TEST_CASE_TEMPLATE("frame::from_normal is orthonormal on a dense sphere of normals", T, float, double) {
    // A Fibonacci lattice of 2000 unit normals covers every direction evenly.
    const int count = 2000;
    for (int i = 0; i < count; ++i) {
        const T z = T(1) - (T(2) * T(i) + T(1)) / T(count);
        const T r = std::sqrt(T(1) - z * z);
        const T phi = T(2.399963229728653) * T(i);
        const shade::vec3<T> n(r * std::cos(phi), r * std::sin(phi), z);
        const auto f = shade::frame<T>::from_normal(n);
        check_orthonormal(f, f.n);
    }
}

TEST_CASE_TEMPLATE("frame::to_local and to_world are inverse and map n to +z", T, float, double) {
    const auto n = glm::normalize(shade::vec3<T>(1, 2, 3));
    const auto f = shade::frame<T>::from_normal(n);
    const auto local_n = f.to_local(n);
    CHECK(local_n.x == doctest::Approx(0).epsilon(1e-6));
    CHECK(local_n.z == doctest::Approx(1).epsilon(1e-6));
    const shade::vec3<T> w(T(0.3), T(-0.4), T(0.5));
    const auto back = f.to_world(f.to_local(w));
    CHECK(glm::length(back - w) < T(1e-6));
}

TEST_CASE_TEMPLATE("frame::from_normal_tangent keeps the tangent direction", T, float, double) {
    // Tangent (1,0,1) against n = +z: Gram-Schmidt removes the z part, leaving +x.
    const auto f = shade::frame<T>::from_normal_tangent({0, 0, 2}, {1, 0, 1});
    CHECK(glm::length(f.t - shade::vec3<T>(1, 0, 0)) < T(1e-6));
    CHECK(glm::length(f.b - shade::vec3<T>(0, 1, 0)) < T(1e-6));
    CHECK(f.n == shade::vec3<T>(0, 0, 1));
}

TEST_CASE_TEMPLATE("frame factories reject bad normals and tangents by name", T, float, double) {
    using v = shade::vec3<T>;
    const T nan = std::numeric_limits<T>::quiet_NaN();
    CHECK_THROWS_WITH_AS((void)shade::frame<T>::from_normal_checked(v(0, 0, 0)),
                         doctest::Contains("'normal'"), shade::invalid_parameter);
    CHECK_THROWS_WITH_AS((void)shade::frame<T>::from_normal_checked(v(nan, 0, 1)),
                         doctest::Contains("'normal' must be finite"), shade::invalid_parameter);
    CHECK_THROWS_WITH_AS((void)shade::frame<T>::from_normal_tangent(v(0, 0, 1), v(0, 0, 0)),
                         doctest::Contains("'tangent'"), shade::invalid_parameter);
    CHECK_THROWS_WITH_AS((void)shade::frame<T>::from_normal_tangent(v(0, 0, 1), v(0, 0, 5)),
                         doctest::Contains("parallel"), shade::invalid_parameter);
    // Tiny and huge but finite normals are fine: require_direction rescales first.
    const auto tiny = shade::frame<T>::from_normal_checked(v(0, 0, T(1e-30)));
    CHECK(tiny.n == v(0, 0, 1));
    const auto huge = shade::frame<T>::from_normal_checked(v(0, T(1e30), 0));
    CHECK(huge.n == v(0, 1, 0));
}

TEST_CASE_TEMPLATE("frame::from_normal_tangent is orthonormal to rounding for a tangent near the normal", T, float,
                   double) {
    // A tangent 2e-3 rad from the normal (just above the 1e-3 rejection): one Gram-Schmidt
    // projection leaves t·n off by about epsilon / 2e-3 (6e-5 in float); the second
    // projection brings it to a few epsilon.
    using v = shade::vec3<T>;
    const T eps = std::numeric_limits<T>::epsilon();
    for (const v& n : {v(0, 0, 1), glm::normalize(v(T(0.3), T(-0.5), T(0.8))), glm::normalize(v(1, 1, T(1e-3)))}) {
        const v side = glm::normalize(glm::cross(n, v(T(0.6), T(0.7), T(0.2))));
        const auto f = shade::frame<T>::from_normal_tangent(n, n + T(2e-3) * side);
        CHECK(std::abs(glm::dot(f.t, f.n)) <= 8 * eps);
        CHECK(std::abs(glm::dot(f.b, f.n)) <= 8 * eps);
        CHECK(std::abs(glm::dot(f.t, f.b)) <= 8 * eps);
        CHECK(std::abs(glm::length(f.t) - T(1)) <= 4 * eps);
        CHECK(glm::dot(f.t, side) > T(0.999)); // still the tangent's direction
    }
}
