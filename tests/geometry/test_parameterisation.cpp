// The uv and dp/du of the hit records of plane, sphere and triangle, and the shading frame
// surface_at builds from them.

#include <cmath>
#include <numbers>

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/core/random.hpp>
#include <shade/geometry/hit.hpp>
#include <shade/geometry/plane.hpp>
#include <shade/geometry/sphere.hpp>
#include <shade/geometry/triangle.hpp>
#include <shade/brdf/lambert.hpp>
#include <shade/shading/checker.hpp>

namespace {

template <class T>
T tol() {
    return sizeof(T) == 4 ? T(2e-5) : T(1e-12);
}

template <class T>
bool near(const shade::vec3<T>& a, const shade::vec3<T>& b, T eps) {
    return glm::length(a - b) <= eps * (T(1) + glm::length(b));
}

template <class T>
bool near(const shade::vec2<T>& a, const shade::vec2<T>& b, T eps) {
    return glm::length(a - b) <= eps * (T(1) + glm::length(b));
}

// The point of the sphere (c, R) at uv, from shade::sphere's parameterisation:
// phi = 2 pi u, theta = pi (1 - v), p = c + R (sin theta cos phi, sin theta sin phi, cos theta).
template <class T>
shade::vec3<T> sphere_point(const shade::vec3<T>& c, T radius, const shade::vec2<T>& uv) {
    const T phi = T(2) * std::numbers::pi_v<T> * uv.x;
    const T theta = std::numbers::pi_v<T> * (T(1) - uv.y);
    return c + radius * shade::vec3<T>(std::sin(theta) * std::cos(phi),
                                       std::sin(theta) * std::sin(phi), std::cos(theta));
}

template <class T>
shade::vec3<T> random_unit(shade::rng& g) {
    const T z = T(2) * g.uniform<T>() - T(1);
    const T phi = T(2) * std::numbers::pi_v<T> * g.uniform<T>();
    const T s = std::sqrt(T(1) - z * z);
    return {s * std::cos(phi), s * std::sin(phi), z};
}

} // namespace

TEST_CASE_TEMPLATE("plane: uv are world coordinates along tangent and bitangent", T, float, double) {
    using v3 = shade::vec3<T>;
    const T s = T(1) / std::sqrt(T(2));
    // Normal +z, tangent (1, 1, 0)/sqrt 2, so bitangent = cross(n, t) = (-1, 1, 0)/sqrt 2.
    const shade::plane<T> pl(v3(0, 0, 1), v3(0, 0, 2), v3(1, 1, 0));
    CHECK(near(pl.tangent(), v3(s, s, 0), tol<T>()));
    CHECK(near(pl.bitangent(), v3(-s, s, 0), tol<T>()));
    // Straight down onto (3, 1, 1): offset (3, 1, 0), u = 4/sqrt 2 = 2 sqrt 2, v = -2/sqrt 2.
    const auto h = shade::intersect(shade::ray<T>::checked(v3(3, 1, 5), v3(0, 0, -1)), pl);
    REQUIRE(h);
    CHECK(near(h->uv, shade::vec2<T>(T(2) * std::sqrt(T(2)), -std::sqrt(T(2))), tol<T>()));
    CHECK(h->dpdu == pl.tangent());
    // The default frame is orthonormal and right-handed, and p = point + u t + v b.
    const shade::plane<T> tilted(v3(1, -2, 0.5), v3(0.3, -0.2, 0.9));
    CHECK(near(glm::cross(tilted.tangent(), tilted.bitangent()), tilted.normal(), tol<T>()));
    CHECK(std::abs(glm::dot(tilted.tangent(), tilted.normal())) <= tol<T>());
    shade::rng g(7);
    for (int i = 0; i < 100; ++i) {
        const v3 o = tilted.point() + tilted.normal() * T(3) + T(2) * random_unit<T>(g);
        const auto hi = shade::intersect(shade::ray<T>::checked(o, -tilted.normal() + T(0.3) * random_unit<T>(g)), tilted);
        REQUIRE(hi);
        const v3 rebuilt = tilted.point() + hi->uv.x * tilted.tangent() + hi->uv.y * tilted.bitangent();
        CHECK(near(rebuilt, hi->p, T(10) * tol<T>()));
    }
}

TEST_CASE_TEMPLATE("plane: a tangent parallel to the normal is rejected by name", T, float, double) {
    using v3 = shade::vec3<T>;
    CHECK_THROWS_WITH_AS((void)shade::plane<T>(v3(0), v3(0, 0, 1), v3(0, 0, 3)),
                         doctest::Contains("'tangent'"), shade::invalid_parameter);
    CHECK_THROWS_WITH_AS((void)shade::plane<T>(v3(0), v3(0, 0, 1), v3(0)), doctest::Contains("'tangent'"),
                         shade::invalid_parameter);
}

