// Bounding-volume hierarchies (bvh, primitive_bvh, triangle_bvh), with nodes of four and
// of eight children: closest, triangle_bvh's find_closest (with make_hit, closest's record)
// and any agree with a brute-force loop over every primitive on
// random rays over random meshes; a closed mesh behind the watertight test lets no ray
// through shared edges or vertices escape; degenerate inputs (empty, one triangle, all
// coplanar, NaN vertices). The tests of hits run under each eight-wide walk the CPU can
// take (for_each_walk: with AVX-512, its walk and the AVX one).

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <optional>
#include <span>
#include <type_traits>
#include <vector>

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/core/error.hpp>
#include <shade/core/random.hpp>
#include <shade/geometry/bvh.hpp>
#include <shade/geometry/triangle_bvh.hpp>

#include "support/thread_executor.hpp"

namespace {

template <class T>
using v3 = shade::vec3<T>;

// Both node widths (eight is four where this build or CPU lacks AVX; the test of
// shade::bvh_width below checks which).
constexpr shade::bvh_width widths[] = {shade::bvh_width::four, shade::bvh_width::eight};

// Runs body under each eight-wide walk traversal can take here: where the build has the
// walk compiled for AVX-512 and the CPU runs it (g++ builds without -mavx512f on such
// CPUs), once with it (the default) and once with the walk compiled for AVX that other
// CPUs take; elsewhere once.
template <class F>
void for_each_walk(const F& body) {
    struct restore {
        ~restore() { shade::detail::bvh_avx512_walk = true; }
    } guard;
    for (const bool avx512 : {true, false}) {
        if (avx512 && !shade::detail::bvh_avx512_walk_available()) continue;
        CAPTURE(avx512);
        shade::detail::bvh_avx512_walk = avx512;
        body();
    }
}

template <class T>
v3<T> in_cube(shade::rng& g, T half) {
    return half * v3<T>(2 * g.uniform<T>() - 1, 2 * g.uniform<T>() - 1, 2 * g.uniform<T>() - 1);
}

// n random triangles of size ~size with centres in [-4, 4]^3.
template <class T>
std::vector<shade::triangle<T>> random_mesh(shade::rng& g, std::size_t n, T size) {
    std::vector<shade::triangle<T>> tris;
    for (std::size_t i = 0; i < n; ++i) {
        const v3<T> c = in_cube<T>(g, T(4));
        tris.push_back({c + in_cube<T>(g, size), c + in_cube<T>(g, size), c + in_cube<T>(g, size)});
    }
    return tris;
}

// The nearest hit of Algorithm over all triangles, as a loop would find it (t_max
// shrinking, so the first of equal-t triangles is kept), with its index.
template <class Algorithm, class T>
std::optional<std::pair<std::uint32_t, shade::triangle_intersection<T>>>
brute_force(shade::ray<T> r, std::span<const shade::triangle<T>> tris) {
    std::optional<std::pair<std::uint32_t, shade::triangle_intersection<T>>> best;
    for (std::uint32_t i = 0; i < tris.size(); ++i)
        if (auto x = Algorithm::find(r, tris[i])) {
            if (!best || x->t < best->second.t) best = {i, *x};
            r.t_max = x->t;
        }
    return best;
}

struct tally {
    std::size_t rays = 0, hits = 0;
};

// Every member of two hit records equal, bit for bit.
template <class T>
void check_same_record(const shade::triangle_hit<T>& a, const shade::triangle_hit<T>& b) {
    CHECK(a.t == b.t);
    CHECK(a.p == b.p);
    CHECK(a.n == b.n);
    CHECK(a.front_face == b.front_face);
    CHECK(a.uv == b.uv);
    CHECK(a.dpdu == b.dpdu);
    CHECK(a.p_error == b.p_error);
    CHECK(a.barycentric == b.barycentric);
}

// find_closest against closest on r: the same hit or miss, the same triangle, t,
// barycentrics and front_face, all finite, and make_hit of it closest's record.
template <class Algorithm, class T>
void check_lean_query(const shade::triangle_bvh<T, Algorithm>& accel, const shade::ray<T>& r,
                      shade::culling cull = shade::culling::none) {
    const auto full = accel.closest(r, cull);
    const auto lean = accel.find_closest(r, cull);
    REQUIRE(lean.has_value() == full.has_value());
    if (!lean) return;
    CHECK(lean->primitive == full->primitive);
    CHECK(lean->hit.t == full->hit.t);
    CHECK(lean->hit.barycentric == full->hit.barycentric);
    CHECK(lean->hit.front_face == full->hit.front_face);
    CHECK(std::isfinite(lean->hit.t));
    CHECK(shade::is_finite(lean->hit.barycentric));
    const auto record = accel.make_hit(*lean);
    CHECK(record.primitive == full->primitive);
    check_same_record(record.hit, full->hit);
    CHECK(shade::is_finite(record.hit.p));
    CHECK(shade::is_finite(record.hit.n));
    CHECK(shade::is_finite(record.hit.p_error));
}

// closest, find_closest and any against brute force on rays; t, the record and the
// triangle must match exactly (the triangle may differ only when another one is hit at
// the same t).
template <class Algorithm, class T>
void check_against_brute_force(const shade::triangle_bvh<T, Algorithm>& accel,
                               std::span<const shade::triangle<T>> tris, const std::vector<shade::ray<T>>& rays,
                               tally& count) {
    for (const auto& r : rays) {
        const auto expected = brute_force<Algorithm>(r, tris);
        const auto got = accel.closest(r);
        ++count.rays;
        REQUIRE(got.has_value() == expected.has_value());
        CHECK(accel.any(r) == expected.has_value());
        check_lean_query(accel, r);
        if (!expected) continue;
        ++count.hits;
        CHECK(got->hit.t == expected->second.t);
        if (got->primitive != expected->first) {
            // Only a tie at the same t may pick another triangle.
            const auto other = Algorithm::find(r, tris[got->primitive]);
            REQUIRE(other);
            CHECK(other->t == expected->second.t);
            continue;
        }
        const auto h = shade::make_hit(tris[expected->first], expected->second);
        CHECK(got->hit.barycentric == h.barycentric);
        CHECK(got->hit.p == h.p);
        CHECK(got->hit.n == h.n);
        CHECK(got->hit.front_face == h.front_face);
    }
}

template <class T>
std::vector<shade::ray<T>> random_rays(shade::rng& g, std::size_t n) {
    std::vector<shade::ray<T>> rays;
    for (std::size_t i = 0; i < n; ++i) {
        shade::ray<T> r{in_cube<T>(g, T(6)), in_cube<T>(g, T(1))};
        if (i % 4 == 1) r.t_max = T(3) * g.uniform<T>(); // a bounded interval
        if (i % 4 == 2) r.t_min = g.uniform<T>();
        rays.push_back(r);
    }
    return rays;
}

// An icosahedron subdivided `levels` times, vertices projected on the unit sphere and
// shared exactly between neighbouring triangles (a closed, watertight mesh).
template <class T>
std::vector<shade::triangle<T>> closed_sphere(int levels) {
    const T g = (1 + std::sqrt(T(5))) / 2;
    std::vector<v3<T>> p = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                            {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
    for (auto& v : p) v = glm::normalize(v);
    std::vector<std::uint32_t> idx = {0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4,
                                      11, 10, 2, 10, 7, 6, 7, 1, 8, 3, 9, 4, 3, 4, 2, 3, 2, 6, 3, 6, 8,
                                      3, 8, 9, 4, 9, 5, 2, 4, 11, 6, 2, 10, 8, 6, 7, 9, 8, 1};
    for (int level = 0; level < levels; ++level) {
        std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> mids;
        const auto mid = [&](std::uint32_t a, std::uint32_t b) {
            const auto key = std::make_pair(std::min(a, b), std::max(a, b));
            if (auto f = mids.find(key); f != mids.end()) return f->second;
            p.push_back(glm::normalize(p[a] + p[b]));
            return mids[key] = static_cast<std::uint32_t>(p.size() - 1);
        };
        std::vector<std::uint32_t> next;
        for (std::size_t t = 0; t < idx.size(); t += 3) {
            const std::uint32_t a = idx[t], b = idx[t + 1], c = idx[t + 2];
            const std::uint32_t ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
            next.insert(next.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
        }
        idx = std::move(next);
    }
    std::vector<shade::triangle<T>> tris;
    for (std::size_t t = 0; t < idx.size(); t += 3) tris.push_back({p[idx[t]], p[idx[t + 1]], p[idx[t + 2]]});
    return tris;
}

} // namespace

TEST_CASE_TEMPLATE("triangle_bvh: closest and any agree with brute force on random meshes", T, float, double) {
    for_each_walk([&] {
        shade::rng g(42);
        tally count;
        // Sizes around the leaf and node widths, and larger meshes of small and large triangles.
        for (const std::size_t n : {std::size_t(2), std::size_t(5), std::size_t(17), std::size_t(300), std::size_t(3000)}) {
            const auto tris = random_mesh<T>(g, n, n > 1000 ? T(0.2) : T(1));
            const auto rays = random_rays<T>(g, 400);
            for (const shade::bvh_width width : widths) {
                CAPTURE(width);
                check_against_brute_force(shade::triangle_bvh<T>(tris, width), std::span<const shade::triangle<T>>(tris),
                                          rays, count);
                check_against_brute_force(shade::triangle_bvh<T, shade::watertight>(tris, width),
                                          std::span<const shade::triangle<T>>(tris), rays, count);
            }
        }
        CHECK(count.hits > 200); // both outcomes exercised
        CHECK(count.hits < count.rays);
        // Back-face culling reaches the leaves: a closed sphere seen from inside has only
        // back faces toward the origin.
        const auto sphere = closed_sphere<T>(2);
        const shade::triangle_bvh<T> accel(sphere);
        const shade::ray<T> inside{{0, 0, 0}, {0.3, 0.2, 1}};
        CHECK(accel.closest(inside));
        CHECK_FALSE(accel.closest(inside, shade::culling::back_faces));
        CHECK(accel.find_closest(inside));
        CHECK_FALSE(accel.find_closest(inside, shade::culling::back_faces));
        // From outside only front faces face the ray: the same hit with culling as without.
        const shade::ray<T> outside{{0.1, 0.2, -3}, {0, 0, 1}};
        check_lean_query(accel, outside, shade::culling::back_faces);
        REQUIRE(accel.find_closest(outside, shade::culling::back_faces));
        CHECK(accel.find_closest(outside, shade::culling::back_faces)->hit.front_face);
        CHECK_FALSE(accel.any(inside, shade::culling::back_faces));
    });
}

// Rays from inside a closed sphere mesh toward its vertices and points on its edges (the
// places where a non-watertight test can let a ray through) must all hit with the
// watertight test behind the hierarchy, as they do without it.
TEST_CASE_TEMPLATE("triangle_bvh<watertight>: no ray escapes a closed mesh through shared edges or vertices", T,
                   float, double) {
    for_each_walk([&] {
        const auto tris = closed_sphere<T>(3); // 1280 triangles
        const shade::triangle_bvh<T, shade::watertight> accel(tris, shade::bvh_width::four);
        const shade::triangle_bvh<T, shade::watertight> wide(tris, shade::bvh_width::eight);
        shade::rng g(3);
        std::size_t rays = 0, escaped = 0, escaped_wide = 0, escaped_brute = 0;
        for (const auto& tri : tris) {
            const v3<T> origin = in_cube<T>(g, T(0.3)); // inside the sphere, off-centre
            const v3<T> targets[] = {tri.v0, tri.v1, (tri.v0 + tri.v1) * T(0.5), tri.v0 + (tri.v2 - tri.v0) * T(0.25)};
            for (const v3<T>& target : targets) {
                const shade::ray<T> r{origin, target - origin};
                ++rays;
                escaped += !accel.closest(r).has_value();
                escaped += !accel.any(r);
                escaped_wide += !wide.closest(r).has_value();
                escaped_wide += !wide.any(r);
                escaped_brute += !brute_force<shade::watertight>(r, std::span<const shade::triangle<T>>(tris));
            }
        }
        CHECK(rays == 4 * tris.size());
        CHECK(escaped_brute == 0);
        CHECK(escaped == 0);
        CHECK(escaped_wide == 0);
    });
}

TEST_CASE_TEMPLATE("triangle_bvh: degenerate inputs", T, float, double) {
    const shade::ray<T> down{{0.25, 0.25, 1}, {0, 0, -1}};
    SUBCASE("an empty mesh hits nothing") {
        const shade::triangle_bvh<T> empty(std::span<const shade::triangle<T>>{});
        CHECK(empty.size() == 0);
        CHECK_FALSE(empty.closest(down));
        CHECK_FALSE(empty.find_closest(down));
        CHECK_FALSE(empty.any(down));
        const shade::triangle_bvh<T> defaulted;
        CHECK_FALSE(defaulted.closest(down));
        CHECK_FALSE(defaulted.find_closest(down));
    }
    SUBCASE("one triangle") {
        const std::vector<shade::triangle<T>> one{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}};
        for (const shade::bvh_width width : widths) {
            CAPTURE(width);
            const shade::triangle_bvh<T> accel(one, width);
            const auto h = accel.closest(down);
            REQUIRE(h);
            CHECK(h->primitive == 0);
            CHECK(h->hit.t == T(1));
            // b1 = b2 = 1/4, b0 = 1/2 at (1/4, 1/4, 0).
            CHECK(h->hit.barycentric == v3<T>(0.5, 0.25, 0.25));
            CHECK(h->hit.p == v3<T>(0.25, 0.25, 0));
            const auto lean = accel.find_closest(down);
            REQUIRE(lean);
            CHECK(lean->primitive == 0);
            CHECK(lean->hit.t == T(1));
            CHECK(lean->hit.barycentric == v3<T>(0.5, 0.25, 0.25));
            CHECK(lean->hit.front_face);
            CHECK(accel.make_hit(*lean).hit.p == v3<T>(0.25, 0.25, 0));
            // The interval decides: t = 1 lies outside [0, 0.5] and inside [1, 1].
            CHECK_FALSE(accel.find_closest(shade::ray<T>{down.origin, down.direction, T(0), T(0.5)}));
            CHECK(accel.find_closest(shade::ray<T>{down.origin, down.direction, T(1), T(1)}));
            CHECK_FALSE(accel.find_closest(shade::ray<T>{down.origin, down.direction, T(1.5), T(3)}));
            CHECK_FALSE(accel.closest(shade::ray<T>{{0.75, 0.75, 1}, {0, 0, -1}}));
            CHECK_FALSE(accel.find_closest(shade::ray<T>{{0.75, 0.75, 1}, {0, 0, -1}}));
            CHECK_FALSE(accel.closest(down, shade::culling::back_faces) == std::nullopt); // front face
            CHECK(accel.any(down));
        }
    }
    SUBCASE("all triangles coplanar: a flat boxes' hierarchy still finds every hit") {
        // A 40 x 40 grid of unit squares in z = 0 (3200 triangles): every box is flat.
        std::vector<shade::triangle<T>> grid;
        for (int i = 0; i < 40; ++i)
            for (int j = 0; j < 40; ++j) {
                const v3<T> a(T(i), T(j), 0), b(T(i + 1), T(j), 0), c(T(i + 1), T(j + 1), 0), d(T(i), T(j + 1), 0);
                grid.push_back({a, b, c});
                grid.push_back({a, c, d});
            }
        const shade::triangle_bvh<T> accel(grid, shade::bvh_width::four);
        const shade::triangle_bvh<T, shade::watertight> tight(grid, shade::bvh_width::four);
        const shade::triangle_bvh<T> accel_wide(grid, shade::bvh_width::eight);
        const shade::triangle_bvh<T, shade::watertight> tight_wide(grid, shade::bvh_width::eight);
        shade::rng g(9);
        tally count;
        std::vector<shade::ray<T>> rays;
        for (int k = 0; k < 300; ++k) {
            const v3<T> target(T(40) * g.uniform<T>(), T(40) * g.uniform<T>(), 0);
            const v3<T> o = target + v3<T>(in_cube<T>(g, T(3)).x, in_cube<T>(g, T(3)).y, T(1) + g.uniform<T>());
            rays.push_back({o, target - o});
            // Rays inside the plane never hit (parallel to every triangle).
            rays.push_back({v3<T>(T(-1), target.y, 0), v3<T>(1, 0, 0)});
        }
        check_against_brute_force(accel, std::span<const shade::triangle<T>>(grid), rays, count);
        check_against_brute_force(tight, std::span<const shade::triangle<T>>(grid), rays, count);
        CHECK(count.hits == 600); // every ray from above hits, none in the plane
        tally wide;
        check_against_brute_force(accel_wide, std::span<const shade::triangle<T>>(grid), rays, wide);
        check_against_brute_force(tight_wide, std::span<const shade::triangle<T>>(grid), rays, wide);
        CHECK(wide.hits == 600);
    }
    SUBCASE("NaN or infinite vertices are rejected naming the triangle") {
        std::vector<shade::triangle<T>> bad{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}},
                                           {{0, 0, 0}, {1, std::numeric_limits<T>::quiet_NaN(), 0}, {0, 1, 0}}};
        try {
            const shade::triangle_bvh<T> accel(bad);
            FAIL("a NaN vertex was accepted");
        } catch (const shade::invalid_parameter& e) {
            CHECK(e.parameter() == "triangles");
            CHECK(std::string(e.what()).find("triangle 1") != std::string::npos);
        }
        bad[1].v1.y = std::numeric_limits<T>::infinity();
        using tight_bvh = shade::triangle_bvh<T, shade::watertight>;
        CHECK_THROWS_AS(tight_bvh{bad}, shade::invalid_parameter);
    }
}

