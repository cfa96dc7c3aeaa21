#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/geometry/triangle.hpp>
#include <shade/geometry/triangle_algorithms.hpp>

#include "geometry/closed_meshes.hpp"
#include "geometry/special_rays.hpp"

namespace {

template <class T>
using v3 = shade::vec3<T>;

// One (algorithm, scalar) pair, so that TEST_CASE_TEMPLATE can run every algorithm in float
// and double over the same test body.
template <class Algorithm, class Scalar>
struct combo {
    using algorithm = Algorithm;
    using scalar = Scalar;
};

#define SHADE_TEST_ALL_COMBOS                                                              \
    combo<shade::moller_trumbore, float>, combo<shade::moller_trumbore, double>,           \
        combo<shade::plane_then_areas, float>, combo<shade::plane_then_areas, double>,     \
        combo<shade::watertight, float>, combo<shade::watertight, double>

static_assert(shade::triangle_algorithm<shade::moller_trumbore, float>);
static_assert(shade::triangle_algorithm<shade::plane_then_areas, double>);
static_assert(shade::triangle_algorithm<shade::watertight, float>);
static_assert(std::tuple_size_v<shade::triangle_algorithms> == 3);

template <class T>
bool near_rel(T a, T b, T rel) {
    return std::abs(a - b) <= rel * std::max(std::abs(a), std::abs(b));
}

template <class T>
bool near_vec(const v3<T>& a, const v3<T>& b, T tol) {
    return std::abs(a.x - b.x) <= tol && std::abs(a.y - b.y) <= tol && std::abs(a.z - b.z) <= tol;
}

template <class T>
constexpr T eps = std::numeric_limits<T>::epsilon();

// Calls f(algorithm_tag) for every algorithm in shade::triangle_algorithms.
template <class F>
void for_each_algorithm(F&& f) {
    std::apply([&](auto... algorithm) { (f(algorithm), ...); }, shade::triangle_algorithms{});
}

} // namespace

TEST_CASE_TEMPLATE("triangle: known front-face hit with hand-derived t, point, normal, barycentrics",
                   C, SHADE_TEST_ALL_COMBOS) {
    using T = typename C::scalar;
    using A = typename C::algorithm;
    // v0 = 0, v1 = (2,0,0), v2 = (0,2,0): counter-clockwise seen from +z, so
    // n = normalize((2,0,0) x (0,2,0)) = normalize((0,0,4)) = (0,0,1).
    // Ray from (0.5, 0.5, 3) along (0,0,-1) meets z = 0 at t = 3, p = (0.5, 0.5, 0).
    // p = v0 + u (v1 - v0) + v (v2 - v0) = (2u, 2v, 0) gives u = v = 0.25, so
    // (b0, b1, b2) = (1 - u - v, u, v) = (0.5, 0.25, 0.25). d·n = -1 < 0: front face.
    // All inputs and results are exact in binary, so only a few rounding steps separate
    // the computed values from these.
    const shade::triangle<T> tri{{0, 0, 0}, {2, 0, 0}, {0, 2, 0}};
    const shade::ray<T> r{{T(0.5), T(0.5), 3}, {0, 0, -1}};
    const auto h = shade::intersect<A>(r, tri);
    REQUIRE(h.has_value());
    const T tol = 8 * eps<T>;
    CHECK(near_rel(h->t, T(3), tol));
    CHECK(near_vec(h->p, v3<T>(T(0.5), T(0.5), 0), tol));
    CHECK(h->n == v3<T>(0, 0, 1));
    CHECK(h->front_face);
    CHECK(near_vec(h->barycentric, v3<T>(T(0.5), T(0.25), T(0.25)), tol));
    CHECK(h->u() == h->barycentric.y);
    CHECK(h->v() == h->barycentric.z);
    CHECK(h->facing_normal() == v3<T>(0, 0, 1));
    // Back-face culling keeps this front-face hit.
    CHECK(shade::intersect<A>(r, tri, shade::culling::back_faces).has_value());
}

TEST_CASE_TEMPLATE("triangle: back-face hit is reported double-sided and culled on request", C,
                   SHADE_TEST_ALL_COMBOS) {
    using T = typename C::scalar;
    using A = typename C::algorithm;
    // Same triangle, ray from below: origin (0.5, 1, -1), direction (0,0,2) (not unit).
    // z(t) = -1 + 2t = 0 at t = 0.5; p = (0.5, 1, 0): 2u = 0.5, 2v = 1, so
    // (b0, b1, b2) = (0.25, 0.25, 0.5). d·n = 2 > 0: back face; the normal stays the
    // triangle's own (0,0,1) and facing_normal() flips it toward the origin.
    const shade::triangle<T> tri{{0, 0, 0}, {2, 0, 0}, {0, 2, 0}};
    const shade::ray<T> r{{T(0.5), 1, -1}, {0, 0, 2}};
    const auto h = shade::intersect<A>(r, tri);
    REQUIRE(h.has_value());
    const T tol = 8 * eps<T>;
    CHECK(near_rel(h->t, T(0.5), tol));
    CHECK(near_vec(h->p, v3<T>(T(0.5), 1, 0), tol));
    CHECK(h->n == v3<T>(0, 0, 1));
    CHECK_FALSE(h->front_face);
    CHECK(h->facing_normal() == v3<T>(0, 0, -1));
    CHECK(near_vec(h->barycentric, v3<T>(T(0.25), T(0.25), T(0.5)), tol));
    CHECK_FALSE(shade::intersect<A>(r, tri, shade::culling::back_faces).has_value());
}

