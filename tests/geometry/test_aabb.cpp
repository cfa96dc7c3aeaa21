// aabb: the box itself, and the robust slab test against an exact reference on rays that
// touch boxes only at a corner or along an edge (where rounding decides), with a check
// that the Ize enlargement is what makes those pass.

#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

#include <doctest/doctest.h>

#include <shade/core/random.hpp>
#include <shade/geometry/aabb.hpp>
#include <shade/geometry/bvh.hpp> // bounds(triangle), bounds(sphere)

namespace {

template <class T>
using v3 = shade::vec3<T>;

// The slab test of shade::intersect(ray, aabb) with the far distances multiplied by
// `enlarge` instead of 1 + 2 gamma(3): enlarge = 1 is the plain test, which rounding can
// make miss a box the ray touches.
template <class T>
bool slab_hit(const shade::ray<T>& r, const shade::aabb<T>& box, T enlarge) {
    T t0 = r.t_min, t1 = r.t_max;
    for (int k = 0; k < 3; ++k) {
        const T inv = T(1) / r.direction[k];
        const bool neg = std::signbit(r.direction[k]);
        const T tn = ((neg ? box.hi[k] : box.lo[k]) - r.origin[k]) * inv;
        const T tf = ((neg ? box.lo[k] : box.hi[k]) - r.origin[k]) * inv * enlarge;
        t0 = tn > t0 ? tn : t0;
        t1 = tf < t1 ? tf : t1;
    }
    return t0 <= t1;
}

} // namespace

TEST_CASE_TEMPLATE("aabb: empty, grow, contains, centre and surface area", T, float, double) {
    shade::aabb<T> box;
    CHECK(box.empty());
    CHECK(box.surface_area() == T(0));
    box.grow(v3<T>(1, 2, 3));
    CHECK_FALSE(box.empty());
    box.grow(v3<T>(-1, 0, 4));
    CHECK(box.lo == v3<T>(-1, 0, 3));
    CHECK(box.hi == v3<T>(1, 2, 4));
    CHECK(box.contains(v3<T>(0, 1, 3.5)));
    CHECK(box.contains(v3<T>(1, 2, 4))); // closed
    CHECK_FALSE(box.contains(v3<T>(0, 1, 4.5)));
    CHECK(box.center() == v3<T>(0, 1, 3.5));
    // Edges 2, 2, 1: 2 (2*2 + 2*1 + 1*2) = 16.
    CHECK(box.surface_area() == T(16));
    shade::aabb<T> other;
    other.grow(box);
    CHECK(other.lo == box.lo);
    CHECK(other.hi == box.hi);

    const shade::triangle<T> tri{{0, 0, 0}, {2, -1, 0}, {1, 3, -2}};
    const shade::aabb<T> tb = shade::bounds(tri);
    CHECK(tb.lo == v3<T>(0, -1, -2));
    CHECK(tb.hi == v3<T>(2, 3, 0));
    // 0.1 is not exact: the sphere's box is rounded outward, so it holds c ± r.
    const shade::sphere<T> s({T(0.1), 0, 0}, T(0.3));
    const shade::aabb<T> sb = shade::bounds(s);
    CHECK(sb.lo.x < T(0.1) - T(0.3));
    CHECK(sb.hi.x > T(0.1) + T(0.3));
}

