#include <array>
#include <cmath>
#include <limits>

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/geometry/plane.hpp>

#include "geometry/special_rays.hpp"

namespace {

template <class T>
using v3 = shade::vec3<T>;

template <class T>
constexpr T eps = std::numeric_limits<T>::epsilon();

template <class T>
bool near_vec(const v3<T>& a, const v3<T>& b, T tol) {
    return std::abs(a.x - b.x) <= tol && std::abs(a.y - b.y) <= tol && std::abs(a.z - b.z) <= tol;
}

} // namespace

TEST_CASE_TEMPLATE("plane: known hits from the front and from the back", T, float, double) {
    // Plane z = -2 with normal +z (given as (0,0,5): normalised to (0,0,1)).
    const shade::plane<T> pl({7, -3, -2}, {0, 0, 5});
    CHECK(pl.normal() == v3<T>(0, 0, 1));
    // From (1,1,3) along (0,0,-1): t = n·(q - o) / n·d = (-2 - 3) / (-1) = 5,
    // p = (1,1,-2); n·d < 0: front face. All exact.
    const auto h = shade::intersect(shade::ray<T>{{1, 1, 3}, {0, 0, -1}}, pl);
    REQUIRE(h.has_value());
    CHECK(h->t == T(5));
    CHECK(h->p == v3<T>(1, 1, -2));
    CHECK(h->n == v3<T>(0, 0, 1));
    CHECK(h->front_face);
    // From (1,1,-5) along (0,0,2): t = (-2 + 5) / 2 = 1.5, p = (1,1,-2); back face.
    const shade::ray<T> below{{1, 1, -5}, {0, 0, 2}};
    const auto g = shade::intersect(below, pl);
    REQUIRE(g.has_value());
    CHECK(g->t == T(1.5));
    CHECK(g->p == v3<T>(1, 1, -2));
    CHECK(g->n == v3<T>(0, 0, 1));
    CHECK_FALSE(g->front_face);
    CHECK(g->facing_normal() == v3<T>(0, 0, -1));
    CHECK_FALSE(shade::intersect(below, pl, shade::culling::back_faces).has_value());
    CHECK(shade::intersect(shade::ray<T>{{1, 1, 3}, {0, 0, -1}}, pl, shade::culling::back_faces));
}

TEST_CASE_TEMPLATE("plane: oblique hit", T, float, double) {
    // Plane x + y = 1: point (1,0,0), normal (1,1,0)/sqrt(2). Ray from the origin along
    // (1,2,0): n·(q - o) = 1/sqrt(2), n·d = 3/sqrt(2), so t = 1/3 and p = (1/3, 2/3, 0);
    // n·d > 0: the ray hits the back (the origin is on the side n points away from).
    const shade::plane<T> pl({1, 0, 0}, {1, 1, 0});
    const auto h = shade::intersect(shade::ray<T>{{0, 0, 0}, {1, 2, 0}}, pl);
    REQUIRE(h.has_value());
    const T tol = 8 * eps<T>;
    CHECK(std::abs(h->t - T(1) / T(3)) <= tol);
    CHECK(near_vec(h->p, v3<T>(T(1) / T(3), T(2) / T(3), 0), tol));
    CHECK(near_vec(h->n, v3<T>(1, 1, 0) / std::sqrt(T(2)), tol));
    CHECK_FALSE(h->front_face);
}

TEST_CASE_TEMPLATE("plane: t is measured in units of the direction", T, float, double) {
    // Plane z = 0, origin at height 8: with direction (0,0,-d) the hit is at t = 8/d.
    const shade::plane<T> pl({0, 0, 0}, {0, 0, 1});
    for (const T d : {T(0.25), T(1), T(4), T(1e-20), T(1e20)}) {
        CAPTURE(d);
        const auto h = shade::intersect(shade::ray<T>{{0, 0, 8}, {0, 0, -d}}, pl);
        REQUIRE(h.has_value());
        CHECK(std::abs(h->t * d - T(8)) <= 8 * T(8) * eps<T>);
        CHECK(std::abs(h->p.z) <= 8 * T(8) * eps<T>);
    }
}