TEST_CASE_TEMPLATE("triangle: oblique triangle hit at its centroid", C, SHADE_TEST_ALL_COMBOS) {
    using T = typename C::scalar;
    using A = typename C::algorithm;
    // Triangle (1,0,0), (0,1,0), (0,0,1) lies in x + y + z = 1.
    // e1 = (-1,1,0), e2 = (-1,0,1): e1 x e2 = (1*1 - 0*0, 0*(-1) - (-1)*1, (-1)*0 - 1*(-1))
    // = (1,1,1), so n = (1,1,1)/sqrt(3), pointing away from the origin.
    // The ray from the origin along (1,1,1) meets the plane at 3t = 1: t = 1/3,
    // p = (1/3,1/3,1/3), the centroid, b = (1/3,1/3,1/3). d·n > 0: back face.
    const shade::triangle<T> tri{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    const shade::ray<T> r{{0, 0, 0}, {1, 1, 1}};
    const auto h = shade::intersect<A>(r, tri);
    REQUIRE(h.has_value());
    const T third = T(1) / T(3);
    const T tol = 16 * eps<T>;
    CHECK(near_rel(h->t, third, tol));
    CHECK(near_vec(h->p, v3<T>(third, third, third), tol));
    CHECK(near_vec(h->n, v3<T>(1, 1, 1) / std::sqrt(T(3)), tol));
    CHECK_FALSE(h->front_face);
    CHECK(near_vec(h->barycentric, v3<T>(third, third, third), tol));
    // The reverse ray from (1,1,1) along -(1,1,1) hits the front at t = 2/3.
    const auto g = shade::intersect<A>(shade::ray<T>{{1, 1, 1}, {-1, -1, -1}}, tri);
    REQUIRE(g.has_value());
    CHECK(g->front_face);
    CHECK(near_rel(g->t, 2 * third, tol));
}

TEST_CASE_TEMPLATE("triangle: clear misses beside each edge and beyond each vertex", C,
                   SHADE_TEST_ALL_COMBOS) {
    using T = typename C::scalar;
    using A = typename C::algorithm;
    // Triangle x >= 0, y >= 0, x + y <= 2 in z = 0. Rays straight down through points
    // outside it: (-0.1, 0.5) beyond edge v0v2 (x < 0), (0.5, -0.1) beyond v0v1, (1.1, 1)
    // beyond v1v2 (x + y = 2.1 > 2), and points past each vertex.
    const shade::triangle<T> tri{{0, 0, 0}, {2, 0, 0}, {0, 2, 0}};
    for (const auto& xy : {std::pair<T, T>(T(-0.1), T(0.5)), std::pair<T, T>(T(0.5), T(-0.1)),
                           std::pair<T, T>(T(1.1), T(1)), std::pair<T, T>(T(-0.1), T(-0.1)),
                           std::pair<T, T>(T(2.1), T(0)), std::pair<T, T>(T(0), T(2.1))}) {
        CAPTURE(xy.first);
        CAPTURE(xy.second);
        CHECK_FALSE(shade::intersect<A>(shade::ray<T>{{xy.first, xy.second, 1}, {0, 0, -1}}, tri)
                        .has_value());
    }
}

TEST_CASE_TEMPLATE("triangle: bad input never produces a hit", C, SHADE_TEST_ALL_COMBOS) {
    using T = typename C::scalar;
    using A = typename C::algorithm;
    const T nan = std::numeric_limits<T>::quiet_NaN();
    const T inf = std::numeric_limits<T>::infinity();
    const shade::triangle<T> tri{{0, 0, 0}, {2, 0, 0}, {0, 2, 0}};
    // A ray that hits tri at t = 3 (see the first test), as a baseline.
    const shade::ray<T> good{{T(0.5), T(0.5), 3}, {0, 0, -1}};
    REQUIRE(shade::intersect<A>(good, tri).has_value());
    auto miss = [&](const shade::ray<T>& r, const shade::triangle<T>& t) {
        return !shade::intersect<A>(r, t).has_value();
    };

    SUBCASE("NaN or zero direction, non-finite origin") {
        CHECK(miss({good.origin, {0, 0, nan}}, tri));
        CHECK(miss({good.origin, {nan, nan, nan}}, tri));
        CHECK(miss({good.origin, {0, 0, 0}}, tri));
        CHECK(miss({good.origin, {0, 0, -inf}}, tri));
        CHECK(miss({{T(0.5), T(0.5), inf}, good.direction}, tri));
        CHECK(miss({{nan, T(0.5), 3}, good.direction}, tri));
    }
    SUBCASE("bad ray interval") {
        CHECK(miss({good.origin, good.direction, nan, shade::infinity<T>}, tri));
        CHECK(miss({good.origin, good.direction, 0, nan}, tri));
        CHECK(miss({good.origin, good.direction, 4, 2}, tri)); // t_min > t_max
        CHECK(miss({good.origin, good.direction, -1, 10}, tri)); // t_min < 0 is invalid
    }
    SUBCASE("t outside [t_min, t_max]") {
        CHECK(miss({good.origin, good.direction, 0, T(2.5)}, tri));
        CHECK(miss({good.origin, good.direction, T(3.5), 10}, tri));
        // Closed interval: the hit at t = 3 (exact here) is kept at either end.
        CHECK_FALSE(miss({good.origin, good.direction, 3, 3}, tri));
    }
    SUBCASE("triangle behind the origin") {
        CHECK(miss({good.origin, {0, 0, 1}}, tri));
        CHECK(miss({{T(0.5), T(0.5), -3}, {0, 0, -1}}, tri));
    }
    SUBCASE("ray parallel to the triangle's plane, off it and in it") {
        CHECK(miss({{-1, T(0.5), 1}, {1, 0, 0}}, tri));
        CHECK(miss({{-1, T(0.5), 0}, {1, 0, 0}}, tri)); // lies in the plane, crosses the triangle
    }
    SUBCASE("degenerate (zero-area) triangles") {
        // Two equal vertices, all equal, and collinear vertices (exactly: (2,2,2) = 2(1,1,1)).
        CHECK(miss(good, {{0, 0, 0}, {0, 0, 0}, {0, 2, 0}}));
        CHECK(miss(good, {{T(0.5), T(0.5), 0}, {T(0.5), T(0.5), 0}, {T(0.5), T(0.5), 0}}));
        CHECK(miss({{1, 1, 3}, {0, 0, -1}}, {{0, 0, 0}, {1, 1, 0}, {2, 2, 0}}));
        CHECK(miss({{-1, 0, 0}, {1, 1, 1}}, {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}}));
    }
    SUBCASE("non-finite vertices") {
        CHECK(miss(good, {{0, 0, 0}, {inf, 0, 0}, {0, 2, 0}}));
        CHECK(miss(good, {{nan, 0, 0}, {2, 0, 0}, {0, 2, 0}}));
        CHECK(miss(good, {{0, 0, 0}, {2, 0, 0}, {0, 2, nan}}));
    }
}

