#include <array>
#include <cmath>
#include <limits>
#include <type_traits>
#include <vector>

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/geometry/sphere.hpp>

#include "geometry/special_rays.hpp"

namespace {

template <class T>
using v3 = shade::vec3<T>;

template <class T>
constexpr T eps = std::numeric_limits<T>::epsilon();

template <class T>
bool near_rel(T a, T b, T rel) {
    return std::abs(a - b) <= rel * std::max(std::abs(a), std::abs(b));
}

template <class T>
bool near_vec(const v3<T>& a, const v3<T>& b, T tol) {
    return std::abs(a.x - b.x) <= tol && std::abs(a.y - b.y) <= tol && std::abs(a.z - b.z) <= tol;
}

} // namespace

TEST_CASE_TEMPLATE("sphere: known entering hits, centred and off-centre", T, float, double) {
    const shade::sphere<T> s({0, 0, -5}, 2);
    const T tol = 8 * eps<T>;
    // Centred: from the origin along -z the ray enters at z = -5 + 2 = -3: t = 3,
    // p = (0,0,-3), outward normal (0,0,1), front face.
    const auto h = shade::intersect(shade::ray<T>{{0, 0, 0}, {0, 0, -1}}, s);
    REQUIRE(h.has_value());
    CHECK(near_rel(h->t, T(3), tol));
    CHECK(near_vec(h->p, v3<T>(0, 0, -3), tol * 3));
    CHECK(near_vec(h->n, v3<T>(0, 0, 1), tol));
    CHECK(h->front_face);
    // Off-centre: from (1,0,0) along -z the ray passes the centre at distance 1; it enters
    // sqrt(2^2 - 1^2) = sqrt(3) before z = -5: t = 5 - sqrt(3), p = (1, 0, -5 + sqrt(3)),
    // n = (p - c) / 2 = (1, 0, sqrt(3)) / 2.
    const auto g = shade::intersect(shade::ray<T>{{1, 0, 0}, {0, 0, -1}}, s);
    REQUIRE(g.has_value());
    const T r3 = std::sqrt(T(3));
    CHECK(near_rel(g->t, T(5) - r3, tol));
    CHECK(near_vec(g->p, v3<T>(1, 0, T(-5) + r3), tol * 5));
    CHECK(near_vec(g->n, v3<T>(1, 0, r3) / T(2), tol * 5));
    CHECK(std::abs(glm::length(g->n) - T(1)) <= tol);
    CHECK(g->front_face);
}

TEST_CASE_TEMPLATE("sphere: an origin inside gives the exit hit", T, float, double) {
    const shade::sphere<T> s({0, 0, -5}, 2);
    const T tol = 8 * eps<T>;
    // From the centre along +x: exit at (2, 0, -5), t = 2, outward normal (1,0,0); the ray
    // strikes the inside (back) of the surface.
    const auto h = shade::intersect(shade::ray<T>{{0, 0, -5}, {1, 0, 0}}, s);
    REQUIRE(h.has_value());
    CHECK(near_rel(h->t, T(2), tol));
    CHECK(near_vec(h->p, v3<T>(2, 0, -5), tol * 5));
    CHECK(near_vec(h->n, v3<T>(1, 0, 0), tol));
    CHECK_FALSE(h->front_face);
    CHECK(near_vec(h->facing_normal(), v3<T>(-1, 0, 0), tol));
    // From (0,1,-5) along +x: x^2 + 1 = 4 at x = sqrt(3): t = sqrt(3), n = (sqrt(3), 1, 0)/2.
    const auto g = shade::intersect(shade::ray<T>{{0, 1, -5}, {1, 0, 0}}, s);
    REQUIRE(g.has_value());
    const T r3 = std::sqrt(T(3));
    CHECK(near_rel(g->t, r3, tol));
    CHECK(near_vec(g->n, v3<T>(r3, 1, 0) / T(2), tol * 2));
    CHECK_FALSE(g->front_face);
}

