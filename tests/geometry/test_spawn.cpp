// Spawned rays (shade/geometry/spawn.hpp) never hit the surface they leave: 10^6 rays per
// mesh and scalar type, half leaving outward and half inward from random points of a
// unit icosphere placed 10^5 units from the origin and of the jittered icosphere with
// slivers and needles near it; rays off far-away spheres and planes; and the bounds
// themselves hold against points computed in long double.

#include <cmath>
#include <cstdint>
#include <vector>

#include <doctest/doctest.h>

#include <shade/core/frame.hpp>
#include <shade/core/random.hpp>
#include <shade/core/sampling.hpp>
#include <shade/geometry/plane.hpp>
#include <shade/geometry/spawn.hpp>
#include <shade/geometry/sphere.hpp>
#include <shade/geometry/triangle_bvh.hpp>

#include "closed_meshes.hpp"

namespace {

template <class T>
using v3 = shade::vec3<T>;

// The mesh's vertices moved by `offset` (added in double, rounded to T once per vertex, so
// neighbours keep equal coordinates).
template <class T>
std::vector<shade::triangle<T>> triangles_of(const geometry_test::mesh<double>& m, const v3<double>& offset) {
    std::vector<v3<T>> vertices;
    for (const auto& v : m.vertices) vertices.push_back(v3<T>(v + offset));
    std::vector<shade::triangle<T>> out;
    for (const auto& f : m.faces)
        out.push_back({vertices[std::size_t(f[0])], vertices[std::size_t(f[1])], vertices[std::size_t(f[2])]});
    return out;
}

struct self_hit_count {
    std::size_t spawned = 0;
    std::size_t same_triangle = 0; ///< a ray reported the triangle it left (never possible exactly)
    std::size_t outward_hits = 0;  ///< an outward ray hit anything (impossible on a convex mesh)
};

// `pairs` points, each uniformly on a random triangle, are found by a ray from outside
// aimed at them; from each hit two rays are spawned, one into the hemisphere of the
// outward normal and one into the other (cosine-distributed about the normal).
template <class T, class Algorithm>
self_hit_count spawn_from_mesh(const std::vector<shade::triangle<T>>& tris, const v3<T>& centre, std::size_t pairs,
                               std::uint64_t seed) {
    const shade::triangle_bvh<T, Algorithm> accel(tris);
    shade::rng random(seed);
    self_hit_count count;
    for (std::size_t k = 0; k < pairs; ++k) {
        const auto f = std::size_t(random.uniform<double>() * double(tris.size())) % tris.size();
        const auto& tri = tris[f];
        double b1 = random.uniform<double>(), b2 = random.uniform<double>();
        if (b1 + b2 > 1) b1 = 1 - b1, b2 = 1 - b2;
        const v3<double> target = (1 - b1 - b2) * v3<double>(tri.v0) + b1 * v3<double>(tri.v1) + b2 * v3<double>(tri.v2);
        // From a point 3 units outside along a direction in the triangle's outer hemisphere.
        const v3<double> n = glm::normalize(v3<double>(tri.normal()));
        const auto frame = shade::frame<double>::from_normal(n);
        const v3<double> out_dir =
            frame.to_world(shade::square_to_cosine_hemisphere(shade::vec2<double>(random.uniform<double>(), random.uniform<double>())));
        const v3<T> origin(target + 3.0 * out_dir);
        const auto h = accel.closest(shade::ray<T>{origin, v3<T>(target) - origin});
        if (!h) continue; // grazing a neighbour's edge can miss the chosen point's triangle
        for (const double side : {1.0, -1.0}) {
            const auto hn = shade::frame<double>::from_normal(side * v3<double>(h->hit.n));
            const v3<T> w(hn.to_world(
                shade::square_to_cosine_hemisphere(shade::vec2<double>(random.uniform<double>(), random.uniform<double>()))));
            const shade::ray<T> spawned = shade::spawn_ray(h->hit, w);
            ++count.spawned;
            const auto again = accel.closest(spawned);
            if (again && again->primitive == h->primitive) ++count.same_triangle;
            if (again && side > 0) ++count.outward_hits;
        }
    }
    (void)centre;
    return count;
}

} // namespace

TEST_CASE_TEMPLATE("spawn_ray: no self-hit in 10^6 rays off a mesh 10^5 units from the origin", T, float, double) {
    // The unit icosphere is convex: a ray leaving it outward hits nothing at all, and one
    // leaving inward hits the far side, never its own triangle.
    const auto m = geometry_test::icosphere<double>(4);
    const v3<double> offset(1e5, -0.6e5, 0.8e5);
    const auto tris = triangles_of<T>(m, offset);
    const auto c = spawn_from_mesh<T, shade::moller_trumbore>(tris, v3<T>(offset), 500000, 1);
    CHECK(c.spawned >= 990000);
    CHECK(c.same_triangle == 0);
    CHECK(c.outward_hits == 0);
    const auto w = spawn_from_mesh<T, shade::watertight>(tris, v3<T>(offset), 50000, 2);
    CHECK(w.same_triangle == 0);
    CHECK(w.outward_hits == 0);
}