// closest(), find_closest() and any() test a ray's validity in the walk, with the test
// for a direction that needs scaling: for a float ray in the eight-wide walk by
// detail::bvh_ray_plain8 (valid and needing no scaling, eight lanes at once), else by
// detail::bvh_ray_valid (a vector form of ray::valid() for float rays) and
// bvh_scale_needed. Each gives the scalar answer for every value in every one and every
// two of the ray's eight numbers (origin, direction, t_min, t_max), from a valid ray and
// from one with a zero direction; the invalid rays hit nothing and the valid ones (some
// scaled) hit as the triangle test does, at both widths.
TEST_CASE_TEMPLATE("triangle_bvh: a ray's validity as ray::valid() decides it", T, float, double) {
    for_each_walk([&] {
        using lim = std::numeric_limits<T>;
        const T values[] = {T(0), -T(0), T(1), T(-2.5), lim::denorm_min(), -lim::min(), lim::max(),
                            lim::lowest(), lim::infinity(), -lim::infinity(), lim::quiet_NaN(),
                            T(0x1p-125), T(-0x1p+125), T(0x1p+126)}; // the bounds of the unscaled range and beyond
        const auto slot = [](shade::ray<T>& r, int k) -> T& {
            return k < 3 ? r.origin[k] : k < 6 ? r.direction[k - 3] : k == 6 ? r.t_min : r.t_max;
        };
        // The one triangle of the plane z = 0 around the origin's column: hit by valid rays
        // pointing down from (0, 0, 1), whatever else changes.
        const std::vector<shade::triangle<T>> tris{{{-10, -10, 0}, {10, -10, 0}, {0, 10, 0}}};
        const shade::triangle_bvh<T> four(tris, shade::bvh_width::four);
        const shade::triangle_bvh<T> eight(tris, shade::bvh_width::eight);
        const shade::ray<T> bases[] = {{{0, 0, 1}, {0, 0, -1}, T(0), lim::infinity()},
                                       {{0, 0, 1}, {0, 0, 0}, T(0), T(2)}};
        // The walk alone (bvh_traverse validating), over one leaf of the triangle's box: an
        // invalid ray reaches no leaf.
        std::vector<shade::detail::bvh_prim_ref> refs{shade::detail::make_prim_ref(shade::bounds(tris[0]), 0)};
        auto refs8 = refs;
        const auto tree4 = shade::detail::bvh_builder(1, 1).build(refs, 4);
        const auto tree8 = shade::detail::bvh_builder(1, 1).build(refs8, shade::detail::bvh_node_width(8));
        std::size_t valid = 0, invalid = 0, scaled = 0, hits = 0;
        for (const shade::ray<T>& base : bases)
            for (int i = 0; i < 8; ++i)
                for (int j = i; j < 8; ++j)
                    for (const T a : values)
                        for (const T b : values) {
                            shade::ray<T> r = base;
                            slot(r, i) = a;
                            slot(r, j) = b; // i == j: one number changed
                            CAPTURE(i);
                            CAPTURE(j);
                            CAPTURE(a);
                            CAPTURE(b);
                            const bool expected = r.valid();
                            REQUIRE(shade::detail::bvh_ray_valid(r) == expected);
                            const bool needs_scaling = shade::detail::bvh_ray_scale<T>::needed(r.direction);
                            REQUIRE(shade::detail::bvh_scale_needed(r.direction) == needs_scaling);
    #if defined(__GNUC__) && defined(__x86_64__)
                            if constexpr (std::is_same_v<T, float>)
                                if (shade::detail::cpu_has_avx())
                                    REQUIRE(shade::detail::bvh_ray_plain8(r) == (expected && !needs_scaling));
    #endif
                            (expected ? valid : invalid) += 1;
                            scaled += expected && needs_scaling;
                            const auto loop = brute_force<shade::moller_trumbore>(r, std::span<const shade::triangle<T>>(tris));
                            hits += loop.has_value();
                            for (const auto* tree : {&tree4, &tree8}) {
                                std::size_t leaves = 0;
                                shade::detail::bvh_traverse<shade::detail::bvh_order::sorted, true>(
                                    *tree, r, r.t_max, [&](std::uint32_t, std::uint32_t, auto) { return ++leaves, false; });
                                if (!expected) CHECK(leaves == 0);
                                if (expected && loop) CHECK(leaves == 1); // a hit lies in the box
                            }
                            for (const auto* accel : {&four, &eight}) {
                                if (!expected) {
                                    CHECK_FALSE(accel->closest(r));
                                    CHECK_FALSE(accel->find_closest(r));
                                    CHECK_FALSE(accel->any(r));
                                    continue;
                                }
                                check_lean_query(*accel, r);
                                CHECK(accel->any(r) == loop.has_value());
                                const auto h = accel->closest(r);
                                REQUIRE(h.has_value() == loop.has_value());
                                if (h) CHECK(h->hit.t == loop->second.t);
                            }
                        }
        // Both answers occur many times (each base with one number changed to 1 alone gives
        // valid rays from the valid base and, through the direction, from the zero one), and
        // valid rays that need scaling, and hits, too.
        CHECK(valid > 1000);
        CHECK(invalid > 1000);
        CHECK(scaled > 100);
        CHECK(hits > 100);
    });
}