TEST_CASE_TEMPLATE("sphere: t is in units of the direction, for tiny and huge directions too", T, float, double) {
    // The centred hit of the first test is 3 length units away, so with direction
    // (0,0,-len) t = 3 / len. a = d·d would underflow (len = 1e-30: 1e-60) or overflow
    // (len = 1e30: 1e60) in float without the exact power-of-two rescaling.
    const shade::sphere<T> s({0, 0, -5}, 2);
    for (const T len : {T(4), T(0.25), T(1e-30), T(1e30)}) {
        CAPTURE(len);
        const auto h = shade::intersect(shade::ray<T>{{0, 0, 0}, {0, 0, -len}}, s);
        REQUIRE(h.has_value());
        CHECK(near_rel(h->t * len, T(3), 8 * eps<T>));
        CHECK(near_vec(h->p, v3<T>(0, 0, -3), 32 * eps<T>));
    }
}

TEST_CASE_TEMPLATE("sphere: a subnormal direction still hits (regression, found by fuzzing)", T, float, double) {
    // The rescaling factor 2^-e for a subnormal largest component is not representable
    // (float: denorm_min = 2^-149 needs 2^149), so it must be applied as an exponent.
    // Unit sphere at the origin, origin 1/1024 outside it on -z: the ray along +z with
    // direction length len enters at distance 1/1024, so t = 2^-10 / len. With
    // len = 2^-130 (float) or 2^-1030 (double), both subnormal, t = 2^120 or 2^1020,
    // finite in each type (the largest are just below 2^128 and 2^1024); the old factor
    // 2^129 or 2^1029 was infinite.
    const T len = std::is_same_v<T, float> ? std::ldexp(T(1), -130) : std::ldexp(T(1), -1030);
    REQUIRE(len < std::numeric_limits<T>::min()); // subnormal
    REQUIRE(len > T(0));
    const shade::sphere<T> s({0, 0, 0}, 1);
    const T start = T(1) + std::ldexp(T(1), -10);
    const auto h = shade::intersect(shade::ray<T>{{0, 0, -start}, {0, 0, len}}, s);
    REQUIRE(h.has_value());
    CHECK(h->front_face);
    CHECK(near_rel(h->t, std::ldexp(T(1), -10) / len, 8 * eps<T>));
    CHECK(near_vec(h->p, v3<T>(0, 0, -1), 8 * eps<T>));
}

TEST_CASE_TEMPLATE("sphere: a subnormal radius still gives the unit normal", T, float, double) {
    // The normal is normalised as (p - c) 2^k with R 2^k in [0.5, 1); for a subnormal R
    // that 2^k is not a T (float: R = 2^-129 needs 2^128), and the general
    // normalize_or_zero must take over. Sphere of radius R = min / 8 at the origin, ray
    // from (0, 0, -4R) along +z. Every square here underflows to 0, so the quadratic sees
    // a tangent ray: c_0 = |f|^2 - R^2 = 0 makes one root 0, and t = 0 puts p at the
    // origin (0, 0, -4R), on the -z axis like the true hit at t = 3R: the outward normal
    // is exactly (0, 0, -1) either way (p - c has only a z component).
    const T radius = std::numeric_limits<T>::min() / 8;
    REQUIRE(radius > T(0));
    const shade::sphere<T> s({0, 0, 0}, radius);
    const auto h = shade::intersect(shade::ray<T>{{0, 0, -4 * radius}, {0, 0, 1}}, s);
    REQUIRE(h.has_value());
    CHECK(h->front_face);
    CHECK(h->n == v3<T>(0, 0, -1));
    CHECK(shade::is_finite(h->p));
}