TEST_CASE_TEMPLATE("aabb: ray/box intervals with known values", T, float, double) {
    shade::aabb<T> box{{0, 0, 0}, {1, 2, 4}};
    // Along +x from x = -1 at y = 1, z = 1: enters at t = 1 (x = 0), leaves at t = 2 (x = 1).
    auto h = shade::intersect(shade::ray<T>{{-1, 1, 1}, {1, 0, 0}}, box);
    REQUIRE(h);
    CHECK(h->t_enter == T(1));
    CHECK(h->t_exit >= T(2));
    CHECK(h->t_exit <= T(2) * (T(1) + T(8) * std::numeric_limits<T>::epsilon()));
    // From inside: enters at t_min.
    h = shade::intersect(shade::ray<T>{{0.5, 1, 1}, {0, 0, -1}, T(0.25)}, box);
    REQUIRE(h);
    CHECK(h->t_enter == T(0.25));
    // Box behind the ray, beside it, beyond t_max; an empty box; an invalid ray.
    CHECK_FALSE(shade::intersect(shade::ray<T>{{2, 1, 1}, {1, 0, 0}}, box));
    CHECK_FALSE(shade::intersect(shade::ray<T>{{-1, 3, 1}, {1, 0, 0}}, box));
    CHECK_FALSE(shade::intersect(shade::ray<T>{{-1, 1, 1}, {1, 0, 0}, 0, T(0.5)}, box));
    CHECK_FALSE(shade::intersect(shade::ray<T>{{-1, 1, 1}, {1, 0, 0}}, shade::aabb<T>{}));
    CHECK_FALSE(shade::intersect(shade::ray<T>{{-1, 1, 1}, {0, 0, 0}}, box));
    // A ray along a face of the box (direction component 0, origin exactly on the plane
    // y = 2, where (2 - 2) * inf is NaN): the closed box holds it, so it is entered.
    h = shade::intersect(shade::ray<T>{{-1, 2, 1}, {1, 0, 0}}, box);
    REQUIRE(h);
    CHECK(h->t_enter == T(1));
    h = shade::intersect(shade::ray<T>{{-1, 2, 1}, {1, -0.0, 0}}, box); // -0 too
    REQUIRE(h);
    CHECK_FALSE(shade::intersect(shade::ray<T>{{-1, 2.5, 1}, {1, 0, 0}}, box));
}

// Rays through a corner of a box, exactly: the coordinates are dyadic numbers with few
// bits, so corner = o + t d holds exactly and the exact ray touches the box at that one
// point. The robust test must report every one; the plain slab test (enlarge = 1) misses
// some of them, which shows the enlargement is needed and that this test would catch its
// removal.
TEST_CASE_TEMPLATE("aabb: rays through a box corner are never missed (Ize 2013)", T, float, double) {
    shade::rng g(7);
    int plain_misses = 0;
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
        // Corner with coordinates k / 2^c in [-4, 4], direction components j / 2^e with
        // j in [1, 2^e) and a random sign, t = m / 2^8 with m in [1, M]: t d has few
        // enough bits that o = corner - t d is exact in T (c = 6, e = 3, M = 2^6 for
        // float; c = 30, e = 12, M = 2^12 for double, where the float sizes happened
        // never to round the two distances apart).
        constexpr bool is_float = sizeof(T) == 4;
        const double c_scale = is_float ? 64.0 : 1073741824.0;
        const double e_scale = is_float ? 8.0 : 4096.0;
        const double m_count = is_float ? 64.0 : 4096.0;
        v3<T> corner, d;
        for (int k = 0; k < 3; ++k) {
            corner[k] = T((std::floor(g.uniform<double>() * 8 * c_scale) - 4 * c_scale) / c_scale);
            T dk = T((std::floor(g.uniform<double>() * (e_scale - 1)) + 1) / e_scale);
            if (g.uniform<double>() < 0.5) dk = -dk;
            d[k] = dk;
        }
        const T t = T((std::floor(g.uniform<double>() * m_count) + 1) / 256.0);
        const v3<T> o = corner - t * d;
        // On axis 0 the ray enters the box's slab exactly at the corner, on axis 1 it
        // leaves its slab there, on axis 2 either: so the ray is inside all three slabs
        // at t and at no other t, and the test compares two roundings of t.
        shade::aabb<T> box;
        for (int k = 0; k < 3; ++k) {
            const bool enters = k == 0 || (k == 2 && g.uniform<double>() < 0.5);
            // Entering (the slab ahead along d) or leaving (the slab behind).
            const bool above = enters == (d[k] > 0);
            box.lo[k] = above ? corner[k] : corner[k] - T(1);
            box.hi[k] = above ? corner[k] + T(1) : corner[k];
        }
        const shade::ray<T> r{o, d};
        CHECK(shade::intersect(r, box).has_value());
        if (!slab_hit(r, box, T(1))) ++plain_misses;
    }
    MESSAGE("plain slab test missed " << plain_misses << " of " << n << " corner rays");
    CHECK(plain_misses > 0);
}
