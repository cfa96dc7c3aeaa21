// triangle_batch: the SoA, division-deferred Möller-Trumbore must give bitwise the same
// results as the scalar shade::moller_trumbore on every lane: same hit or miss, same t,
// barycentrics and front_face (compared as bit patterns, so even -0 vs +0 would fail),
// and from intersect_closest the same p and n.

#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <random>
#include <span>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include <shade/geometry/triangle.hpp>
#include <shade/geometry/triangle_batch.hpp>

namespace {

template <class T>
using v3 = shade::vec3<T>;

template <class T>
auto bits(T x) {
    if constexpr (sizeof(T) == 4)
        return std::bit_cast<std::uint32_t>(x);
    else
        return std::bit_cast<std::uint64_t>(x);
}

template <class T>
bool same_bits(const v3<T>& a, const v3<T>& b) {
    return bits(a.x) == bits(b.x) && bits(a.y) == bits(b.y) && bits(a.z) == bits(b.z);
}

// Counts lanes compared and lanes hit, so a test can also assert that it exercised both
// outcomes (a comparison that only ever sees misses proves little).
struct tally {
    std::size_t lanes = 0;
    std::size_t hits = 0;
};

// Compares every lane of batch against the scalar algorithm on the same triangle, and
// intersect_closest against the nearest scalar hit (lowest lane on equal t).
template <class T, std::size_t N, class Triangles>
void check_against_scalar(const shade::ray<T>& r, const shade::triangle_batch<T, N>& batch,
                          const Triangles& packed, // the triangles the batch holds, in lane order
                          shade::culling cull, tally& count) {
    const std::span<const shade::triangle<T>> tris(packed);
    const auto all = shade::intersect(r, batch, cull);
    // Every form of the kernel must give the same bits as the one intersect chose here:
    // the portable one-lane-at-a-time kernel (compilers without GNU vector extensions),
    // the kernel for the build's own target and, on x86-64 where this CPU has AVX or
    // AVX-512F, the AVX and AVX-512F kernels that intersect selects at run time in builds
    // without -mavx (compared in every build, -mavx and SHADE_NO_RUNTIME_DISPATCH included).
    std::vector<shade::triangle_batch_hits<T, N>> forms{
        shade::detail::intersect_batch<shade::detail::scalar_lanes<T>>(r, batch, cull),
        shade::detail::intersect_batch<shade::detail::default_lanes<T, N>>(r, batch, cull)};
    // The same triangles as vertices only (detail::vertex_batch, shade::triangle_bvh's
    // leaves), whose edges and normal the kernel forms itself: the same bits in every form.
    const shade::detail::vertex_batch<T, N> vertices(tris.data(), batch.size());
    forms.push_back(shade::detail::intersect_batch<shade::detail::scalar_lanes<T>>(r, vertices, cull));
    forms.push_back(shade::detail::intersect_batch<shade::detail::default_lanes<T, N>>(r, vertices, cull));
#if defined(__GNUC__) && defined(__x86_64__)
    if (shade::detail::cpu_has_avx()) {
        forms.push_back(shade::detail::intersect_batch_avx(r, batch, cull));
        forms.push_back(shade::detail::intersect_batch_avx(r, vertices, cull));
    }
    if constexpr (shade::detail::whole_avx512_steps<T, N>) {
        if (shade::detail::cpu_has_avx512f()) {
            forms.push_back(shade::detail::intersect_batch_avx512(r, batch, cull));
            forms.push_back(shade::detail::intersect_batch_avx512(r, vertices, cull));
        }
    }
#endif
    for (const auto& form : forms) {
        CHECK(form.hit_bits == all.hit_bits);
        CHECK(form.front_bits == all.front_bits);
        for (std::size_t i = 0; i < N; ++i) {
            CHECK(bits(form.t[i]) == bits(all.t[i]));
            CHECK(bits(form.b0[i]) == bits(all.b0[i]));
            CHECK(bits(form.b1[i]) == bits(all.b1[i]));
            CHECK(bits(form.b2[i]) == bits(all.b2[i]));
        }
    }
    // The any-hit form (shade::triangle_bvh::any's leaves) decides as hit_bits does, in
    // its portable and build-target forms on both layouts (its AVX form runs inlined in
    // the eight-wide walk, checked against brute force in test_bvh.cpp).
    const bool any_hit = all.hit_bits != 0;
    CHECK(shade::detail::intersect_batch_any<shade::detail::scalar_lanes<T>>(r, batch, cull) == any_hit);
    CHECK(shade::detail::intersect_batch_any<shade::detail::default_lanes<T, N>>(r, batch, cull) == any_hit);
    CHECK(shade::detail::intersect_batch_any<shade::detail::scalar_lanes<T>>(r, vertices, cull) == any_hit);
    CHECK(shade::detail::intersect_batch_any<shade::detail::default_lanes<T, N>>(r, vertices, cull) == any_hit);
    // Without its own test of t_min (for the walks that test the ray): the same decision
    // for the rays that have t_min >= 0.
    if (r.t_min >= T(0)) {
        CHECK(shade::detail::intersect_batch_any<shade::detail::scalar_lanes<T>, true>(r, vertices, cull) == any_hit);
        CHECK(shade::detail::intersect_batch_any<shade::detail::default_lanes<T, N>, true>(r, vertices, cull) ==
              any_hit);
    }
    std::optional<std::size_t> nearest;
    std::optional<shade::triangle_hit<T>> nearest_hit;
    for (std::size_t i = 0; i < N; ++i) {
        std::optional<shade::triangle_hit<T>> h;
        if (i < batch.size()) h = shade::intersect<shade::moller_trumbore>(r, tris[i], cull);
        ++count.lanes;
        REQUIRE(all.hit(i) == h.has_value());
        if (!h) {
            CHECK(all.t[i] == shade::infinity<T>);
            continue;
        }
        ++count.hits;
        CHECK(bits(all.t[i]) == bits(h->t));
        CHECK(bits(all.b0[i]) == bits(h->barycentric.x));
        CHECK(bits(all.b1[i]) == bits(h->barycentric.y));
        CHECK(bits(all.b2[i]) == bits(h->barycentric.z));
        CHECK(all.front_face(i) == h->front_face);
        if (!nearest || h->t < nearest_hit->t) {
            nearest = i;
            nearest_hit = h;
        }
    }
    const auto closest = shade::intersect_closest(r, batch, tris, cull);
    REQUIRE(closest.has_value() == nearest.has_value());
    CHECK(all.closest() == nearest);
    if (!closest) return;
    CHECK(closest->index == *nearest);
    CHECK(bits(closest->hit.t) == bits(nearest_hit->t));
    CHECK(same_bits(closest->hit.p, nearest_hit->p));
    CHECK(same_bits(closest->hit.n, nearest_hit->n));
    CHECK(same_bits(closest->hit.barycentric, nearest_hit->barycentric));
    CHECK(closest->hit.front_face == nearest_hit->front_face);
}

template <class T>
constexpr T inf = std::numeric_limits<T>::infinity();

} // namespace