TEST_CASE_TEMPLATE("sphere: a radius whose square overflows is hit like a unit sphere", T, float, double) {
    // R = 1e20 in float (R^2 = 1e40 > FLT_MAX = 3.4e38) and R = 1e160 in double (R^2 =
    // 1e320 > DBL_MAX = 1.8e308). The sphere is the unit sphere scaled by R: the ray from
    // (0, 0, -3R) along +z enters at t = 2R (point (0, 0, -R), normal (0, 0, -1)), and the
    // ray from the centre leaves at t = R (point (0, 0, R), normal (0, 0, 1)).
    const T radius = std::is_same_v<T, float> ? T(1e20) : T(1e160);
    REQUIRE(std::isinf(radius * radius));
    const shade::sphere<T> s({0, 0, 0}, radius);
    const auto enter = shade::intersect(shade::ray<T>{{0, 0, -3 * radius}, {0, 0, 1}}, s);
    REQUIRE(enter.has_value());
    CHECK(enter->front_face);
    CHECK(near_rel(enter->t, 2 * radius, 4 * eps<T>));
    CHECK(near_vec(enter->p / radius, v3<T>(0, 0, -1), 4 * eps<T>));
    CHECK(near_vec(enter->n, v3<T>(0, 0, -1), 4 * eps<T>));
    const auto leave = shade::intersect(shade::ray<T>{{0, 0, 0}, {0, 0, 1}}, s);
    REQUIRE(leave.has_value());
    CHECK_FALSE(leave->front_face);
    CHECK(near_rel(leave->t, radius, 4 * eps<T>));
    CHECK(near_vec(leave->n, v3<T>(0, 0, 1), 4 * eps<T>));
    // Off-centre and oblique: centre (R, 2R, -R), ray from the centre + (0, 0, -4R) toward
    // the point centre + R (0.6, 0, -0.8): direction R (0.6, 0, 3.2), which reaches the
    // sphere at t = 1 (|(0.6, 0, -0.8)| = 1), the entering root.
    const v3<T> c(radius, 2 * radius, -radius);
    const shade::sphere<T> off(c, radius);
    const v3<T> o = c + v3<T>(0, 0, -4 * radius);
    const auto oblique = shade::intersect(shade::ray<T>{o, radius * v3<T>(T(0.6), 0, T(3.2))}, off);
    REQUIRE(oblique.has_value());
    CHECK(near_rel(oblique->t, T(1), 16 * eps<T>));
    CHECK(near_vec(oblique->n, v3<T>(T(0.6), 0, T(-0.8)), 16 * eps<T>));
}

TEST_CASE_TEMPLATE("sphere: tangent ray touches once; a hair outside misses", T, float, double) {
    // Centre (0,0,-5), radius 2. The ray from (-5, 2, -5) along +x passes the centre at
    // distance exactly 2: f = o - c = (-5,2,0), l = f - (f·d/d·d) d = (0,2,0), so the
    // discriminant R^2 - |l|^2 = 4 - 4 = 0 exactly. Single root t = 5 at p = (0,2,-5),
    // n = (0,1,0); reported as an entering (front-face) hit.
    const shade::sphere<T> s({0, 0, -5}, 2);
    const auto h = shade::intersect(shade::ray<T>{{-5, 2, -5}, {1, 0, 0}}, s);
    REQUIRE(h.has_value());
    CHECK(h->t == T(5));
    CHECK(h->p == v3<T>(0, 2, -5));
    CHECK(h->n == v3<T>(0, 1, 0));
    CHECK(h->front_face);
    // One ulp farther out: |l| > R, no hit. One ulp inside: a (short) chord, entered
    // before x = 0.
    const T out = std::nextafter(T(2), T(3));
    const T in = std::nextafter(T(2), T(0));
    CHECK_FALSE(shade::intersect(shade::ray<T>{{-5, out, -5}, {1, 0, 0}}, s).has_value());
    const auto g = shade::intersect(shade::ray<T>{{-5, in, -5}, {1, 0, 0}}, s);
    REQUIRE(g.has_value());
    CHECK(g->t < T(5));
    CHECK(g->front_face);
}