TEST_CASE_TEMPLATE("primitive_bvh and bvh: spheres against brute force", T, float, double) {
    for_each_walk([&] {
        shade::rng g(5);
        std::vector<shade::sphere<T>> spheres;
        for (int i = 0; i < 500; ++i) spheres.emplace_back(in_cube<T>(g, T(5)), T(0.05) + T(0.3) * g.uniform<T>());
        std::vector<shade::aabb<T>> boxes;
        for (const auto& s : spheres) boxes.push_back(shade::bounds(s));
        for (const shade::bvh_width width : widths) {
            CAPTURE(width);
            const shade::primitive_bvh<shade::sphere<T>> accel(spheres, width);
            const shade::bvh<T> tree(boxes, width);
            CHECK(tree.size() == spheres.size());
            std::size_t hits = 0;
            for (int k = 0; k < 2000; ++k) {
                const shade::ray<T> r{in_cube<T>(g, T(7)), in_cube<T>(g, T(1))};
                std::optional<std::pair<std::uint32_t, shade::hit<T>>> best;
                for (std::uint32_t i = 0; i < spheres.size(); ++i)
                    if (auto h = shade::intersect(r, spheres[i]); h && (!best || h->t < best->second.t)) best = {i, *h};
                const auto got = accel.closest(r);
                const auto via_tree = tree.closest(r, [&](std::uint32_t i, const shade::ray<T>& rr) {
                    return shade::intersect(rr, spheres[i]);
                });
                REQUIRE(got.has_value() == best.has_value());
                REQUIRE(via_tree.has_value() == best.has_value());
                CHECK(accel.any(r) == best.has_value());
                CHECK(tree.any(r, [&](std::uint32_t i, const shade::ray<T>& rr) { return shade::intersect(rr, spheres[i]).has_value(); }) ==
                      best.has_value());
                if (!best) continue;
                ++hits;
                CHECK(got->hit.t == best->second.t);
                CHECK(got->primitive == best->first);
                CHECK(via_tree->hit.t == best->second.t);
            }
            CHECK(hits > 100);
            CHECK(hits < 1900);
        }
        std::vector<shade::aabb<T>> bad_boxes{shade::aabb<T>{}};
        CHECK_THROWS_AS(shade::bvh<T>{std::span<const shade::aabb<T>>(bad_boxes)}, shade::invalid_parameter);
    });
}