TEST_CASE_TEMPLATE("triangle_batch: known hit in one lane, misses and empty lanes elsewhere", T,
                   float, double) {
    // Lane 1 is v0 = 0, v1 = (2,0,0), v2 = (0,2,0) (counter-clockwise seen from +z). The
    // ray from (0.5, 0.5, 3) along (0,0,-1) meets z = 0 at t = 3 in p = (0.5, 0.5, 0) =
    // v0 + u (v1 - v0) + v (v2 - v0) with u = v = 0.25, so (b0, b1, b2) = (0.5, 0.25,
    // 0.25); d·n = -1 < 0: front face. With these inputs every operation is exact
    // (n = (0,0,4), det = -d·n = 4, c = d × (o - v0) = (0.5,-0.5,0),
    // U = -e2·c = 1, V = e1·c = 1, W = det - U - V = 2, s·n = 12), so the values compare exactly. Lane 0 is the same
    // triangle moved to x = 10 (missed); lanes 2..7 are empty.
    const std::array<shade::triangle<T>, 2> tris{
        shade::triangle<T>{{10, 0, 0}, {12, 0, 0}, {10, 2, 0}},
        shade::triangle<T>{{0, 0, 0}, {2, 0, 0}, {0, 2, 0}}};
    const shade::triangle_batch<T, 8> batch(tris);
    CHECK(batch.size() == 2);
    const shade::ray<T> r{{T(0.5), T(0.5), 3}, {0, 0, -1}};
    const auto all = shade::intersect(r, batch);
    CHECK(all.count() == 1);
    CHECK_FALSE(all.hit(0));
    REQUIRE(all.hit(1));
    CHECK(all.t[1] == T(3));
    CHECK(all.b0[1] == T(0.5));
    CHECK(all.b1[1] == T(0.25));
    CHECK(all.b2[1] == T(0.25));
    CHECK(all.front_face(1));
    for (std::size_t i = 2; i < 8; ++i) CHECK_FALSE(all.hit(i));
    const auto c = shade::intersect_closest(r, batch, std::span<const shade::triangle<T>>(tris));
    REQUIRE(c.has_value());
    CHECK(c->index == 1);
    CHECK(c->hit.p == v3<T>(T(0.5), T(0.5), 0));
    CHECK(c->hit.n == v3<T>(0, 0, 1));
    // The same ray from below hits the back face: det = -4, culled on request.
    const shade::ray<T> below{{T(0.5), T(0.5), -3}, {0, 0, 1}};
    const auto back = shade::intersect(below, batch);
    REQUIRE(back.hit(1));
    CHECK_FALSE(back.front_face(1));
    CHECK(shade::intersect(below, batch, shade::culling::back_faces).count() == 0);
    // An empty batch never hits.
    CHECK(shade::intersect(r, shade::triangle_batch<T, 8>{}).count() == 0);
}