TEST_CASE_TEMPLATE("spawn_ray: no self-hit in 10^6 rays off the jittered icosphere with slivers", T, float, double) {
    const auto m = geometry_test::jittered_icosphere_with_slivers<double>(4);
    const auto tris = triangles_of<T>(m, v3<double>(0));
    const auto c = spawn_from_mesh<T, shade::moller_trumbore>(tris, v3<T>(0), 500000, 3);
    CHECK(c.spawned >= 990000);
    CHECK(c.same_triangle == 0);
    const auto w = spawn_from_mesh<T, shade::watertight>(tris, v3<T>(0), 50000, 4);
    CHECK(w.same_triangle == 0);
}

TEST_CASE_TEMPLATE("spawn_ray: spheres and planes far from the origin are not hit again", T, float, double) {
    shade::rng random(5);
    const shade::sphere<T> s(v3<T>(T(1e5), T(-2e5), T(3e4)), T(0.75));
    const shade::plane<T> pl(v3<T>(T(-3e5), T(1e5), T(2e5)), glm::normalize(v3<T>(T(0.3), T(-0.5), T(0.8))));
    int self_hits = 0, spawned = 0;
    for (int k = 0; k < 20000; ++k) {
        const v3<T> from = s.center() + T(3) * v3<T>(shade::square_to_uniform_sphere(
                                                shade::vec2<T>(random.uniform<T>(), random.uniform<T>())));
        const auto h = shade::intersect(shade::ray<T>{from, s.center() - from}, s);
        REQUIRE(h);
        // Outward: the sphere is convex, nothing to hit. Inward (the cosine to -n at least
        // 0.05, so the exact chord is at least 0.1 R): the far side, never a point within
        // 1e-3 R of the origin.
        const auto frame_out = shade::frame<T>::from_normal(h->n);
        const v3<T> out = frame_out.to_world(shade::square_to_cosine_hemisphere(shade::vec2<T>(random.uniform<T>(), random.uniform<T>())));
        ++spawned;
        if (shade::intersect(shade::spawn_ray(*h, out), s)) ++self_hits;
        v3<T> in = shade::frame<T>::from_normal(-h->n).to_world(
            shade::square_to_cosine_hemisphere(shade::vec2<T>(random.uniform<T>(), random.uniform<T>())));
        if (glm::dot(in, -h->n) < T(0.05)) continue;
        ++spawned;
        const auto back = shade::intersect(shade::spawn_ray(*h, in), s);
        if (!back || back->front_face || glm::length(back->p - h->p) < T(1e-3) * s.radius()) ++self_hits;
    }
    for (int k = 0; k < 20000; ++k) {
        const v3<T> from = pl.point() + T(10) * v3<T>(shade::square_to_uniform_sphere(
                                                 shade::vec2<T>(random.uniform<T>(), random.uniform<T>())));
        const v3<T> to = pl.point() + T(5) * (random.uniform<T>() - T(0.5)) * pl.tangent() +
                         T(5) * (random.uniform<T>() - T(0.5)) * pl.bitangent();
        const auto h = shade::intersect(shade::ray<T>{from, to - from}, pl);
        if (!h) continue;
        for (const T side : {T(1), T(-1)}) {
            const v3<T> w = shade::frame<T>::from_normal(side * h->n)
                                .to_world(shade::square_to_cosine_hemisphere(shade::vec2<T>(random.uniform<T>(), random.uniform<T>())));
            ++spawned;
            if (shade::intersect(shade::spawn_ray(*h, w), pl)) ++self_hits;
        }
    }
    CHECK(spawned > 50000);
    CHECK(self_hits == 0);
}

TEST_CASE_TEMPLATE("hit::p_error bounds the distance of p from the surface (long double reference)", T, float, double) {
    // Triangle hits 10^5 from the origin: the exact distance of p from the triangle's
    // plane, in long double, is within dot(|n|, p_error), the offset spawn_ray applies.
    shade::rng random(9);
    const v3<T> base(T(1e5), T(-0.6e5), T(0.8e5));
    int checked = 0;
    for (int k = 0; k < 20000; ++k) {
        const auto r3 = [&] { return v3<T>(random.uniform<T>(), random.uniform<T>(), random.uniform<T>()) - T(0.5); };
        const shade::triangle<T> tri{base + r3(), base + r3(), base + r3()};
        const v3<T> target = tri.v0 + T(0.25) * (tri.v1 - tri.v0) + T(0.25) * (tri.v2 - tri.v0);
        const v3<T> from = target + T(2) * glm::normalize(r3());
        const auto h = shade::intersect(shade::ray<T>{from, target - from}, tri);
        if (!h) continue;
        using L = long double;
        const L e1[3] = {L(tri.v1.x) - L(tri.v0.x), L(tri.v1.y) - L(tri.v0.y), L(tri.v1.z) - L(tri.v0.z)};
        const L e2[3] = {L(tri.v2.x) - L(tri.v0.x), L(tri.v2.y) - L(tri.v0.y), L(tri.v2.z) - L(tri.v0.z)};
        const L nx = e1[1] * e2[2] - e1[2] * e2[1], ny = e1[2] * e2[0] - e1[0] * e2[2], nz = e1[0] * e2[1] - e1[1] * e2[0];
        const L len = std::sqrt(nx * nx + ny * ny + nz * nz);
        const L dist = std::abs((L(h->p.x) - L(tri.v0.x)) * nx + (L(h->p.y) - L(tri.v0.y)) * ny +
                                (L(h->p.z) - L(tri.v0.z)) * nz) / len;
        CHECK(double(dist) <= double(glm::dot(glm::abs(h->n), h->p_error)));
        ++checked;
    }
    CHECK(checked > 10000);
}
