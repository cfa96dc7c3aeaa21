#include <cmath>
#include <cstdint>
#include <limits>

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/light/area.hpp>

namespace {

// The square [-a, a]^2 at height h, emitting downward: edges (0, 2a, 0) then (2a, 0, 0)
// make cross(edge_u, edge_v) = (0, 0, -4a^2), so the normal is -z.
template <class T>
shade::area_light<T> square_above(T a, T h, const shade::emission<T>& e = {},
                                  shade::sidedness sides = shade::sidedness::one_sided) {
    return shade::area_light<T>(shade::vec3<T>(-a, -a, h), shade::vec3<T>(0, 2 * a, 0),
                                shade::vec3<T>(2 * a, 0, 0), e, sides);
}

// A small deterministic generator for jitter (64-bit LCG, Knuth's MMIX constants), so the
// test is reproducible.
struct lcg {
    std::uint64_t state = 12345;
    double next() {
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        return double(state >> 11) * (1.0 / 9007199254740992.0); // [0, 1)
    }
};

} // namespace

TEST_CASE_TEMPLATE("area_light geometry: normal, area, points", T, float, double) {
    using v = shade::vec3<T>;
    const auto light = square_above(T(1), T(1));
    CHECK(light.normal() == v(0, 0, -1));
    CHECK(light.area() == doctest::Approx(4.0).epsilon(1e-6));
    CHECK(light.point_at(shade::vec2<T>(T(0.5))) == v(0, 0, 1));
    CHECK(light.point_at(shade::vec2<T>(1, 0)) == v(-1, 1, 1));
    CHECK(!light.is_delta());
    // A non-rectangular parallelogram: edges (2,0,0), (1,3,0): area |cross| = 6.
    const shade::area_light<T> slanted(v(0), v(2, 0, 0), v(1, 3, 0));
    CHECK(slanted.area() == doctest::Approx(6.0).epsilon(1e-6));
    CHECK(slanted.normal() == v(0, 0, 1));
}

TEST_CASE_TEMPLATE("area_light sample: direction, distance and the cos A / r^2 weight", T, float, double) {
    using v = shade::vec3<T>;
    shade::emission<T> e;
    e.intensity = T(0.5);
    e.ambient = shade::rgb<T>(T(0.25));
    const auto light = square_above(T(1), T(2), e);
    // u = (1/2, 1/2) is the centre (0, 0, 2), straight above the origin: l = +z, r = 2,
    // cos_light = 1, A = 4: weight 0.5 x 1 x 4 / 4 = 0.5.
    const auto centre = light.sample(v(0), shade::vec2<T>(T(0.5)));
    CHECK(centre.l == v(0, 0, 1));
    CHECK(centre.distance == T(2));
    CHECK(centre.diffuse == shade::rgb<T>(T(0.5)));
    CHECK(centre.specular == shade::rgb<T>(T(0.5)));
    CHECK(centre.ambient == shade::rgb<T>(T(0.125)));
    // u = (0, 0) is the corner (-1, -1, 2): r = sqrt(1 + 1 + 4) = sqrt(6),
    // l = (-1, -1, 2)/sqrt(6), cos_light = 2/sqrt(6): weight 0.5 x (2/sqrt(6)) x 4 / 6
    // = 2 / (3 sqrt(6)).
    const auto corner = light.sample(v(0), shade::vec2<T>(0));
    CHECK(corner.distance == doctest::Approx(std::sqrt(6.0)).epsilon(1e-6));
    CHECK(corner.l.x == doctest::Approx(-1.0 / std::sqrt(6.0)).epsilon(1e-6));
    CHECK(corner.l.z == doctest::Approx(2.0 / std::sqrt(6.0)).epsilon(1e-6));
    CHECK(corner.diffuse.x == doctest::Approx(2.0 / (3.0 * std::sqrt(6.0))).epsilon(1e-6));
}