// An unused child slot of a node has an empty box (+inf, -inf). A double ray whose
// direction components are so large that their reciprocals round to 0 in float gets the
// slab distance (inf - o) * 0 = NaN against that box, which the slab test ignores, so the
// slot is entered. It must then lead nowhere: it used to lead back to the root, and the
// walk ran past the end of its stack (found by a libFuzzer run: two spheres, the first
// with a radius beyond the float range; the ray below).
namespace {
/// A hit record of nothing but its ray parameter, for bvh::closest.
template <class T>
struct t_only {
    T t;
};
} // namespace

// The walk's box test (detail::bvh_test_boxes: far distances through the reciprocal
// pre-multiplied by 1 + 2 gamma(n)) on rays through a box corner, exactly, as in
// test_aabb.cpp's test of shade::intersect(ray, aabb): the corner is the only point of the
// box on the exact ray, so only a conservative test reports every one (without the
// enlargement the float walk misses about one ray in nine). A hierarchy over that box and
// seven others far away, at both widths: any() and closest() must reach it.
TEST_CASE_TEMPLATE("bvh: the walk's box test never misses a ray through a box corner", T, float, double) {
    for_each_walk([&] {
        shade::rng g(11);
        const int n = 20000;
        for (const shade::bvh_width width : widths) {
            CAPTURE(width);
            int missed = 0;
            for (int i = 0; i < n; ++i) {
                // Dyadic corner, direction and t with few bits (float sizes in both types: the
                // node's float planes then hold the box exactly), so o = corner - t d is exact.
                shade::vec3<T> corner, d;
                for (int k = 0; k < 3; ++k) {
                    corner[k] = T((std::floor(g.uniform<double>() * 512) - 256) / 64);
                    T dk = T((std::floor(g.uniform<double>() * 7) + 1) / 8);
                    if (g.uniform<double>() < 0.5) dk = -dk;
                    d[k] = dk;
                }
                const T t = T((std::floor(g.uniform<double>() * 64) + 1) / 256.0);
                const shade::vec3<T> o = corner - t * d;
                std::vector<shade::aabb<T>> boxes(8);
                for (int k = 0; k < 3; ++k) {
                    const bool enters = k == 0 || (k == 2 && g.uniform<double>() < 0.5);
                    const bool above = enters == (d[k] > 0);
                    boxes[0].lo[k] = above ? corner[k] : corner[k] - T(1);
                    boxes[0].hi[k] = above ? corner[k] + T(1) : corner[k];
                }
                for (std::size_t b = 1; b < boxes.size(); ++b) {
                    boxes[b].lo = shade::vec3<T>(T(100 + 10 * int(b)));
                    boxes[b].hi = boxes[b].lo + shade::vec3<T>(1);
                }
                const shade::bvh<T> accel(boxes, width);
                const shade::ray<T> r{o, d};
                const auto first = [](std::uint32_t p, const shade::ray<T>&) { return p == 0; };
                const auto h = accel.closest(r, [&](std::uint32_t p, const shade::ray<T>& s) {
                    return p == 0 && t >= s.t_min && t <= s.t_max ? std::optional<t_only<T>>(t_only<T>{t}) : std::nullopt;
                });
                if (!accel.any(r, first) || !h) ++missed;
            }
            CHECK(missed == 0);
        }
    });
}