TEST_CASE_TEMPLATE("plane: bad input never produces a hit", T, float, double) {
    const T nan = std::numeric_limits<T>::quiet_NaN();
    const T inf = std::numeric_limits<T>::infinity();
    const shade::plane<T> pl({0, 0, 0}, {0, 0, 1});
    const v3<T> o(1, 1, 3), d(0, 0, -1); // hits at t = 3
    REQUIRE(shade::intersect(shade::ray<T>{o, d}, pl).has_value());
    auto miss = [&](const shade::ray<T>& r) { return !shade::intersect(r, pl).has_value(); };
    CHECK(miss({o, {nan, 0, -1}}));
    CHECK(miss({o, {0, 0, 0}}));
    CHECK(miss({{inf, 1, 3}, d}));
    CHECK(miss({{1, nan, 3}, d}));
    CHECK(miss({o, {1, 0, 0}}));           // parallel, above the plane
    CHECK(miss({{1, 1, 0}, {1, 1, 0}}));   // parallel, lying in the plane
    CHECK(miss({o, {0, 0, 1}}));           // plane behind the origin
    CHECK(miss({o, d, 0, T(2.5)}));        // hit beyond t_max
    CHECK(miss({o, d, T(3.5), inf}));      // hit before t_min
    CHECK(miss({o, d, T(-1), inf}));       // t_min < 0: invalid ray
    CHECK(miss({o, d, nan, inf}));
    CHECK(miss({o, d, T(4), T(2)}));       // t_max < t_min
    CHECK(miss({o, d, inf, inf}));
    CHECK(miss({o, d, 0, nan}));
    // A direction with an infinite component: n·d = -inf gives t = -3 / -inf = +0, and
    // the point o + 0 d is NaN; an infinity across the normal makes n·d NaN.
    CHECK(miss({o, {0, 0, -inf}}));
    CHECK(miss({o, {inf, 0, -1}}));
    CHECK(miss({{1, 1, inf}, {0, 0, -inf}}));
    CHECK_FALSE(miss({o, d, 3, 3}));       // closed interval keeps t = 3
    // Nearly parallel rays are not rejected by an epsilon: direction (1, 0, -1e-30) from
    // height 3 meets the plane at t = 3e30 (finite in float: max 3.4e38).
    const auto far = shade::intersect(shade::ray<T>{o, {1, 0, T(-1e-30)}}, pl);
    REQUIRE(far.has_value());
    CHECK(std::abs(far->t - T(3e30)) <= 8 * T(3e30) * eps<T>);
    // ...but a hit whose t or point overflows to infinity is not a hit.
    CHECK(miss({{0, 0, std::numeric_limits<T>::max()}, {1, 0, -std::numeric_limits<T>::min()}}));
}

TEST_CASE_TEMPLATE("plane: scaled by 1e-3 or 1e3, or translated by 1e4, gives the same hit", T, float, double) {
    // Plane through (0.5, 0.25, -1) with normal (1, 2, 4); ray from (1, -2, 3) along
    // (-0.5, 0.75, -1). Scaling points by s (directions kept) scales t by s; translating
    // changes nothing. 32 eps: a few roundings of the inputs times a condition number
    // |n||d|/|n·d| = sqrt(21) sqrt(1.8125) / 3 ≈ 2.06 for this ray.
    const v3<T> q(T(0.5), T(0.25), -1), n(1, 2, 4), o(1, -2, 3), d(T(-0.5), T(0.75), -1);
    const auto h = shade::intersect(shade::ray<T>{o, d}, shade::plane<T>(q, n));
    REQUIRE(h.has_value());
    for (const T s : {T(1e-3), T(1e3)}) {
        const auto g = shade::intersect(shade::ray<T>{o * s, d}, shade::plane<T>(q * s, n));
        REQUIRE(g.has_value());
        CHECK(std::abs(g->t - h->t * s) <= 32 * eps<T> * h->t * s);
        CHECK(g->front_face == h->front_face);
    }
    const v3<T> shift(T(1e4), T(-1e4), T(1e4));
    const auto g = shade::intersect(shade::ray<T>{o + shift, d}, shade::plane<T>(q + shift, n));
    REQUIRE(g.has_value());
    CHECK(std::abs(g->t - h->t) <= 32 * eps<T> * h->t);
}

TEST_CASE_TEMPLATE("plane: constructor rejects bad parameters by name", T, float, double) {
    const T nan = std::numeric_limits<T>::quiet_NaN();
    CHECK_THROWS_WITH_AS((void)shade::plane<T>({0, 0, 0}, {0, 0, 0}), doctest::Contains("'normal'"),
                         shade::invalid_parameter);
    CHECK_THROWS_WITH_AS((void)shade::plane<T>({0, 0, 0}, {nan, 0, 1}), doctest::Contains("'normal'"),
                         shade::invalid_parameter);
    CHECK_THROWS_WITH_AS((void)shade::plane<T>({0, nan, 0}, {0, 0, 1}), doctest::Contains("'point'"),
                         shade::invalid_parameter);
}

TEST_CASE_TEMPLATE("plane: no ray that is not valid() hits, over a sweep of special values", T, float, double) {
    // intersect tests only t_min >= 0 of the ray and relies on a non-finite or zero origin
    // or direction turning its arithmetic into NaN or infinity (see the comment in
    // include/shade/geometry/plane.hpp); geometry/special_rays.hpp checks that.
    using std::array;
    // Across the unmodified ray's path, one per axis and one oblique.
    const array<shade::plane<T>, 4> shapes{shade::plane<T>({0, 0, -1}, {0, 0, 1}),
                                           shade::plane<T>({-1, 0, 0}, {1, 0, 0}),
                                           shade::plane<T>({0, -1, 0}, {0, 1, 0}),
                                           shade::plane<T>({0, 0, 0}, {1, 2, 3})};
    geometry_test::check_special_rays<T>(shapes);
}