TEST_CASE_TEMPLATE("triangle_batch: packing validates the count and keeps the triangles", T, float,
                   double) {
    std::vector<shade::triangle<T>> tris(9, shade::triangle<T>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    tris[3] = shade::triangle<T>{{1, 2, 3}, {T(-4.5), 5, 6}, {7, 8, T(0.125)}};
    try {
        (void)shade::triangle_batch<T, 8>(std::span<const shade::triangle<T>>(tris));
        FAIL("nine triangles in an 8-wide batch were accepted");
    } catch (const shade::invalid_parameter& e) {
        CHECK(e.parameter() == "triangles");
    }
    const shade::triangle_batch<T, 16> wide{std::span<const shade::triangle<T>>(tris)};
    CHECK(wide.size() == 9);
    // intersect_closest needs the packed triangles themselves, all of them.
    const shade::ray<T> r{{0.25, 0.25, 1}, {0, 0, -1}};
    const std::span<const shade::triangle<T>> packed(tris.data(), 9);
    CHECK(shade::intersect_closest(r, wide, packed).has_value());
    CHECK_THROWS_AS((void)shade::intersect_closest(r, wide, packed.first(8)), shade::invalid_parameter);
}

// Random triangles and rays, about half of them aimed inside a triangle of the batch, so
// both outcomes and the early-out (rays that miss every lane) all occur. Each ray is
// tested double-sided and with back-face culling, with the default [0, inf) interval and
// with a finite t_max.
template <class T, std::size_t N>
void random_batches(std::uint64_t seed, int rays_per_batch, int batches, tally& count) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<T> unit(T(-1), T(1));
    std::uniform_real_distribution<T> unit01(T(0), T(1));
    auto random_point = [&](T scale) { return v3<T>(unit(rng), unit(rng), unit(rng)) * scale; };
    for (int b = 0; b < batches; ++b) {
        std::array<shade::triangle<T>, N> tris;
        for (auto& tri : tris) {
            const v3<T> centre = random_point(2);
            tri = shade::triangle<T>{centre + random_point(1), centre + random_point(1),
                                     centre + random_point(1)};
        }
        const shade::triangle_batch<T, N> batch(tris);
        for (int k = 0; k < rays_per_batch; ++k) {
            const v3<T> origin = random_point(6);
            v3<T> direction = random_point(1);
            if (k % 2 == 0) {
                // Aim at a random point of a random lane's plane, barycentrics in
                // [-0.25, 1.25] so points fall inside and just outside.
                const auto& tri = tris[static_cast<std::size_t>(rng() % N)];
                const T b1 = T(-0.25) + T(1.5) * unit01(rng);
                const T b2 = T(-0.25) + T(1.5) * unit01(rng);
                const v3<T> target = tri.v0 + b1 * (tri.v1 - tri.v0) + b2 * (tri.v2 - tri.v0);
                direction = target - origin;
            }
            if (direction == v3<T>(0, 0, 0)) continue;
            for (const shade::culling cull : {shade::culling::none, shade::culling::back_faces}) {
                check_against_scalar(shade::ray<T>{origin, direction}, batch, tris, cull, count);
                check_against_scalar(shade::ray<T>{origin, direction, T(0), T(1)}, batch, tris, cull, count);
            }
        }
    }
}