TEST_CASE_TEMPLATE("sphere: far away, t stays accurate (no catastrophic cancellation)", T, float, double) {
    // Axis-aligned: unit sphere at (0,0,D), ray from (h,0,0) along +z with h = 0.6. The ray
    // passes the centre at distance h, so it enters sqrt(1 - h^2) = 0.8 before z = D:
    // t = D - 0.8. The textbook discriminant b^2 - a c subtracts two numbers ~D^2 = 1e12
    // whose float spacing is 65536, to get 0.64: all digits lost. Tolerance: a few
    // roundings of t (relative).
    std::vector<T> distances{T(1e6)};
    if constexpr (std::is_same_v<T, double>) distances.push_back(T(1e12));
    const T h = T(0.6);
    for (const T D : distances) {
        CAPTURE(D);
        const auto hit = shade::intersect(shade::ray<T>{{h, 0, 0}, {0, 0, 1}},
                                          shade::sphere<T>({0, 0, D}, 1));
        REQUIRE(hit.has_value());
        CHECK(near_rel(hit->t, D - std::sqrt(1 - h * h), 4 * eps<T>));
        CHECK(hit->front_face);
        // The normal points back toward the ray: (h, 0, -0.8). The hit point, like t, is
        // only known to about one spacing of the numbers near D (eps D absolute), so
        // n = (p - c) / R carries an error of that size (R = 1).
        CHECK(near_vec(hit->n, v3<T>(h, 0, -std::sqrt(1 - h * h)), 4 * eps<T> * D));
    }
    // Oblique: direction d = (1,2,2) (|d| = 3), centre c = k d + p with p = (0.5,-0.5,0.25)
    // orthogonal to d (p·d = 0.5 - 1 + 0.5 = 0) and |p| = 0.75; k = 2^18 in float (the
    // sphere is ~8e5 away) and 2^40 in double (~3e12 away). Every coordinate is exact in
    // binary. The ray passes the centre at distance 0.75 at t = k, and enters
    // sqrt(1 - 0.5625) = sqrt(0.4375) length units earlier, i.e. sqrt(0.4375)/3 in t:
    // t = k - sqrt(0.4375) / 3.
    const T k = std::is_same_v<T, float> ? T(262144) : T(1099511627776.0);
    const v3<T> d(1, 2, 2);
    const v3<T> c = k * d + v3<T>(T(0.5), T(-0.5), T(0.25));
    REQUIRE(c.z - T(2) * k == T(0.25)); // c is exact
    const auto hit = shade::intersect(shade::ray<T>{{0, 0, 0}, d}, shade::sphere<T>(c, 1));
    REQUIRE(hit.has_value());
    CHECK(near_rel(hit->t, k - std::sqrt(T(0.4375)) / T(3), 8 * eps<T>));
    CHECK(hit->front_face);
}

TEST_CASE_TEMPLATE("sphere: bad input never produces a hit", T, float, double) {
    const T nan = std::numeric_limits<T>::quiet_NaN();
    const T inf = std::numeric_limits<T>::infinity();
    const shade::sphere<T> s({0, 0, -5}, 2);
    const v3<T> o(0, 0, 0), d(0, 0, -1); // enters at t = 3, leaves at t = 7
    REQUIRE(shade::intersect(shade::ray<T>{o, d}, s).has_value());
    auto miss = [&](const shade::ray<T>& r) { return !shade::intersect(r, s).has_value(); };
    CHECK(miss({o, {0, nan, -1}}));
    CHECK(miss({o, {0, 0, 0}}));
    CHECK(miss({{inf, 0, 0}, d}));
    CHECK(miss({{0, 0, nan}, d}));
    CHECK(miss({o, {0, 0, 1}}));          // sphere behind the origin
    CHECK(miss({o, {0, 1, 0}}));          // passes beside it
    CHECK(miss({o, d, 0, T(2.5)}));       // entry beyond t_max
    CHECK(miss({o, d, 8, inf}));          // both roots before t_min
    CHECK(miss({o, d, T(-1), inf}));      // invalid interval
    CHECK(miss({o, d, 0, nan}));
    CHECK(miss({o, d, T(5), T(4)}));      // t_max < t_min
    CHECK(miss({o, d, inf, inf}));
    // Infinite directions, along the axis to the centre and across it, and an infinite
    // origin where the direction is zero or not.
    CHECK(miss({o, {0, 0, -inf}}));
    CHECK(miss({o, {inf, 0, -1}}));
    CHECK(miss({o, {-inf, inf, -inf}}));
    CHECK(miss({{0, inf, 0}, d}));
    CHECK(miss({{0, 0, -inf}, d}));
    CHECK(miss({{0, 0, 5}, {0, 0, -nan}}));
    // With t_min between the roots the exit is reported: t = 7, p = (0,0,-7), n = (0,0,-1).
    const auto exit = shade::intersect(shade::ray<T>{o, d, 4, inf}, s);
    REQUIRE(exit.has_value());
    CHECK(near_rel(exit->t, T(7), 8 * eps<T>));
    CHECK(near_vec(exit->n, v3<T>(0, 0, -1), 8 * eps<T>));
    CHECK_FALSE(exit->front_face);
    // A centre so far that o - c overflows gives no hit rather than NaN.
    const T big = std::numeric_limits<T>::max();
    CHECK_FALSE(shade::intersect(shade::ray<T>{{0, 0, -big}, {0, 0, 1}},
                                 shade::sphere<T>({0, 0, big}, 1))
                    .has_value());
}