// The triangle v0 = 0, v1 = (2L, 0, 0), v2 = (L, 2L, 0) in the plane z = 0 and a ray from
// (1, 1, z0) along (0, 0, -z0 D), z0 = ±1, toward the corner v0. With s = o - v0 = (1, 1, z0)
// and d = (0, 0, -z0 D):
//     n = e1 × e2 = (0, 0, 4 L^2),   c = d × s = (z0 D, -z0 D, 0),
//     U = -e2·c = z0 L D,  V = e1·c = 2 z0 L D,  T = s·n = 4 z0 L^2,  det = -d·n = 4 z0 D L^2,
// so the true t = T/det = 1/D, b1 = 1/(4L), b2 = 1/(2L). L = 1e15, D = 1e10 (float) or
// L = 1e150, D = 1e10 (double): n, U, V and T are finite, but det = ±4e40 (±4e310)
// overflows to ±infinity. Then W = det - (U + V) is infinite with the sign of det, t = T/det
// rounds to +0, and b0 = W/det would be NaN: Möller-Trumbore must report no hit (its
// documented rule for an overflowing product) rather than a hit at t = 0.
TEST_CASE_TEMPLATE("triangle: an overflowing det, with U, V and T finite, is no Möller-Trumbore hit",
                   T, float, double) {
    const T L = std::is_same_v<T, float> ? T(1e15) : T(1e150);
    const T D = T(1e10);
    const shade::triangle<T> tri{{0, 0, 0}, {2 * L, 0, 0}, {L, 2 * L, 0}};
    REQUIRE(std::isfinite(glm::cross(tri.v1 - tri.v0, tri.v2 - tri.v0).z));
    for (const T z0 : {T(1), T(-1)}) { // front face, then back face
        CAPTURE(z0);
        const shade::ray<T> r{{1, 1, z0}, {0, 0, -z0 * D}};
        REQUIRE(std::isinf(glm::dot(r.direction, glm::cross(tri.v1 - tri.v0, tri.v2 - tri.v0))));
        CHECK_FALSE(shade::find_intersection<shade::moller_trumbore>(r, tri).has_value());
        // The other algorithms may find the hit at t = 1/D; whatever they report must be a
        // valid record.
        for_each_algorithm([&](auto algorithm) {
            using A = decltype(algorithm);
            CAPTURE(A::name);
            if (const auto x = shade::find_intersection<A>(r, tri)) {
                CHECK(std::isfinite(x->t));
                CHECK(x->t >= T(0));
                CHECK(shade::is_finite(x->barycentric));
            }
        });
    }
}