TEST_CASE_TEMPLATE("sphere: uv and dp/du at known points", T, float, double) {
    using v3 = shade::vec3<T>;
    const T pi = std::numbers::pi_v<T>;
    const v3 c(1, 2, 3);
    const shade::sphere<T> s(c, T(2));
    // Each ray comes straight in along -axis and hits where the outward normal is axis.
    struct known {
        v3 axis;
        shade::vec2<T> uv;  // (phi / 2 pi, 1 - theta / pi)
        v3 dpdu;            // 2 pi R (-n_y, n_x, 0), R = 2
    };
    const known cases[] = {
        {v3(1, 0, 0), {T(0), T(0.5)}, v3(0, 4 * pi, 0)},
        {v3(0, 1, 0), {T(0.25), T(0.5)}, v3(-4 * pi, 0, 0)},
        {v3(-1, 0, 0), {T(0.5), T(0.5)}, v3(0, -4 * pi, 0)},
        {v3(0, -1, 0), {T(0.75), T(0.5)}, v3(4 * pi, 0, 0)},
        {v3(0, 0, 1), {T(0), T(1)}, v3(0)},   // north pole: dp/du = 0
        {v3(0, 0, -1), {T(0), T(0)}, v3(0)},  // south pole
    };
    for (const known& k : cases) {
        CAPTURE(k.axis);
        const auto h = shade::intersect(shade::ray<T>::checked(c + T(10) * k.axis, -k.axis), s);
        REQUIRE(h);
        CHECK(near(h->uv, k.uv, tol<T>()));
        CHECK(near(h->dpdu, k.dpdu, T(4) * tol<T>()));
    }
}

TEST_CASE_TEMPLATE("sphere: uv rebuild the point, dp/du is the derivative, (u, v) is right-handed", T, float, double) {
    using v3 = shade::vec3<T>;
    const v3 c(-1, 0.5, 2);
    const T radius = T(1.5);
    const shade::sphere<T> s(c, radius);
    shade::rng g(11);
    const T h = sizeof(T) == 4 ? T(1e-3) : T(1e-6); // finite-difference step in u and v
    for (int i = 0; i < 200; ++i) {
        const v3 toward = random_unit<T>(g);
        const auto hi = shade::intersect(shade::ray<T>::checked(c + T(5) * toward, -toward), s);
        REQUIRE(hi);
        const shade::vec2<T> uv = hi->uv;
        CHECK(uv.x >= T(0));
        CHECK(uv.x < T(1));
        CHECK(uv.y >= T(0));
        CHECK(uv.y <= T(1));
        CHECK(near(sphere_point(c, radius, uv), hi->p, T(10) * tol<T>()));
        if (uv.y < T(0.01) || uv.y > T(0.99)) continue; // keep the differences off the poles
        const v3 dpdu = (sphere_point(c, radius, uv + shade::vec2<T>(h, 0)) -
                         sphere_point(c, radius, uv - shade::vec2<T>(h, 0))) / (T(2) * h);
        const v3 dpdv = (sphere_point(c, radius, uv + shade::vec2<T>(0, h)) -
                         sphere_point(c, radius, uv - shade::vec2<T>(0, h))) / (T(2) * h);
        // Central differences: error ~ h^2 |p'''| plus rounding / h.
        CHECK(near(hi->dpdu, dpdu, sizeof(T) == 4 ? T(1e-2) : T(1e-6)));
        CHECK(std::abs(glm::dot(hi->dpdu, hi->n)) <= T(100) * tol<T>() * glm::length(hi->dpdu));
        CHECK(glm::dot(glm::cross(hi->dpdu, dpdv), hi->n) > T(0));
    }
}