TEST_CASE_TEMPLATE("area_light: one-sided lights are dark behind, two-sided are not", T, float, double) {
    using v = shade::vec3<T>;
    const auto one = square_above(T(1), T(1));
    const auto two = square_above(T(1), T(1), {}, shade::sidedness::two_sided);
    const v above(0, 0, 3); // behind the downward-facing emitter, 2 above its centre
    const auto behind = one.sample(above, shade::vec2<T>(T(0.5)));
    CHECK(behind.diffuse == shade::rgb<T>(0));
    CHECK(behind.l == v(0, 0, -1)); // the direction is still reported
    CHECK(behind.distance == T(2));
    // Two-sided: |cos| = 1, r = 2: weight 4 / 4 = 1.
    const auto s = two.sample(above, shade::vec2<T>(T(0.5)));
    CHECK(s.diffuse == shade::rgb<T>(1));
    CHECK(s.l == v(0, 0, -1));
}

TEST_CASE_TEMPLATE("area_light: a small far rectangle averages to the equivalent point light", T, float, double) {
    using v = shade::vec3<T>;
    // Square of side 0.01 (A = 1e-4) centred at (0, 0, 10), facing down, intensity 1.
    // Seen from p = (3, 0, 0): r^2 = 9 + 100 = 109 and cos_light = 10 / sqrt(109). A point
    // light of intensity A x cos_light with 1/r^2 falloff gives A cos_light / r^2. Across
    // the square r and cos_light vary by O((side / r)^2) ~ 1e-6 relative and the
    // average of 64 weights rounds by ~64 float ulps ~ 4e-6, so 2e-5 is generous.
    const auto light = square_above(T(0.005), T(10));
    const v p(3, 0, 0);
    const double expected = 1e-4 * (10.0 / std::sqrt(109.0)) / 109.0;
    double sum = 0;
    v mean_l(0);
    light.for_each_sample(p, 8, [&](const shade::light_sample<T>& s) {
        sum += double(s.diffuse.x);
        mean_l += s.l;
    });
    CHECK(sum / 64 == doctest::Approx(expected).epsilon(2e-5));
    // The mean direction is the direction to the centre, (-3, 0, 10) / sqrt(109).
    mean_l /= T(64);
    CHECK(mean_l.x == doctest::Approx(-3.0 / std::sqrt(109.0)).epsilon(1e-5));
    CHECK(mean_l.z == doctest::Approx(10.0 / std::sqrt(109.0)).epsilon(1e-5));
}

TEST_CASE_TEMPLATE("area_light: stratified average under a square matches the analytic form factor", T, float, double) {
    using v = shade::vec3<T>;
    // A point at the origin with normal +z under the square [-a, a]^2 at height h, white
    // light of intensity 1. A white Lambert surface reflects
    //   (1/N) sum (n.l) diffuse  ->  integral over the square of cos_p cos_l / r^2 dA
    //                                = pi F,
    // F the point-to-square form factor. Derivation by Lambert's contour integral (pi F =
    // 1/2 sum over edges of theta_i n.g_i, g_i the unit normal of the plane through p and
    // edge i, theta_i the angle the edge subtends): corners (+-a, +-a, h); for the edge
    // from (a, a, h) to (-a, a, h), cos theta = h^2 / (2a^2 + h^2), i.e.
    // theta = 2 atan(a / sqrt(a^2 + h^2)), and n.g = a / sqrt(a^2 + h^2). Four equal edges:
    //   pi F = 4 k atan(k),  k = a / sqrt(a^2 + h^2).
    // (Same as 4 corner rectangles a x a with the classic corner formula.) For a = h = 1,
    // k = 1/sqrt(2): pi F = 2 sqrt(2) atan(1/sqrt(2)) = 1.7408395...
    const T a = T(1), h = T(1);
    const double k = 1.0 / std::sqrt(2.0);
    const double expected = 4 * k * std::atan(k);
    const auto light = square_above(a, h);
    const v p(0), n(0, 0, 1);

    // Cell centres (the midpoint rule): error ~ (Delta^2 / 24) x integral of the
    // Laplacian of g = h^2 / (rho^2 + h^2)^2 (cos_p cos_l / r^2); |Laplacian g| <= 8 on the
    // square (its value at the centre), so with Delta = 2/64 the error is at most
    // (1/32)^2 / 24 x 4 x 8 = 1.3e-3. Tolerance 1.5e-3 absolute.
    double grid = 0;
    light.for_each_sample(p, 64, [&](const shade::light_sample<T>& s) {
        grid += double(glm::dot(n, s.l) * s.diffuse.x);
    });
    grid /= 64.0 * 64.0;
    CHECK(std::abs(grid - expected) <= 1.5e-3);

    // Jittered strata: unbiased; per stratum the estimate A g varies by at most
    // A |grad g| Delta sqrt(2) = 4 x 1.04 x 0.044 (|grad g| <= 1.04 at rho = 1/sqrt(5)),
    // variance <= that^2 / 12 = 2.8e-3, so the mean of 4096 strata has a standard
    // deviation <= sqrt(2.8e-3 / 4096) = 8.3e-4: tolerance 4e-3 is ~5 sigma.
    lcg rng;
    double jittered = 0;
    light.for_each_sample(
        p, 64,
        [&](const shade::light_sample<T>& s) { jittered += double(glm::dot(n, s.l) * s.diffuse.x); },
        [&](int, int) { return shade::vec2<T>(T(rng.next()), T(rng.next())); });
    jittered /= 64.0 * 64.0;
    CHECK(std::abs(jittered - expected) <= 4e-3);

    // A coarse grid is further off than a fine one (the estimator converges).
    double coarse = 0;
    light.for_each_sample(p, 2, [&](const shade::light_sample<T>& s) {
        coarse += double(glm::dot(n, s.l) * s.diffuse.x);
    });
    coarse /= 4.0;
    CHECK(std::abs(coarse - expected) > std::abs(grid - expected));
}