TEST_CASE_TEMPLATE("triangle: tiny triangles at distance 1 are hit (no absolute epsilon)", C,
                   SHADE_TEST_ALL_COMBOS) {
    using T = typename C::scalar;
    using A = typename C::algorithm;
    // A right triangle of legs w in the plane z = -1: v0 = (0,0,-1), v1 = v0 + (w,0,0),
    // v2 = v0 + (0,w,0), front face toward +z. The ray from the origin along
    // (w/4, w/4, -1) meets z = -1 at t = 1, p = (w/4, w/4, -1) = v0 + u e1 + v e2 with
    // u = v = 1/4, so b = (1/2, 1/4, 1/4). GLM 0.9.9.8's intersectRayTriangle rejects
    // |det| < epsilon = 1.2e-7 (float), and det = w^2 = 1e-8 here for w = 1e-4: a miss.
    // Widths down to 1e-6 in float and 1e-12 in double are tested; the relative
    // tolerance is a few roundings of the barycentric and t computations.
    std::vector<T> widths{T(1e-4), T(1e-6)};
    if constexpr (std::is_same_v<T, double>) {
        widths.push_back(T(1e-9));
        widths.push_back(T(1e-12));
    }
    for (const T w : widths) {
        CAPTURE(w);
        const shade::triangle<T> tri{{0, 0, -1}, {w, 0, -1}, {0, w, -1}};
        const shade::ray<T> r{{0, 0, 0}, {w / 4, w / 4, -1}};
        const auto h = shade::intersect<A>(r, tri);
        REQUIRE(h.has_value());
        CHECK(near_rel(h->t, T(1), 8 * eps<T>));
        CHECK(h->front_face);
        CHECK(h->n == v3<T>(0, 0, 1));
        CHECK(near_vec(h->barycentric, v3<T>(T(0.5), T(0.25), T(0.25)), 64 * eps<T>));
        // Just beside the tiny triangle (a quarter width past the hypotenuse) is a miss.
        const shade::ray<T> beside{{0, 0, 0}, {w * T(0.625), w * T(0.625), -1}};
        CHECK_FALSE(shade::intersect<A>(beside, tri).has_value());
    }
}

// ---------------------------------------------------------------------------------------
// All algorithms agree on random ray/triangle pairs.
//
// Reference: the ray/plane parameter and the barycentrics solved in long double (Cramer's
// rule, 64-bit mantissa on x86-64, far more precise than the float and double under test):
//     b_i = signed sub-triangle area / total area in the plane, t = n·(v0 - o) / n·d.
// Every algorithm must match the reference's hit/miss verdict, except where the reference
// hit point is within `edge_band` (in barycentric units) of an edge: there, rounding in
// the algorithm may legitimately flip the verdict. Such edge-grazing disagreements are
// counted and the count is asserted to be tiny.
//
// Error model. Each algorithm's barycentric (and t) is a ratio of sums of products of the
// inputs, so its absolute rounding error is a modest multiple of eps times the
// condition number kappa = |d| |n| / |d·n| (1 / cos of the angle between the ray and the
// normal): the in-plane position error of a ray hitting at a grazing angle is stretched
// by 1/cos. Möller-Trumbore's t also grows with the triangle's skinniness, since it
// divides by det = -d·n with numerators of size |d||e1||e2| rather than |d||n| (seen: up
// to ~50 eps kappa on these random triangles; the others stay below ~4). With inputs and
// edges of size ~1, a band of 2^10 eps kappa (about a thousand roundings) covers the
// hit/miss flips and the t tolerance is 2^8 eps kappa relative. Both are far below
// anything a wrong formula would produce (errors of order 1). Each algorithm's worst t
// error is reported in units of eps kappa.
namespace {

struct reference_result {
    bool hit = false;       // exact-ish verdict: t in range and every b_i >= 0
    long double t = 0;      // ray parameter of the plane hit
    long double b_min = 0;  // smallest barycentric (negative: outside by that much)
    long double kappa = 0;  // |d||n| / |d·n|
};

template <class T>
reference_result reference(const shade::ray<T>& r, const shade::triangle<T>& tri) {
    using L = long double;
    using lv = glm::vec<3, L>;
    const lv o(r.origin), d(r.direction), p0(tri.v0), p1(tri.v1), p2(tri.v2);
    const lv n = glm::cross(p1 - p0, p2 - p0);
    const L n_dot_d = glm::dot(n, d);
    reference_result res;
    if (n_dot_d == 0) return res;
    res.t = glm::dot(n, p0 - o) / n_dot_d;
    const lv p = o + res.t * d;
    const L nn = glm::dot(n, n);
    const L b0 = glm::dot(n, glm::cross(p2 - p1, p - p1)) / nn;
    const L b1 = glm::dot(n, glm::cross(p0 - p2, p - p2)) / nn;
    const L b2 = glm::dot(n, glm::cross(p1 - p0, p - p0)) / nn;
    res.b_min = std::min(b0, std::min(b1, b2));
    res.kappa = std::sqrt(nn) * glm::length(d) / std::abs(n_dot_d);
    res.hit = res.t >= 0 && res.b_min >= 0;
    return res;
}

} // namespace