TEST_CASE("bvh: a ray entering an unused child slot visits nothing") {
    for_each_walk([&] {
        const std::vector<shade::sphere<double>> spheres{
            shade::sphere<double>({0.0, 0.0, -0x1p-8}, 0x1.1004001004003p+977),
            shade::sphere<double>({0x1p-7, 0x1p-8, -0.0}, 0x1.8p-6)};
        shade::ray<double> r{{0, 0, 0}, {-0x1.014107194c1d2p+977, 0x1.57015ecc657c2p+975, 0x1.57015ecc657c2p+973}};
        r.t_max = 0x1.001004003ffffp-1019;
        std::optional<std::pair<std::uint32_t, double>> nearest;
        for (std::uint32_t i = 0; i < spheres.size(); ++i)
            if (auto h = shade::intersect(r, spheres[i]); h && (!nearest || h->t < nearest->second))
                nearest = {i, h->t};
        for (const shade::bvh_width width : widths) {
            CAPTURE(width);
            const shade::primitive_bvh<shade::sphere<double>> accel(spheres, width);
            const auto h = accel.closest(r);
            REQUIRE(h.has_value() == nearest.has_value());
            if (h) {
                CHECK(h->primitive == nearest->first);
                CHECK(h->hit.t == nearest->second);
            }
            CHECK(accel.any(r) == nearest.has_value());
        }
    });
}