TEST_CASE_TEMPLATE("area_light: degenerate shaded points give finite, ambient-only samples", T, float, double) {
    using v = shade::vec3<T>;
    shade::emission<T> e;
    e.ambient = shade::rgb<T>(T(0.5));
    const auto light = square_above(T(1), T(1), e);
    // p exactly on the sampled light point.
    const auto on = light.sample(v(-1, -1, 1), shade::vec2<T>(0));
    CHECK(on.diffuse == shade::rgb<T>(0));
    CHECK(on.ambient == shade::rgb<T>(T(0.5)));
    CHECK(shade::is_finite(on.l));
    // p in the light's plane (grazing, cos_light = 0).
    const auto grazing = light.sample(v(5, 0, 1), shade::vec2<T>(T(0.5)));
    CHECK(grazing.diffuse == shade::rgb<T>(0));
    CHECK(shade::is_finite(grazing.l));
    // p a hair below the sampled point: huge but finite, or dropped; never Inf/NaN.
    const auto close = light.sample(v(0, 0, T(1) - T(1e-30)), shade::vec2<T>(T(0.5)));
    CHECK(shade::is_finite(close.diffuse));
}

TEST_CASE_TEMPLATE("area_light rejects bad parameters by name", T, float, double) {
    using v = shade::vec3<T>;
    const T nan = std::numeric_limits<T>::quiet_NaN();
    CHECK_THROWS_WITH_AS(shade::area_light<T>(v(0), v(0), v(0, 1, 0)), doctest::Contains("'edge_u'"),
                         shade::invalid_parameter);
    CHECK_THROWS_WITH_AS(shade::area_light<T>(v(0), v(1, 0, 0), v(0, nan, 0)),
                         doctest::Contains("'edge_v'"), shade::invalid_parameter);
    CHECK_THROWS_WITH_AS(shade::area_light<T>(v(0), v(1, 0, 0), v(-2, 0, 0)),
                         doctest::Contains("'edge_v' must not be parallel"), shade::invalid_parameter);
    CHECK_THROWS_WITH_AS(shade::area_light<T>(v(nan), v(1, 0, 0), v(0, 1, 0)),
                         doctest::Contains("'corner'"), shade::invalid_parameter);
    CHECK_THROWS_WITH_AS(
        shade::area_light<T>(v(0), v(1, 0, 0), v(0, 1, 0), {}, static_cast<shade::sidedness>(5)),
        doctest::Contains("'sides'"), shade::invalid_parameter);
    shade::emission<T> e;
    e.ambient = {0, 0, T(-2)};
    CHECK_THROWS_WITH_AS(shade::area_light<T>(v(0), v(1, 0, 0), v(0, 1, 0), e),
                         doctest::Contains("'ambient'"), shade::invalid_parameter);
    const auto light = square_above(T(1), T(1));
    CHECK_THROWS_WITH_AS(light.for_each_sample(v(0), 0, [](const auto&) {}),
                         doctest::Contains("'samples_per_side'"), shade::invalid_parameter);
}