TEST_CASE_TEMPLATE("triangle: all algorithms agree on 10^5 random ray/triangle pairs", T, float,
                   double) {
    std::mt19937_64 rng(20240611);
    std::uniform_real_distribution<T> unit(T(-1), T(1));
    auto random_point = [&](T scale) { return v3<T>(unit(rng), unit(rng), unit(rng)) * scale; };

    const int pairs = 100000;
    const T edge_factor = T(1024); // band 2^10 eps kappa, see the error model above
    const T t_factor = T(256);     // t tolerance 2^8 eps kappa, relative
    struct tally {
        int hits = 0, disagreements = 0, t_failures = 0, unexplained = 0;
        long double worst_t = 0; // largest |t - t_ref| / (eps kappa |t_ref|) seen
    };
    std::map<std::string, tally> tallies;
    int reference_hits = 0;

    for (int i = 0; i < pairs; ++i) {
        const shade::triangle<T> tri{random_point(1), random_point(1), random_point(1)};
        // Origins in a cube of half-width 4 around the triangle, aimed at a random point of
        // the triangle's plane with barycentrics (1 - b1 - b2, b1, b2), b1, b2 uniform in
        // [-0.25, 1]: roughly a third of the rays hit.
        const v3<T> origin = random_point(4);
        const T b1 = T(0.375) + T(0.625) * unit(rng);
        const T b2 = T(0.375) + T(0.625) * unit(rng);
        const v3<T> target = (1 - b1 - b2) * tri.v0 + b1 * tri.v1 + b2 * tri.v2;
        const shade::ray<T> r{origin, target - origin};
        const reference_result ref = reference(r, tri);
        if (ref.hit) ++reference_hits;
        const long double band =
            static_cast<long double>(edge_factor * eps<T>) * ref.kappa;

        for_each_algorithm([&](auto algorithm) {
            using A = decltype(algorithm);
            tally& k = tallies[std::string(A::name)];
            const auto h = shade::intersect<A>(r, tri, shade::culling::none);
            if (h) ++k.hits;
            if (h.has_value() != ref.hit) {
                ++k.disagreements;
                if (!(std::abs(ref.b_min) <= band)) ++k.unexplained;
            } else if (h) {
                const long double unit_error =
                    static_cast<long double>(eps<T>) * ref.kappa * std::abs(ref.t);
                const long double error = std::abs(static_cast<long double>(h->t) - ref.t);
                k.worst_t = std::max(k.worst_t, error / unit_error);
                if (!(error <= static_cast<long double>(t_factor) * unit_error)) ++k.t_failures;
            }
        });
    }

    MESSAGE("reference hits: " << reference_hits << " of " << pairs);
    for (const auto& entry : tallies) {
        const std::string& name = entry.first; // not a structured binding: CAPTURE needs a variable
        const tally& k = entry.second;
        MESSAGE(name << ": hits " << k.hits << ", edge-grazing disagreements with the reference "
                     << k.disagreements << ", worst t error " << static_cast<double>(k.worst_t)
                     << " eps kappa");
        CAPTURE(name);
        CHECK(k.unexplained == 0); // every disagreement lies within the edge band
        CHECK(k.t_failures == 0);
        // Hits within the edge band are rare (the band is ~1e-4 wide in float at kappa ~ 1,
        // ~1e-12 in double); at most 1 pair in 1000 may disagree.
        CHECK(k.disagreements <= pairs / 1000);
    }
    // The test must be able to see hits and misses in numbers.
    CHECK(reference_hits > pairs / 5);
    CHECK(reference_hits < pairs * 4 / 5);
}

// ---------------------------------------------------------------------------------------
// Watertightness on closed meshes with exactly shared vertices.
namespace {

using geometry_test::edge_and_vertex_targets;
using geometry_test::icosphere;
using geometry_test::mesh;
using geometry_test::tessellated_cube;

template <class A, class T>
bool mesh_hit(const mesh<T>& m, const shade::ray<T>& r) {
    for (std::size_t f = 0; f < m.faces.size(); ++f)
        if (shade::intersect<A>(r, m.triangle(f), shade::culling::none)) return true;
    return false;
}

// Counts, per algorithm, the rays that pass through no triangle of the closed mesh m,
// for rays from several inside and outside origins aimed at every target. Every such ray
// crosses the surface: from inside it must leave the mesh, and from outside it heads into
// the convex mesh (the origins are placed outward of the target, roughly along the
// surface normal, so no ray grazes the silhouette).
template <class T>
std::map<std::string, int> count_misses(const mesh<T>& m, const std::vector<v3<T>>& targets,
                                        int& rays) {
    std::map<std::string, int> misses;
    for_each_algorithm([&](auto algorithm) { misses[std::string(decltype(algorithm)::name)] = 0; });
    const std::array<v3<T>, 3> inside{v3<T>(0, 0, 0), v3<T>(T(0.1), T(-0.2), T(0.3)),
                                      v3<T>(T(-0.25), T(0.125), T(-0.0625))};
    const std::array<v3<T>, 3> outside_offset{v3<T>(0, 0, 0), v3<T>(T(0.3), T(0.1), T(-0.2)),
                                              v3<T>(T(-0.2), T(0.25), T(0.1))};
    rays = 0;
    for (const v3<T>& target : targets) {
        std::vector<shade::ray<T>> batch;
        for (const v3<T>& o : inside) batch.push_back({o, target - o});
        for (const v3<T>& off : outside_offset) {
            const v3<T> o = target * T(3) + off;
            batch.push_back({o, target - o});
        }
        for (const auto& r : batch) {
            ++rays;
            for_each_algorithm([&](auto algorithm) {
                using A = decltype(algorithm);
                if (!mesh_hit<A>(m, r)) ++misses[std::string(A::name)];
            });
        }
    }
    return misses;
}

} // namespace

TEST_CASE_TEMPLATE("triangle: watertight never misses shared edges and vertices of a closed icosphere",
                   T, float, double) {
    const mesh<T> m = icosphere<T>(2); // 320 faces, 162 shared vertices, 480 edges
    REQUIRE(m.faces.size() == 320);
    REQUIRE(m.vertices.size() == 162);
    REQUIRE(m.edges().size() == 480);
    int rays = 0;
    const auto misses = count_misses(m, edge_and_vertex_targets(m), rays);
    for (const auto& [name, count] : misses)
        MESSAGE(name << ": " << count << " of " << rays << " edge/vertex rays miss the icosphere");
    CHECK(misses.at("watertight") == 0);
}

