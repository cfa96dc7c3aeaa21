// shade::make_spherical_triangle and shade::sample_spherical_triangle (Arvo 1995): the
// solid angle against independent formulas, and samples uniform over the solid angle.

#include <cmath>
#include <numbers>

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/core/random.hpp>
#include <shade/core/sampling.hpp>
#include <shade/core/spherical_triangle.hpp>
#include <shade/geometry/ray.hpp>
#include <shade/geometry/triangle.hpp>

namespace {

template <class T>
using v3 = shade::vec3<T>;
template <class T>
using v2 = shade::vec2<T>;

constexpr double pi = std::numbers::pi;

// The solid angle of the triangle v0 v1 v2 seen from p by Van Oosterom, Strackee 1983,
// "The Solid Angle of a Plane Triangle", IEEE Trans. Biomedical Engineering 30(2), eq. 8:
// tan(Omega / 2) = |a·(b x c)| / (|a||b||c| + (a·b)|c| + (a·c)|b| + (b·c)|a|), with a, b, c
// the vectors from p to the vertices. A formula independent of the internal angles.
double van_oosterom(const glm::dvec3& p, const glm::dvec3& v0, const glm::dvec3& v1, const glm::dvec3& v2) {
    const glm::dvec3 a = v0 - p, b = v1 - p, c = v2 - p;
    const double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
    const double num = std::abs(glm::dot(a, glm::cross(b, c)));
    const double den = la * lb * lc + glm::dot(a, b) * lc + glm::dot(a, c) * lb + glm::dot(b, c) * la;
    double half = std::atan2(num, den);
    if (half < 0) half += pi;
    return 2 * half;
}

glm::dvec3 random_point(shade::rng& g, double scale) {
    return scale * glm::dvec3(2 * g.uniform<double>() - 1, 2 * g.uniform<double>() - 1, 2 * g.uniform<double>() - 1);
}

} // namespace

TEST_CASE_TEMPLATE("spherical triangle: an octant subtends pi / 2 with three right angles", T, float, double) {
    // The triangle (1,0,0), (0,1,0), (0,0,1) seen from the origin covers one eighth of the
    // sphere, 4 pi / 8, and each of its angles is pi / 2 (the coordinate planes meet at right angles).
    const auto s = shade::make_spherical_triangle(v3<T>(0), v3<T>(1, 0, 0), v3<T>(0, 1, 0), v3<T>(0, 0, 1));
    CHECK(s.area == doctest::Approx(pi / 2).epsilon(1e-7));
    CHECK(s.alpha == doctest::Approx(pi / 2).epsilon(1e-7));
    CHECK(s.beta == doctest::Approx(pi / 2).epsilon(1e-7));
    CHECK(s.gamma == doctest::Approx(pi / 2).epsilon(1e-7));
}

TEST_CASE("spherical triangle: the solid angle agrees with Van Oosterom and Strackee's formula") {
    shade::rng g(11);
    int checked = 0;
    for (int k = 0; k < 2000; ++k) {
        const glm::dvec3 p = random_point(g, 1), v0 = random_point(g, 2), v1 = random_point(g, 2), v2 = random_point(g, 2);
        const auto s = shade::make_spherical_triangle(p, v0, v1, v2);
        const double reference = van_oosterom(p, v0, v1, v2);
        CAPTURE(reference);
        CHECK(s.area == doctest::Approx(reference).epsilon(1e-9).scale(1e-12));
        ++checked;
    }
    CHECK(checked == 2000);
}

TEST_CASE("spherical triangle: small and far, the solid angle tends to A cos / r^2") {
    // A right triangle of legs 1 in the plane z = 1000 seen from the origin: area 1/2,
    // cos = 1 at its corner direction; Omega = A cos / r^2 to relative O((size / r)^2).
    const auto s = shade::make_spherical_triangle(glm::dvec3(0), glm::dvec3(0, 0, 1000), glm::dvec3(1, 0, 1000),
                                                  glm::dvec3(0, 1, 1000));
    CHECK(s.area == doctest::Approx(0.5 / 1e6).epsilon(2e-6));
}

TEST_CASE("spherical triangle: degenerate triangles have area 0") {
    const glm::dvec3 o(0);
    // p in the triangle's plane.
    CHECK(shade::make_spherical_triangle(o, glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0), glm::dvec3(1, 1, 0)).area == 0);
    // A vertex at p.
    CHECK(shade::make_spherical_triangle(o, o, glm::dvec3(0, 1, 0), glm::dvec3(1, 1, 1)).area == 0);
    // Collinear vertices.
    CHECK(shade::make_spherical_triangle(o, glm::dvec3(1, 0, 1), glm::dvec3(2, 0, 1), glm::dvec3(3, 0, 1)).area == 0);
}

TEST_CASE_TEMPLATE("spherical triangle: samples lie in the triangle and are uniform by solid angle", T, float, double) {
    // For triangles seen from p, the stratified samples' mean of g must be the integral of
    // g over the triangle's directions divided by Omega: the integral is estimated
    // independently with uniform directions over the whole sphere that hit the triangle.
    const auto g = [](const glm::dvec3& w) { return 1.0 + w.x + 2.0 * w.z * w.z - 0.5 * w.y * w.x; };
    shade::rng r(3);
    int tested = 0;
    for (int k = 0; tested < 6; ++k) {
        const v3<T> p(random_point(r, 0.5));
        const v3<T> q0(random_point(r, 2)), q1(random_point(r, 2)), q2(random_point(r, 2));
        const shade::triangle<T> tri{q0, q1, q2};
        const auto s = shade::make_spherical_triangle(p, q0, q1, q2);
        if (s.area < 0.05) continue; // too few grid directions would hit it
        ++tested;
        CAPTURE(k);
        const int n = 128;
        double mean = 0;
        int outside = 0;
        for (int j = 0; j < n; ++j) {
            for (int i = 0; i < n; ++i) {
                const v3<T> w = shade::sample_spherical_triangle(s, shade::stratified_u<T>(i, j, n, v2<T>(T(0.5))));
                CHECK(std::abs(double(glm::length(w)) - 1) < 1e-5);
                // Inside: the ray from p along w meets the triangle (a sample on an edge may
                // round outside, hence the small allowance).
                if (!shade::intersect(shade::ray<T>{p, w}, tri)) ++outside;
                mean += g(glm::dvec3(w));
            }
        }
        mean /= double(n) * double(n);
        CHECK(outside <= n * n / 1000);
        const int m = 1024;
        double integral = 0, solid_angle = 0;
        for (int j = 0; j < m; ++j) {
            for (int i = 0; i < m; ++i) {
                const v3<T> w = shade::square_to_uniform_sphere(shade::stratified_u<T>(i, j, m, v2<T>(T(0.5))));
                if (!shade::intersect(shade::ray<T>{p, w}, tri)) continue;
                integral += g(glm::dvec3(w));
                solid_angle += 1;
            }
        }
        const double cell = 4 * pi / (double(m) * double(m));
        CHECK(solid_angle * cell == doctest::Approx(s.area).epsilon(5e-3));
        CHECK(mean == doctest::Approx(integral / solid_angle).epsilon(5e-3));
    }
}