// A direction component whose float reciprocal overflows (|d_k| < 2^-128 after the ray's
// scale): the slab distance (plane - o) / d_k may still be an ordinary number, but
// (plane - o) x inf is not. Found by fuzz_bvh (float, watertight leaves): a ray with
// direction (-2^-23, -0x1.0509p-133, 0) aimed at the vertex (0, 0, 0) of a triangle in
// the plane y = 0 reaches it at t = 1, where the exact ray touches the triangle's
// zero-thickness box; the box test computed t = +inf for the y slab and skipped the box.
// The rays below (float and double, tiny and huge directions) are each aimed at that
// vertex from (a, b, 0): d = -(a, b, 0), so y = b (1 - t) is 0 exactly at t = 1, and x is
// 0 there too. A loop of the watertight test over the triangles hits at t = 1.
TEST_CASE_TEMPLATE("triangle_bvh: directions whose components have no float reciprocal", T, float, double) {
    for_each_walk([&] {
        const std::vector<shade::triangle<T>> tris{
            {{1, 0, 0}, {0, 0, 0}, {1, 0, 1}},   // in y = 0, the one hit
            {{0, 0, -7}, {-6, -6, -13}, {1, 0, 0}},
            {{1, 1, 0}, {0, 0, 0}, {0, 0, 0}}};  // degenerate (a segment through the vertex)
        const shade::triangle_bvh<T, shade::watertight> accel(tris, shade::bvh_width::four);
        const shade::triangle_bvh<T, shade::watertight> wide(tris, shade::bvh_width::eight);
        std::vector<std::pair<T, T>> origins{{T(0x1p-23), T(0x1.0509p-133)}, {T(1), T(0x1p-149)},
                                             {T(0x1p-100), T(0x1p-140)}, {T(0x1p+100), T(0x1p-40)}};
        if constexpr (sizeof(T) == sizeof(double))
            // (Within the watertight test's own range: products of the sheared coordinates,
            // here about a b, between 1e-292 and 1e308.)
            origins.insert(origins.end(), {{T(0x1p-140), T(0x1p-160)}, {T(0x1p-400), T(0x1p-450)},
                                           {T(0x1p+60), T(0x1p+40)}, {T(1), T(0x1p-600)}});
        for (const auto& ab : origins) {
            const T a = ab.first;
            const T b = ab.second;
            CAPTURE(a);
            CAPTURE(b);
            const shade::ray<T> r{{a, b, 0}, {-a, -b, 0}, T(0), T(1)};
            const auto loop = brute_force<shade::watertight, T>(r, tris);
            REQUIRE(loop.has_value());
            CHECK(loop->second.t == T(1));
            for (const auto* tree : {&accel, &wide}) {
                const auto h = tree->closest(r);
                REQUIRE(h.has_value());
                CHECK(h->hit.t == loop->second.t);
                CHECK(tree->any(r));
                check_lean_query(*tree, r);
            }
        }
    });
}

// Which width a hierarchy gets: four when asked; eight when asked or by default exactly
// where the build and the CPU can test eight boxes with AVX; the same hits either way
// (the tests above), in fewer nodes with eight.
TEST_CASE("bvh_width: eight children where AVX is available, four when asked") {
    shade::rng g(11);
    const auto tris = random_mesh<float>(g, 2000, 0.2f);
    const shade::triangle_bvh<float> four(tris, shade::bvh_width::four);
    const shade::triangle_bvh<float> eight(tris, shade::bvh_width::eight);
    const shade::triangle_bvh<float> automatic(tris);
    const std::size_t expected = shade::detail::bvh_node_width(8); // 8 with AVX, else 4
    CHECK(four.node_width() == 4);
    CHECK(eight.node_width() == expected);
    CHECK(automatic.node_width() == expected);
    if (expected == 8) CHECK(eight.node_count() < four.node_count());
    std::vector<shade::aabb<float>> boxes;
    for (const auto& t : tris) boxes.push_back(shade::bounds(t));
    CHECK(shade::bvh<float>(boxes, shade::bvh_width::four).node_width() == 4);
    CHECK(shade::bvh<float>(boxes).node_width() == expected);
    const std::vector<shade::sphere<double>> one{shade::sphere<double>({0.0, 0.0, 0.0}, 1.0)};
    CHECK(shade::primitive_bvh<shade::sphere<double>>(one, shade::bvh_width::eight).node_width() == expected);
}

// The collapse into wide nodes fills the levels next to the leaves. Boxes on a grid of
// 4 x 8 x 8 cells, one per leaf, give a perfect binary tree of depth 8 (every split halves
// the longest side of cells: the heuristic's cost is symmetric and convex in the split
// position). 256 leaves need at least ceil(255 / 7) = 37 nodes of eight (each node adds
// at most 7 children to the one it takes), which the tree of root with 4 children, 4 of 8
// and 32 of 8 reaches; opening children from the top down instead gives 1 + 8 + 64 = 73
// (nodes of 8, 8 and 4). 2 x 8 x 8 cells in nodes of four: at least ceil(127 / 3) = 43.
TEST_CASE("bvh collapse: a perfect binary tree fills its wide nodes from the leaves up") {
    const auto grid = [](int nx) {
        std::vector<shade::detail::bvh_prim_ref> refs;
        for (int x = 0; x < nx; ++x)
            for (int y = 0; y < 8; ++y)
                for (int z = 0; z < 8; ++z) {
                    const v3<float> lo{float(x), float(y), float(z)};
                    refs.push_back(shade::detail::make_prim_ref(shade::aabb<float>{lo, lo + v3<float>(0.5f)},
                                                                static_cast<std::uint32_t>(refs.size())));
                }
        return refs;
    };
    auto refs8 = grid(4);
    const auto wide = shade::detail::bvh_builder(1, 1).build(refs8, 8);
    CHECK(wide.wide_nodes.size() == 37);
    auto refs4 = grid(2);
    const auto four = shade::detail::bvh_builder(1, 1).build(refs4, 4);
    CHECK(four.nodes.size() == 43);
    // Every leaf is reached exactly once.
    std::vector<int> seen(refs8.size());
    for (const auto& node : wide.wide_nodes)
        for (const std::uint32_t ref : node.child)
            if (shade::detail::is_leaf_ref(ref) && shade::detail::leaf_count(ref) > 0)
                ++seen[wide.order[shade::detail::leaf_first(ref)]];
    for (const int s : seen) CHECK(s == 1);
}