TEST_CASE_TEMPLATE("triangle: watertight never misses shared edges and vertices of a tessellated cube",
                   T, float, double) {
    // The rays of count_misses, plus axis-parallel rays through points EXACTLY on the
    // shared edges: on a face of the cube, the grid lines and the diagonals
    // x - x0 = y - y0 of each square, at coordinates that are exact in binary.
    const int n = 4;
    const mesh<T> m = tessellated_cube<T>(n);
    REQUIRE(m.faces.size() == 6 * n * n * 2);
    int rays = 0;
    auto misses = count_misses(m, edge_and_vertex_targets(m), rays);

    const T step = T(2) / T(n);
    for (int axis = 0; axis < 3; ++axis)
        for (int side = -1; side <= 1; side += 2)
            for (int i = 0; i < n; ++i)
                for (int j = 0; j <= n; ++j)
                    for (const T s : {T(0), T(0.25), T(0.5), T(0.875)}) {
                        // On the grid line a = -1 + i step + s step, b = -1 + j step, and on
                        // the diagonal of square (i, j): a = b' = -1 + (i + s) step, b' =
                        // -1 + (j + s) step (j < n).
                        const T a = -1 + (T(i) + s) * step;
                        std::vector<std::pair<T, T>> points{{a, -1 + T(j) * step}};
                        if (j < n) points.emplace_back(a, -1 + (T(j) + s) * step);
                        for (const auto& [pa, pb] : points) {
                            // Points on the cube's own edges would give rays lying in the
                            // plane of a side face; keep to rays crossing the surface.
                            if (std::abs(pa) == 1 || std::abs(pb) == 1) continue;
                            for (const T depth : {T(0.5), T(3)}) { // from inside and outside
                                v3<T> o(0, 0, 0), d(0, 0, 0);
                                const int ax = axis;
                                o[(ax + 1) % 3] = pa;
                                o[(ax + 2) % 3] = pb;
                                // Inside (0.5) the ray heads out through face `side`; outside
                                // (3) it heads in through the same face.
                                o[ax] = T(side) * depth;
                                d[ax] = depth < 1 ? T(side) : T(-side);
                                const shade::ray<T> r{o, d};
                                ++rays;
                                for_each_algorithm([&](auto algorithm) {
                                    using A = decltype(algorithm);
                                    if (!mesh_hit<A>(m, r)) ++misses[std::string(A::name)];
                                });
                            }
                        }
                    }
    for (const auto& [name, count] : misses)
        MESSAGE(name << ": " << count << " of " << rays << " edge/vertex rays miss the cube");
    CHECK(misses.at("watertight") == 0);
}

// ---------------------------------------------------------------------------------------
TEST_CASE_TEMPLATE("triangle: scaled by 1e-3 or 1e3, or translated by 1e4, the scene gives the same hits",
                   C, SHADE_TEST_ALL_COMBOS) {
    using T = typename C::scalar;
    using A = typename C::algorithm;
    // A small scene whose coordinates are multiples of 1/8 (exact in binary, and still
    // exact after adding 1e4 in float, whose spacing there is 2^-10). Rays aim at points
    // with barycentrics well inside (>= 1/8 from every edge) or well outside (<= -1/8), so
    // every verdict has a wide margin over rounding.
    const std::vector<shade::triangle<T>> scene{
        {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}},
        {{1, T(0.5), -1}, {T(0.5), 2, T(-0.75)}, {T(-1.5), T(0.25), T(-1.25)}},
        {{T(-0.5), -1, 1}, {T(1.5), T(-0.75), T(1.25)}, {T(0.25), T(1.5), T(0.5)}},
    };
    const std::vector<v3<T>> barycentric_targets{
        {T(0.25), T(0.25), T(0.5)},      {T(0.125), T(0.625), T(0.25)},
        {T(0.75), T(0.125), T(0.125)},   {T(-0.125), T(0.5), T(0.625)},
        {T(0.5), T(0.75), T(-0.25)},     {T(1.25), T(-0.125), T(-0.125)},
    };
    const std::vector<v3<T>> origins{{T(0.5), T(0.25), 4}, {-3, 1, T(-2.5)}, {2, -3, T(0.75)}};

    struct scene_ray {
        shade::ray<T> r;
        std::size_t tri;
    };
    std::vector<scene_ray> rays;
    for (std::size_t k = 0; k < scene.size(); ++k)
        for (const auto& b : barycentric_targets)
            for (const auto& o : origins) {
                const auto& tri = scene[k];
                const v3<T> target = b.x * tri.v0 + b.y * tri.v1 + b.z * tri.v2;
                rays.push_back({shade::ray<T>{o, target - o}, k});
            }

    // Transform points by p -> s p + offset and keep directions: t scales by s.
    auto transformed = [](const v3<T>& p, T s, const v3<T>& offset) { return p * s + offset; };
    struct transform {
        T s;
        v3<T> offset;
    };
    const std::vector<transform> transforms{
        {T(1e-3), {0, 0, 0}}, {T(1e3), {0, 0, 0}}, {T(1), {T(1e4), T(1e4), T(1e4)}}};
    int hits = 0;
    for (const auto& tf : transforms) {
        CAPTURE(tf.s);
        CAPTURE(tf.offset.x);
        for (const auto& sr : rays) {
            const auto& tri = scene[sr.tri];
            const auto h = shade::intersect<A>(sr.r, tri);
            const shade::triangle<T> tri2{transformed(tri.v0, tf.s, tf.offset),
                                          transformed(tri.v1, tf.s, tf.offset),
                                          transformed(tri.v2, tf.s, tf.offset)};
            const shade::ray<T> r2{transformed(sr.r.origin, tf.s, tf.offset), sr.r.direction};
            const auto h2 = shade::intersect<A>(r2, tri2);
            // The tolerance below assumes no grazing ray: cos(angle to the normal) > 0.15
            // (at most about 81 degrees from the normal, condition number below 7).
            REQUIRE(std::abs(glm::dot(tri.normal(), glm::normalize(sr.r.direction))) > T(0.15));
            REQUIRE(h.has_value() == h2.has_value());
            if (!h) continue;
            ++hits;
            // Scaling by 1e-3 rounds each input by up to eps/2 (relative) and translating by
            // 1e4 is exact, so t / s changes by a few roundings times the condition number
            // of these rays (below 7, checked above): 64 eps.
            CHECK(near_rel(h2->t, h->t * tf.s, 64 * eps<T>));
            CHECK(h2->front_face == h->front_face);
            CHECK(near_vec(h2->n, h->n, 64 * eps<T>));
        }
    }
    CHECK(hits > 0);
}