TEST_CASE_TEMPLATE("triangle_batch: bitwise equal to scalar Möller-Trumbore on random rays", T, float,
                   double) {
    tally count;
    random_batches<T, 8>(20240611, 64, 400, count);   // 400 batches x 64 rays x 4 variants
    random_batches<T, 16>(987654321, 32, 200, count); // the 16-wide batch too
    MESSAGE("lanes compared: " << count.lanes << ", hits: " << count.hits);
    // Both outcomes must have occurred in quantity, or the comparison proves little.
    // (About 1% of lanes are hit: half the rays are aimed at one of 8 or 16 lanes.)
    CHECK(count.hits > 10000);
    CHECK(count.hits < count.lanes / 2);
}

// Rays through vertices, edge points and barycentric points just inside and outside the
// edges (one or two ulps, via nextafter), where rounding decides the outcome: the batch
// must decide exactly like the scalar code, including the conservative early-out.
TEST_CASE_TEMPLATE("triangle_batch: bitwise equal to scalar on edges, vertices and near misses", T,
                   float, double) {
    std::mt19937_64 rng(77);
    std::uniform_real_distribution<T> unit(T(-1), T(1));
    auto random_point = [&](T scale) { return v3<T>(unit(rng), unit(rng), unit(rng)) * scale; };
    tally count;
    for (int b = 0; b < 300; ++b) {
        std::array<shade::triangle<T>, 8> tris;
        for (auto& tri : tris) tri = {random_point(1), random_point(1), random_point(1)};
        const shade::triangle_batch<T, 8> batch(tris);
        const auto& tri = tris[static_cast<std::size_t>(b % 8)];
        // Targets: the three vertices, edge midpoints and points along edges, each nudged
        // by 0, +-1 and +-2 ulps in every coordinate direction.
        std::vector<v3<T>> targets{tri.v0, tri.v1, tri.v2, (tri.v0 + tri.v1) * T(0.5),
                                   (tri.v1 + tri.v2) * T(0.5), (tri.v2 + tri.v0) * T(0.5),
                                   tri.v0 + T(0.3) * (tri.v1 - tri.v0),
                                   tri.v1 + T(0.7) * (tri.v2 - tri.v1)};
        const v3<T> origin = random_point(5);
        for (const v3<T>& target : targets) {
            for (int axis = 0; axis < 3; ++axis) {
                for (int step = -2; step <= 2; ++step) {
                    v3<T> p = target;
                    for (int s = 0; s < std::abs(step); ++s)
                        p[axis] = std::nextafter(p[axis], step > 0 ? inf<T> : -inf<T>);
                    const v3<T> direction = p - origin;
                    if (direction == v3<T>(0, 0, 0)) continue;
                    check_against_scalar(shade::ray<T>{origin, direction}, batch, tris,
                                         shade::culling::none, count);
                }
            }
        }
        // Rays starting exactly on a vertex and on an edge midpoint (t = 0 hits).
        check_against_scalar(shade::ray<T>{tri.v1, random_point(1)}, batch, tris, shade::culling::none,
                             count);
        check_against_scalar(shade::ray<T>{(tri.v0 + tri.v2) * T(0.5), random_point(1)}, batch, tris,
                             shade::culling::none, count);
    }
    MESSAGE("lanes compared: " << count.lanes << ", hits: " << count.hits);
    CHECK(count.hits > 1000);
}