TEST_CASE_TEMPLATE("triangle: barycentric uv by default, per-vertex uv when given", T, float, double) {
    using v3 = shade::vec3<T>;
    using v2 = shade::vec2<T>;
    const shade::triangle<T> tri{v3(0, 0, 0), v3(2, 0, 0), v3(0, 3, 0)};
    // Down onto (0.6, 1.5, 0): b1 = 0.6 / 2 = 0.3, b2 = 1.5 / 3 = 0.5, b0 = 0.2.
    const auto r = shade::ray<T>::checked(v3(0.6, 1.5, 4), v3(0, 0, -1));
    const auto x = shade::find_intersection(r, tri);
    REQUIRE(x);
    const auto h = shade::make_hit(tri, *x);
    CHECK(near(h.uv, v2(T(0.3), T(0.5)), tol<T>()));
    CHECK(h.dpdu == v3(2, 0, 0));
    // The full intersect fills the same parameterisation.
    const auto full = shade::intersect(r, tri);
    REQUIRE(full);
    CHECK(full->uv == h.uv);
    CHECK(full->dpdu == h.dpdu);
    // The default triangle_uv is the barycentric parameterisation.
    const auto same = shade::make_hit(tri, *x, shade::triangle_uv<T>{});
    CHECK(same.uv == h.uv);
    CHECK(same.dpdu == h.dpdu);

    // uv0 = (0.5, 0.5), uv1 = (0.5, 1.5), uv2 = (-1, 0.5): duv1 = (0, 1), duv2 = (-1.5, 0),
    // det = 0 * 0 - 1 * (-1.5) = 1.5, dp/du = (0 * e1 - 1 * e2) / 1.5 = (0, -2, 0): going
    // the whole edge e2 = (0, 3, 0) changes u by -1.5. dp/dv = e1 = (2, 0, 0), and
    // cross(dp/du, dp/dv) = (0, 0, 4) is along the normal +z (det > 0: right-handed).
    const shade::triangle_uv<T> uvs{v2(0.5, 0.5), v2(0.5, 1.5), v2(-1, 0.5)};
    const auto mapped = shade::make_hit(tri, *x, uvs);
    // uv = 0.2 (0.5, 0.5) + 0.3 (0.5, 1.5) + 0.5 (-1, 0.5) = (-0.25, 0.8).
    CHECK(near(mapped.uv, v2(T(-0.25), T(0.8)), tol<T>()));
    CHECK(near(mapped.dpdu, v3(0, -2, 0), tol<T>()));
    CHECK(mapped.t == h.t);
    CHECK(mapped.p == h.p);

    // Collinear uv (det = 0) fall back to the barycentric dp/du, v1 - v0.
    const shade::triangle_uv<T> flat{v2(0, 0), v2(1, 1), v2(2, 2)};
    const auto degenerate = shade::make_hit(tri, *x, flat);
    CHECK(degenerate.dpdu == v3(2, 0, 0));
    CHECK(near(degenerate.uv, v2(T(1.3), T(1.3)), tol<T>())); // 0.3 (1, 1) + 0.5 (2, 2)
}

TEST_CASE_TEMPLATE("surface_at: the frame's tangent is dp/du, its normal faces the ray", T, float, double) {
    using v3 = shade::vec3<T>;
    const shade::sphere<T> s(v3(0), T(1));
    // From outside along -x onto (1, 0, 0): n = +x, dp/du = 2 pi (0, 1, 0).
    const auto outside = shade::intersect(shade::ray<T>::checked(v3(5, 0, 0), v3(-1, 0, 0)), s);
    REQUIRE(outside);
    const auto at = shade::surface_at(*outside);
    CHECK(at.p == outside->p);
    CHECK(at.uv == outside->uv);
    CHECK(near(at.shading.n, v3(1, 0, 0), tol<T>()));
    CHECK(near(at.shading.t, v3(0, 1, 0), tol<T>()));
    CHECK(near(at.shading.b, v3(0, 0, 1), tol<T>())); // cross(n, t) = dp/dv's direction
    // From inside, the ray hits the back face at (1, 0, 0): normal -x, same tangent,
    // bitangent cross(-x, y) = -z: right-handed, against dp/dv.
    const auto inside = shade::intersect(shade::ray<T>::checked(v3(0), v3(1, 0, 0)), s);
    REQUIRE(inside);
    CHECK(!inside->front_face);
    const auto back = shade::surface_at(*inside);
    CHECK(near(back.shading.n, v3(-1, 0, 0), tol<T>()));
    CHECK(near(back.shading.t, v3(0, 1, 0), tol<T>()));
    CHECK(near(back.shading.b, v3(0, 0, -1), tol<T>()));
    // At the pole dp/du is zero: an arbitrary orthonormal frame around the normal.
    const auto pole = shade::intersect(shade::ray<T>::checked(v3(0, 0, 5), v3(0, 0, -1)), s);
    REQUIRE(pole);
    const auto at_pole = shade::surface_at(*pole);
    CHECK(near(at_pole.shading.n, v3(0, 0, 1), tol<T>()));
    CHECK(std::abs(glm::dot(at_pole.shading.t, at_pole.shading.n)) <= tol<T>());
    CHECK(near(glm::cross(at_pole.shading.t, at_pole.shading.b), at_pole.shading.n, tol<T>()));
    // A tiny tangent (squares underflow in float) still gives a unit t.
    const auto tiny = shade::surface_point<T>::at(v3(0), v3(0, 0, 1), v3(T(1e-30), 0, 0), {});
    CHECK(near(tiny.shading.t, v3(1, 0, 0), tol<T>()));
}

TEST_CASE_TEMPLATE("checker_2d on uv shows both cells on library sphere hits", T, float, double) {
    using v3 = shade::vec3<T>;
    const shade::sphere<T> s(v3(0), T(1));
    const shade::checker_2d pattern(shade::lambert<T>(shade::rgb<T>(1)), shade::lambert<T>(shade::rgb<T>(0)),
                                    T(0.25), shade::checker_plane::uv, T(0));
    int count[2] = {0, 0};
    shade::rng g(3);
    for (int i = 0; i < 64; ++i) {
        const v3 toward = random_unit<T>(g);
        const auto h = shade::intersect(shade::ray<T>::checked(T(4) * toward, -toward), s);
        REQUIRE(h);
        ++count[pattern.parity(shade::surface_at(*h))];
    }
    CHECK(count[0] > 10);
    CHECK(count[1] > 10);
}