// ---------------------------------------------------------------------------------------
// The lean test and the record: find_intersection and make_hit.

TEST_CASE_TEMPLATE("triangle: intersect is find_intersection followed by make_hit", C,
                   SHADE_TEST_ALL_COMBOS) {
    using T = typename C::scalar;
    using A = typename C::algorithm;
    std::mt19937_64 rng(77);
    std::uniform_real_distribution<T> unit(T(-1), T(1));
    std::size_t hits = 0;
    for (int k = 0; k < 20000; ++k) {
        const shade::triangle<T> tri{{unit(rng), unit(rng), unit(rng)},
                                     {unit(rng), unit(rng), unit(rng)},
                                     {unit(rng), unit(rng), unit(rng)}};
        // Aimed near the centroid, so that about half of the rays hit.
        const v3<T> o(2 * unit(rng), 2 * unit(rng), 2 * unit(rng));
        const v3<T> aim = (tri.v0 + tri.v1 + tri.v2) / T(3) +
                          T(0.3) * v3<T>(unit(rng), unit(rng), unit(rng));
        const shade::ray<T> r{o, aim - o};
        const auto cull = (k % 2) ? shade::culling::back_faces : shade::culling::none;
        const auto x = shade::find_intersection<A>(r, tri, cull);
        const auto h = shade::intersect<A>(r, tri, cull);
        REQUIRE(x.has_value() == h.has_value());
        if (!x) continue;
        ++hits;
        CHECK(x->t == h->t);
        CHECK(x->barycentric == h->barycentric);
        CHECK(x->front_face == h->front_face);
        CHECK(x->u() == x->barycentric.y);
        CHECK(x->v() == x->barycentric.z);
        // The record: the interpolated point and the triangle's own unit normal.
        const auto m = shade::make_hit(tri, *x);
        CHECK(m.n == tri.normal());
        // p = b0 v0 + b1 v1 + b2 v2 up to rounding: an FMA build (tests/robustness) may
        // fuse the sum differently here and in make_hit, so allow a few ulps of the terms.
        const v3<T> interpolated = x->barycentric.x * tri.v0 + x->barycentric.y * tri.v1 +
                                   x->barycentric.z * tri.v2;
        const T scale = glm::length(tri.v0) + glm::length(tri.v1) + glm::length(tri.v2);
        CHECK(near_vec(m.p, interpolated, 4 * eps<T> * scale));
        CHECK(m.p == h->p);
    }
    CHECK(hits > 4000);
}

TEST_CASE_TEMPLATE("triangle: make_hit keeps the point on the triangle's bounding box when the "
                   "interpolation overflows",
                   T, float, double) {
    // Every vertex has x = max. With b = (1/2, 1/2, 2^-20) (sum above 1, as rounded
    // barycentrics may be), b0 max + b1 max = max exactly and adding 2^-20 max overflows:
    // p.x is clamped to the bounding box [max, max].
    const T max = std::numeric_limits<T>::max();
    const shade::triangle<T> tri{{max, 0, 0}, {max, 1, 0}, {max, 0, 1}};
    const shade::triangle_intersection<T> x{T(1), v3<T>(T(0.5), T(0.5), T(0x1p-20)), true};
    REQUIRE_FALSE(std::isfinite(x.barycentric.x * max + x.barycentric.y * max +
                                x.barycentric.z * max));
    const auto h = shade::make_hit(tri, x);
    CHECK(h.p.x == max);
    CHECK(h.p.y == T(0.5));
    CHECK(h.p.z == T(0x1p-20));
    CHECK(h.n == v3<T>(1, 0, 0));
}