TEST_CASE_TEMPLATE("triangle_batch: t_min and t_max bounds at the exact hit t", T, float, double) {
    // A hit at t = t_h is inside [t_h, t_h] and outside [next(t_h), inf) and
    // [0, prev(t_h)]. The scalar t is computed first; the batch must agree on each bound.
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<T> unit(T(-1), T(1));
    auto random_point = [&](T scale) { return v3<T>(unit(rng), unit(rng), unit(rng)) * scale; };
    tally count;
    int bounded = 0;
    for (int k = 0; k < 2000; ++k) {
        std::array<shade::triangle<T>, 8> tris;
        for (auto& tri : tris) tri = {random_point(1), random_point(1), random_point(1)};
        const shade::triangle_batch<T, 8> batch(tris);
        const auto& tri = tris[0];
        const v3<T> origin = random_point(4);
        const v3<T> direction = (tri.v0 + tri.v1 + tri.v2) * T(1.0 / 3.0) - origin;
        if (direction == v3<T>(0, 0, 0)) continue;
        const auto h = shade::intersect(shade::ray<T>{origin, direction}, tri);
        if (!h) continue;
        const T t = h->t;
        ++bounded;
        check_against_scalar(shade::ray<T>{origin, direction, t, t}, batch, tris, shade::culling::none, count);
        check_against_scalar(shade::ray<T>{origin, direction, std::nextafter(t, inf<T>), inf<T>}, batch, tris,
                             shade::culling::none, count);
        check_against_scalar(shade::ray<T>{origin, direction, T(0), std::nextafter(t, T(0))}, batch, tris,
                             shade::culling::none, count);
        // Lane 0 itself: hit on the exact interval, missed just beyond either bound.
        CHECK(shade::intersect(shade::ray<T>{origin, direction, t, t}, batch).hit(0));
        CHECK_FALSE(shade::intersect(shade::ray<T>{origin, direction, std::nextafter(t, inf<T>), inf<T>}, batch).hit(0));
        CHECK_FALSE(shade::intersect(shade::ray<T>{origin, direction, T(0), std::nextafter(t, T(0))}, batch).hit(0));
    }
    CHECK(bounded > 1000);
}