// bvh_node<8>::visit: for each octant a permutation of the eight children, the filled ones
// first, in order of the dot product of the octant's direction with their boxes' centres
// (ties in either order); octant 7 - o lists the filled ones in the opposite order. On a
// random soup (many ties-free keys), at node sizes 1-8, and on boxes with non-finite bounds.
TEST_CASE("bvh visit orders: per octant, the filled children sorted along the octant's direction") {
    shade::rng g(7);
    const auto check = [](const shade::detail::bvh_node<8>& node) {
        std::size_t n = 0;
        while (n < 8 && node.child[n] != shade::detail::make_leaf_ref(0, 0)) ++n;
        const auto key = [&](unsigned o, std::size_t j) {
            float sum = 0.0f;
            for (std::size_t k = 0; k < 3; ++k) {
                const float c = node.planes[2 * k][j] + node.planes[2 * k + 1][j];
                sum += (o >> k & 1u) != 0 ? -c : c;
            }
            return sum;
        };
        for (unsigned o = 0; o < 8; ++o) {
            const std::uint32_t w = node.visit[o];
            CHECK((w >> 24) == 0u);
            unsigned seen = 0;
            for (std::size_t p = 0; p < 8; ++p) {
                const std::size_t j = w >> (3 * p) & 7u;
                seen |= 1u << j;
                CHECK((p < n) == (j < n)); // the filled children first
                if (p == 0 || p >= n) continue;
                const std::size_t prev = w >> (3 * (p - 1)) & 7u;
                const float a = key(o, prev), b = key(o, j);
                if (std::isfinite(a) && std::isfinite(b)) CHECK(a <= b);
            }
            CHECK(seen == 0xffu); // a permutation
            // The opposite octant: the filled children reversed.
            for (std::size_t p = 0; p < n; ++p)
                CHECK((node.visit[7 - o] >> (3 * p) & 7u) == (w >> (3 * (n - 1 - p)) & 7u));
        }
    };
    for (const std::size_t count : {1u, 2u, 3u, 5u, 9u, 40u, 3000u}) {
        std::vector<shade::detail::bvh_prim_ref> refs;
        for (std::size_t i = 0; i < count; ++i) {
            const v3<float> lo{g.uniform<float>() * 100.0f, g.uniform<float>() * 100.0f, g.uniform<float>() * 100.0f};
            refs.push_back(shade::detail::make_prim_ref(shade::aabb<float>{lo, lo + v3<float>(g.uniform<float>())},
                                                        static_cast<std::uint32_t>(i)));
        }
        const auto tree = shade::detail::bvh_builder(1, 1).build(refs, 8);
        REQUIRE(!tree.wide_nodes.empty());
        for (const auto& node : tree.wide_nodes) check(node);
    }
    // A node whose children have infinite keys (bounds at +-max float: their centre sums
    // overflow) and a NaN key (a box from -inf to +inf).
    shade::detail::bvh_node<8> node{};
    const float big = std::numeric_limits<float>::max(), inf = std::numeric_limits<float>::infinity();
    for (std::size_t j = 0; j < 8; ++j) {
        const float lo = j == 1 ? -inf : j < 4 ? big / 2 : float(j), hi = j == 1 ? inf : j < 4 ? big : float(j) + 1;
        for (std::size_t k = 0; k < 3; ++k) node.planes[2 * k][j] = lo, node.planes[2 * k + 1][j] = hi;
        node.child[j] = j < 6 ? shade::detail::make_leaf_ref(static_cast<std::uint32_t>(j), 1) : shade::detail::make_leaf_ref(0, 0);
    }
    shade::detail::bvh_visit_orders(node, 6);
    check(node);
}

// memory_bytes counts the nodes and the leaf data as allocated. One triangle: one node
// (128 bytes with four children, 256 with eight) and, batched, one leaf block of 320 bytes
// (float: the vertices v0, v1, v2 as 9 arrays of 8 floats, 288, then 8 indices of 4 bytes,
// 32: five cache lines; double: 9 arrays of 4 doubles, 288, 4 indices, 16, padded to a
// multiple of 64); for watertight leaves, the
// triangle (36 bytes in float) and its index (4). bvh: the node and one index.
TEST_CASE("memory_bytes: nodes and leaf data, with no unused capacity") {
    const std::vector<shade::triangle<float>> one{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}};
    CHECK(shade::triangle_bvh<float>::leaf_bytes == 320);
    CHECK(shade::triangle_bvh<double>::leaf_bytes == 320);
    CHECK(shade::triangle_bvh<float>(one, shade::bvh_width::four).memory_bytes() == 128 + 320);
    CHECK(shade::triangle_bvh<float, shade::watertight>(one, shade::bvh_width::four).memory_bytes() ==
          128 + 36 + 4);
    const std::vector<shade::aabb<float>> box{shade::bounds(one[0])};
    CHECK(shade::bvh<float>(box, shade::bvh_width::four).memory_bytes() == 128 + 4);
    if (shade::detail::bvh_node_width(8) == 8)
        CHECK(shade::triangle_bvh<float>(one, shade::bvh_width::eight).memory_bytes() == 256 + 320);
    // Many triangles: the nodes are allocated exactly (node_count of them), and the leaf
    // blocks number at least ceil(n / 8).
    shade::rng g(5);
    const auto tris = random_mesh<float>(g, 3000, 0.2f);
    for (const shade::bvh_width width : widths) {
        const shade::triangle_bvh<float> accel(tris, width);
        const std::size_t node_bytes = accel.node_count() * (accel.node_width() == 8 ? 256 : 128);
        const std::size_t leaf_bytes = accel.memory_bytes() - node_bytes;
        CHECK(leaf_bytes % 320 == 0);
        CHECK(leaf_bytes / 320 >= (tris.size() + 7) / 8);
        const shade::triangle_bvh<float, shade::watertight> tight(tris, width);
        CHECK(tight.memory_bytes() == tight.node_count() * (tight.node_width() == 8 ? 256 : 128) + tris.size() * 40);
    }
}