// Only where no fused multiply-add can be formed (tests/robustness builds this file with
// FMA and contraction on, and the compiler may then fuse the lanes and the scalar code
// differently).
#if defined(__GNUC__) && !defined(__FMA__) && !defined(__FP_FAST_FMAF)
namespace {

bool same_bits(float a, float b) { return std::bit_cast<std::uint32_t>(a) == std::bit_cast<std::uint32_t>(b); }
bool same_bits(const v3<float>& a, const v3<float>& b) {
    return same_bits(a.x, b.x) && same_bits(a.y, b.y) && same_bits(a.z, b.z);
}

} // namespace

TEST_CASE("triangle: float make_hit and normal() in lanes give the scalar form's bits") {
    // make_hit<float> and triangle<float>::normal() compute in four-lane vectors
    // (detail::make_hit_lanes); detail::make_hit_scalar and the scalar
    // unit_normal_from_cross(glm::cross(...)) are the same operations one component at a
    // time. Triangles of every scale from 2^-70 to 2^+70 (and some near the largest float,
    // where p overflows and is clamped, and near the smallest, where the normal is
    // rescaled), slivers, axis-aligned ones, and barycentrics that need not sum to 1.
    std::mt19937_64 rng(2026);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f), weight(0.0f, 1.0f);
    std::uniform_int_distribution<int> exponent(-70, 70), kind(0, 9);
    const float max = std::numeric_limits<float>::max();
    std::size_t clamped = 0, rescaled = 0;
    for (int k = 0; k < 200000; ++k) {
        const int shape = kind(rng);
        float scale = std::ldexp(1.0f, exponent(rng));
        if (shape == 0) scale = max * weight(rng);                     // p may overflow
        if (shape == 1) scale = std::ldexp(1.0f, -60 - kind(rng) * 3); // c·c underflows
        const auto point = [&] { return scale * v3<float>(unit(rng), unit(rng), unit(rng)); };
        shade::triangle<float> tri{point(), point(), point()};
        if (shape == 2) tri.v2 = tri.v0 + (tri.v1 - tri.v0) * weight(rng) + 1e-5f * point(); // a sliver
        if (shape == 3) tri.v0.z = tri.v1.z = tri.v2.z;                                    // axis-aligned
        if (shape == 4) tri.v1 = tri.v0;                                                   // degenerate
        if (shape == 0) tri.v0.x = tri.v1.x = tri.v2.x = max;
        const float b1 = weight(rng), b2 = weight(rng) * (1.0f - b1);
        const shade::triangle_intersection<float> x{weight(rng), v3<float>(1.0f - b1 - b2, b1, b2), kind(rng) < 5};
        const auto lanes = shade::make_hit(tri, x);
        const auto scalar = shade::detail::make_hit_scalar(tri, x);
        const v3<float> normal = shade::detail::unit_normal_from_cross(glm::cross(tri.v1 - tri.v0, tri.v2 - tri.v0));
        const float len2 = glm::dot(glm::cross(tri.v1 - tri.v0, tri.v2 - tri.v0), glm::cross(tri.v1 - tri.v0, tri.v2 - tri.v0));
        rescaled += !(len2 >= std::numeric_limits<float>::min());
        clamped += !shade::is_finite(x.barycentric.x * tri.v0 + x.barycentric.y * tri.v1 + x.barycentric.z * tri.v2);
        INFO("triangle ", k, " shape ", shape);
        REQUIRE(same_bits(tri.normal(), normal));
        REQUIRE(same_bits(lanes.n, normal));
        REQUIRE(same_bits(lanes.p, scalar.p));
        REQUIRE(same_bits(lanes.p_error, scalar.p_error));
        REQUIRE(same_bits(lanes.dpdu, scalar.dpdu));
        REQUIRE(same_bits(lanes.t, scalar.t));
        REQUIRE(same_bits(lanes.barycentric, scalar.barycentric));
        REQUIRE(same_bits(lanes.uv.x, scalar.uv.x));
        REQUIRE(same_bits(lanes.uv.y, scalar.uv.y));
        REQUIRE(lanes.front_face == scalar.front_face);
    }
    CHECK(clamped > 100); // about 440
    CHECK(rescaled > 1000);
}
#endif

TEST_CASE_TEMPLATE("triangle: no ray that is not valid() hits, over a sweep of special values", C,
                   SHADE_TEST_ALL_COMBOS) {
    // Möller-Trumbore has no explicit ray::valid() test: it relies on a non-finite or zero
    // origin or direction turning det, U or V into NaN, infinity or zero. The sweep of
    // geometry/special_rays.hpp checks that claim (and the others' explicit test) against
    // triangles the valid version of the ray hits.
    using T = typename C::scalar;
    using A = typename C::algorithm;
    const std::array<shade::triangle<T>, 3> tris{
        shade::triangle<T>{{-4, -4, 0}, {4, -4, 0}, {0, 4, 0}},
        shade::triangle<T>{{0, -4, -4}, {0, 4, -4}, {0, 0, 4}},
        shade::triangle<T>{{-4, 0, -4}, {4, 0, -4}, {0, 0, 4}}};
    // intersect<A> is find_intersection<A> followed by make_hit, so this also checks the
    // hit point and the unit normal of every valid hit.
    geometry_test::check_special_rays<T>(tris, [](const shade::ray<T>& r, const shade::triangle<T>& tri) {
        return shade::intersect<A>(r, tri);
    });
}