TEST_CASE_TEMPLATE("sphere: scaled by 1e-3 or 1e3, or translated by 1e4, gives the same hits", T, float, double) {
    // Centre and origins are multiples of 1/8 (translation by 1e4 stays exact in float).
    // Rays aim at points clearly inside the silhouette (hits) or clearly beside it
    // (misses). Scaling points by s (directions kept) scales t by s; 32 eps: a few
    // roundings of the scaled inputs, no near-tangent ray.
    const v3<T> c(T(0.5), T(-0.25), 3);
    const T radius = T(1.5);
    const std::vector<v3<T>> origins{{0, 0, 0}, {4, 1, T(-2.5)}, {T(0.75), T(-0.5), T(3.25)}};
    const std::vector<v3<T>> targets{c, c + v3<T>(T(0.5), T(0.25), 0), c + v3<T>(3, 0, 0),
                                     c + v3<T>(0, T(-2.5), 1)};
    const shade::sphere<T> s(c, radius);
    int hits = 0;
    for (const auto& o : origins)
        for (const auto& target : targets) {
            const shade::ray<T> r{o, target - o};
            const auto h = shade::intersect(r, s);
            for (const T scale : {T(1e-3), T(1e3)}) {
                const auto g = shade::intersect(shade::ray<T>{o * scale, r.direction},
                                                shade::sphere<T>(c * scale, radius * scale));
                REQUIRE(g.has_value() == h.has_value());
                if (h) {
                    CHECK(near_rel(g->t, h->t * scale, 32 * eps<T>));
                    CHECK(g->front_face == h->front_face);
                }
            }
            const v3<T> shift(T(1e4), T(-1e4), T(1e4));
            const auto g = shade::intersect(shade::ray<T>{o + shift, r.direction},
                                            shade::sphere<T>(c + shift, radius));
            REQUIRE(g.has_value() == h.has_value());
            if (h) {
                ++hits;
                CHECK(near_rel(g->t, h->t, 32 * eps<T>));
            }
        }
    CHECK(hits >= 6);
}

TEST_CASE_TEMPLATE("sphere: constructor rejects bad parameters by name", T, float, double) {
    const T nan = std::numeric_limits<T>::quiet_NaN();
    const T inf = std::numeric_limits<T>::infinity();
    for (const T bad : {T(0), T(-1), nan, inf})
        CHECK_THROWS_WITH_AS((void)shade::sphere<T>({0, 0, 0}, bad), doctest::Contains("'radius'"),
                             shade::invalid_parameter);
    CHECK_THROWS_WITH_AS((void)shade::sphere<T>({0, inf, 0}, 1), doctest::Contains("'center'"),
                         shade::invalid_parameter);
}

TEST_CASE_TEMPLATE("sphere: no ray that is not valid() hits, over a sweep of special values", T, float, double) {
    // intersect tests only t_min >= 0 of the ray and relies on a non-finite or zero origin
    // or direction turning its arithmetic into NaN or infinity (see the comment in
    // include/shade/geometry/sphere.hpp); geometry/special_rays.hpp checks that.
    using std::array;
    // Ahead of the unmodified ray (centre at t = 3), around its origin, and far and large.
    const array<shade::sphere<T>, 3> shapes{shade::sphere<T>({T(0.2), T(-0.35), T(-0.775)}, 1),
                                            shade::sphere<T>({0, 0, 0}, 2),
                                            shade::sphere<T>({-10, -20, -30}, 15)};
    geometry_test::check_special_rays<T>(shapes);
}