TEST_CASE_TEMPLATE("triangle_batch: degenerate, non-finite, tiny and huge triangles; bad rays", T,
                   float, double) {
    const T nan = std::numeric_limits<T>::quiet_NaN();
    const T max = std::numeric_limits<T>::max();
    const T big = max / T(2);
    // 2^-50 (float) or 2^-400 (double): the edge cross product tiny^2 is still a normal
    // number, so the triangle is not degenerate, and every product below is exact.
    const T tiny = std::is_same_v<T, float> ? T(0x1p-50) : T(0x1p-400);
    const std::array<shade::triangle<T>, 8> tris{
        shade::triangle<T>{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}},              // collinear
        shade::triangle<T>{{1, 1, 1}, {1, 1, 1}, {1, 1, 1}},              // a point
        shade::triangle<T>{{nan, 0, 0}, {1, 0, 0}, {0, 1, 0}},            // NaN vertex
        shade::triangle<T>{{0, 0, 0}, {inf<T>, 0, 0}, {0, 1, 0}},         // infinite vertex
        shade::triangle<T>{{0, 0, 0}, {tiny, 0, 0}, {0, tiny, 0}},        // tiny, at origin
        shade::triangle<T>{{max, 0, 0}, {max, 1, 0}, {max, 0, 1}},        // in the plane x = max
        shade::triangle<T>{{-big, -big, 5}, {big, -big, 5}, {0, big, 5}}, // edges overflow
        shade::triangle<T>{{-1, -1, 3}, {1, -1, 3}, {0, 1, 3}}};          // ordinary, z = 3
    const shade::triangle_batch<T, 8> batch(tris);
    tally count;
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<T> unit(T(-1), T(1));
    std::vector<shade::ray<T>> rays{
        {{0, 0, -1}, {0, 0, 1}},                   // through the tiny triangle's v0
        {{tiny / 4, tiny / 4, -1}, {0, 0, 1}},     // inside the tiny triangle
        {{0, 0, 10}, {0, 0, -1}},                  // down through everything
        {{0, 0, 3}, {1, 0, 0}},                    // in the plane z = 3: det = 0
        {{0, 0, 10}, {1, 0, 0}},                   // parallel to every z = const triangle
        {{0, 0, 10}, {0, 0, 1}},                   // pointing away
        {{nan, 0, 10}, {0, 0, -1}},                // invalid: NaN origin
        {{0, 0, 10}, {0, 0, 0}},                   // invalid: zero direction
        {{0, 0, 10}, {0, 0, -1}, T(2), T(1)},      // invalid: t_min > t_max
        {{big, big, 10}, {-1, -1, -1}},            // huge origin
        {{0, 0, 4}, {0, 0, -1}, T(0), T(1)},       // stops exactly at z = 3
    };
    for (int k = 0; k < 500; ++k)
        rays.push_back({{unit(rng), unit(rng), T(10) * unit(rng)}, {unit(rng), unit(rng), unit(rng)}});
    for (const auto& r : rays)
        for (const shade::culling cull : {shade::culling::none, shade::culling::back_faces})
            check_against_scalar(r, batch, tris, cull, count);
    CHECK(count.hits > 10);

    // Rays from (max/2, y, z), |y|, |z| <= 1/2, to random points of the triangle in the
    // plane x = max (t = 1): its hit point b0 v0 + b1 v1 + b2 v2 has x = (b0 + b1 + b2) max, which
    // overflows to infinity whenever the rounded barycentrics sum to a little more than
    // 1. make_hit then clamps p into the triangle's bounding box (x = max), so
    // these hits are kept, in the batch as in the scalar code, and p stays finite.
    // (Starting at x = max/2 keeps every product in c = d × (o - v0) below max/2, and
    // det = -max/2: nothing in the test itself overflows.)
    std::uniform_real_distribution<T> unit01(T(0), T(1));
    std::size_t clamped = 0;
    for (int k = 0; k < 2000; ++k) {
        const T b1 = T(0.5) * unit01(rng), b2 = T(0.5) * unit01(rng);
        const v3<T> origin(max / 2, unit(rng) / 2, unit(rng) / 2);
        const shade::ray<T> r{origin, v3<T>(max, b1, b2) - origin};
        check_against_scalar(r, batch, tris, shade::culling::none, count);
        REQUIRE(shade::intersect(r, batch).hit(5));
        const auto h = shade::intersect(r, tris[5]);
        REQUIRE(h.has_value());
        CHECK(shade::is_finite(h->p));
        // b0 + b1 + b2 = 1 up to a few roundings, so p.x is max within a few ulps, and
        // never above it.
        CHECK(h->p.x <= max);
        CHECK(h->p.x >= max - T(8) * std::numeric_limits<T>::epsilon() * max);
        const auto& b = h->barycentric;
        if (!std::isfinite(b.x * max + b.y * max + b.z * max)) ++clamped;
    }
    MESSAGE("near-max triangle: " << clamped << " of 2000 hit points clamped to the bounding box");
    CHECK(clamped > 0);

    // det overflowing while U, V and T stay finite (derived in test_triangle.cpp's "an
    // overflowing det" case): no hit in any form, front or back.
    {
        const T L = std::is_same_v<T, float> ? T(1e15) : T(1e150);
        const std::array<shade::triangle<T>, 1> huge{
            shade::triangle<T>{{0, 0, 0}, {2 * L, 0, 0}, {L, 2 * L, 0}}};
        const shade::triangle_batch<T, 8> one(huge);
        for (const T z0 : {T(1), T(-1)}) {
            const shade::ray<T> r{{1, 1, z0}, {0, 0, -z0 * T(1e10)}};
            check_against_scalar(r, one, huge, shade::culling::none, count);
            CHECK_FALSE(shade::intersect(r, one).hit(0));
        }
    }

    // Hand-checked outcomes: the ray down the z axis from z = 10 hits the ordinary
    // triangle at t = 7 (z = 3) and the tiny one at t = 10 (in its vertex v0 = 0, which
    // counts as inside; all products are exact powers of two); the degenerate, non-finite
    // and overflowing ones never, and lane 5 (plane x = max) is parallel to it.
    const auto down = shade::intersect(shade::ray<T>{{0, 0, 10}, {0, 0, -1}}, batch);
    for (const std::size_t i : {0u, 1u, 2u, 3u, 5u, 6u}) CHECK_FALSE(down.hit(i));
    CHECK(down.hit(4));
    CHECK(down.t[4] == T(10));
    CHECK(down.hit(7));
    CHECK(down.t[7] == T(7));
    CHECK(down.closest() == std::optional<std::size_t>(7));
}