// The parallel build (detail::bvh_builder with an executor) gives the recursive build's
// tree bit for bit, whatever the executor (in order, in reverse, on 1 to 4 threads) and
// the task size (the nodes above it split level by level, the rest as subtrees), at
// both widths: on a random mesh, a closed sphere, and 5000 copies of one triangle plus
// others (all centroids of the copies coincide: median splits inside the level phase).
TEST_CASE("bvh build: the same tree whatever the executor, threads and task size") {
    shade::rng g(11);
    std::vector<std::vector<shade::triangle<float>>> meshes{random_mesh<float>(g, 9000, 0.05f), closed_sphere<float>(5),
                                                            std::vector<shade::triangle<float>>(5000, {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}})};
    for (const auto& t : random_mesh<float>(g, 300, 0.5f)) meshes[2].push_back(t);
    const auto reverse = [](std::size_t n, const shade::parallel_task& task) {
        for (std::size_t i = n; i-- > 0;) task(i);
    };
    const support::thread_executor one(1), two(2), three(3), four(4);
    const auto same_bytes = [](const auto& a, const auto& b) {
        return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0);
    };
    for (const auto& tris : meshes) {
        std::vector<shade::detail::bvh_prim_ref> input;
        for (std::uint32_t i = 0; i < tris.size(); ++i) input.push_back(shade::detail::make_prim_ref(shade::bounds(tris[i]), i));
        for (const std::size_t width : {std::size_t(4), std::size_t(8)}) {
            auto refs = input;
            // One task for everything: the recursive build.
            const auto expected = shade::detail::bvh_builder(8, 8, 1u << 26).build(refs, width);
            CHECK(expected.order.size() == tris.size());
            int cases = 0;
            const auto check = [&](auto&& exec, std::uint32_t task_size) {
                auto r = input;
                const auto got = shade::detail::bvh_builder(8, 8, task_size).build(r, width, shade::detail::executor_ref(exec));
                CHECK(same_bytes(got.nodes, expected.nodes));
                CHECK(same_bytes(got.wide_nodes, expected.wide_nodes));
                CHECK(same_bytes(got.order, expected.order));
                ++cases;
            };
            for (const std::uint32_t task_size : {64u, 1000u, 4096u}) {
                CAPTURE(task_size);
                check(shade::serial_executor{}, task_size);
                check(reverse, task_size);
                check(one, task_size);
                check(two, task_size);
                check(three, task_size);
                check(four, task_size);
            }
            CHECK(cases == 18);
        }
    }
}

// The public constructors with an executor: the same hierarchy as without one (the same
// memory, nodes and hits, record for record), and hits that agree with brute force, at
// every width, for the batched leaves and the watertight ones, float and double; bvh and
// primitive_bvh too. A mesh above the default task size (4096), so the level phase runs.
TEST_CASE_TEMPLATE("triangle_bvh, bvh: built by an executor, the same hierarchy and hits", T, float, double) {
    for_each_walk([&] {
        shade::rng g(23);
        const auto tris = random_mesh<T>(g, 6000, T(0.3));
        const auto rays = random_rays<T>(g, 150);
        const support::thread_executor two(2);
        tally count;
        for (const shade::bvh_width width : widths) {
            CAPTURE(width);
            const shade::triangle_bvh<T> serial(tris, width);
            const shade::triangle_bvh<T> parallel(tris, width, two);
            CHECK(parallel.memory_bytes() == serial.memory_bytes());
            CHECK(parallel.node_count() == serial.node_count());
            for (const auto& r : rays) {
                const auto a = serial.closest(r), b = parallel.closest(r);
                REQUIRE(a.has_value() == b.has_value());
                if (!a) continue;
                CHECK(a->primitive == b->primitive);
                CHECK(a->hit.t == b->hit.t);
                CHECK(a->hit.p == b->hit.p);
            }
            check_against_brute_force(parallel, std::span<const shade::triangle<T>>(tris), rays, count);
            check_against_brute_force(shade::triangle_bvh<T, shade::watertight>(tris, width, two),
                                      std::span<const shade::triangle<T>>(tris), rays, count);
            std::vector<shade::aabb<T>> boxes;
            for (const auto& t : tris) boxes.push_back(shade::bounds(t));
            const shade::bvh<T> tree(boxes, width, two);
            CHECK(tree.memory_bytes() == shade::bvh<T>(boxes, width).memory_bytes());
            const auto test = [&](std::uint32_t i, const shade::ray<T>& r) { return shade::find_intersection(r, tris[i]); };
            for (const auto& r : rays) {
                const auto expected = brute_force<shade::moller_trumbore>(r, std::span<const shade::triangle<T>>(tris));
                const auto got = tree.closest(r, test);
                REQUIRE(got.has_value() == expected.has_value());
                if (got) CHECK(got->hit.t == expected->second.t);
            }
        }
        CHECK(count.hits > 50);
        CHECK(count.hits < count.rays);
        std::vector<shade::sphere<T>> spheres;
        for (std::size_t i = 0; i < 5000; ++i) spheres.emplace_back(in_cube<T>(g, T(4)), T(0.01));
        const shade::primitive_bvh<shade::sphere<T>> balls(spheres, shade::bvh_width::automatic, two);
        for (const auto& r : rays) {
            std::optional<T> nearest;
            for (const auto& s : spheres)
                if (auto h = shade::intersect(r, s); h && (!nearest || h->t < *nearest)) nearest = h->t;
            const auto got = balls.closest(r);
            REQUIRE(got.has_value() == nearest.has_value());
            if (got) CHECK(got->hit.t == *nearest);
        }
    });
}

// Bad input found by a task still throws from the constructor, naming the first bad
// element (here two, in different tasks of 4096).
TEST_CASE("triangle_bvh, bvh: an executor's build names the first non-finite input") {
    shade::rng g(3);
    auto tris = random_mesh<float>(g, 10000, 0.1f);
    tris[9000].v1.x = std::numeric_limits<float>::quiet_NaN();
    tris[5000].v2.z = std::numeric_limits<float>::infinity();
    const support::thread_executor two(2);
    CHECK_THROWS_WITH_AS(shade::triangle_bvh<float>(tris, shade::bvh_width::automatic, two),
                         doctest::Contains("triangle 5000"), shade::invalid_parameter);
    std::vector<shade::aabb<float>> boxes;
    for (const auto& t : tris) boxes.push_back(shade::bounds(t));
    CHECK_THROWS_WITH_AS(shade::bvh<float>(boxes, shade::bvh_width::automatic, two), doctest::Contains("element 5000"),
                         shade::invalid_parameter);
}