TEST_CASE("triangle_batch: the kernel name says which form intersect runs") {
    const std::string name = shade::triangle_batch_kernel();
#if defined(__GNUC__) && defined(__x86_64__) && !defined(__AVX__) && \
    !defined(SHADE_NO_RUNTIME_DISPATCH)
    // A build without -mavx on x86-64: AVX-512F (64-byte batches) and AVX when the CPU
    // has them, AVX alone, or else the SSE2 baseline.
    static_assert(shade::detail::batch_dispatch_at_run_time);
    const std::string expected =
        shade::detail::cpu_has_avx512f()
            ? "avx512f for batches of 64 bytes (16 floats, 8 or 16 doubles), avx for the others "
              "(selected at run time)"
            : shade::detail::cpu_has_avx() ? "avx (selected at run time)" : "vector 16 bytes";
    CHECK(name == expected);
#elif defined(__AVX__)
    static_assert(!shade::detail::batch_dispatch_at_run_time);
    CHECK(name == "vector 32 bytes");
#elif defined(__GNUC__)
    CHECK(name == "vector 16 bytes");
#else
    CHECK(name == "scalar");
#endif
}

// The arrays are aligned to the largest power of two up to 64 dividing their size in
// bytes (N * sizeof(T)), worked out by hand here: 8 floats = 32 bytes -> 32; 8 doubles =
// 64 -> 64; 16 floats = 64 -> 64; 4 floats = 16 -> 16; 3 floats = 12 -> 4; 3 doubles =
// 24 -> 8; 24 floats = 96 -> 32.
static_assert(shade::detail::batch_array_alignment<float, 8>() == 32);
static_assert(shade::detail::batch_array_alignment<double, 8>() == 64);
static_assert(shade::detail::batch_array_alignment<float, 16>() == 64);
static_assert(shade::detail::batch_array_alignment<float, 4>() == 16);
static_assert(shade::detail::batch_array_alignment<float, 3>() == 4);
static_assert(shade::detail::batch_array_alignment<double, 3>() == 8);
static_assert(shade::detail::batch_array_alignment<float, 24>() == 32);
static_assert(alignof(shade::triangle_batch<float, 8>) == 32);
static_assert(alignof(shade::triangle_batch_hits<double, 8>) == 64);

TEST_CASE_TEMPLATE("triangle_batch: the lane arrays of batches and results are aligned", T, float, double) {
    constexpr std::size_t align = shade::detail::batch_array_alignment<T, 8>();
    const auto aligned = [](const void* p) { return reinterpret_cast<std::uintptr_t>(p) % align == 0; };
    // In a std::vector (over-aligned new) and on the stack.
    const std::vector<shade::triangle_batch<T, 8>> batches(3);
    for (const auto& b : batches) CHECK(aligned(&b));
    const shade::ray<T> r{{0, 0, 1}, {0, 0, -1}};
    const auto hits = shade::intersect(r, batches[1]);
    CHECK(aligned(hits.t.data()));
    CHECK(aligned(hits.b0.data()));
    CHECK(aligned(hits.b1.data()));
    CHECK(aligned(hits.b2.data()));
    CHECK(hits.count() == 0u);
}
