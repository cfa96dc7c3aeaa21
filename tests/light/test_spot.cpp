#include <cmath>
#include <limits>

#include <doctest/doctest.h>

#include <shade/light/spot.hpp>

namespace {

// The spot used below: at (0, 0, 4), pointing straight down, inner half-angle 30 degrees,
// outer 45 degrees, inverse-square falloff, white, intensity 1.
template <class T>
shade::spot_light<T> down_spot() {
    return shade::spot_light<T>(shade::vec3<T>(0, 0, 4), shade::vec3<T>(0, 0, -3),
                                shade::pi<T> / T(6), shade::pi<T> / T(4));
}

// The point at distance 1 from the spot's position, at angle theta from its axis.
template <class T>
shade::vec3<T> at_angle(T theta) {
    return shade::vec3<T>(std::sin(theta), 0, T(4) - std::cos(theta));
}

} // namespace

TEST_CASE_TEMPLATE("spot_cone_factor: 1 inside, 0 outside, smoothstep between", T, float, double) {
    const T cos_inner = T(0.9);
    const T cos_outer = T(0.5);
    CHECK(shade::spot_cone_factor(T(1), cos_inner, cos_outer) == T(1));
    CHECK(shade::spot_cone_factor(T(0.9), cos_inner, cos_outer) == T(1));
    CHECK(shade::spot_cone_factor(T(0.5), cos_inner, cos_outer) == T(0));
    CHECK(shade::spot_cone_factor(T(-1), cos_inner, cos_outer) == T(0));
    // cos_s = 0.7 is halfway: t = 0.2/0.4 = 1/2, smoothstep = 1/4 x (3 - 1) = 1/2.
    CHECK(shade::spot_cone_factor(T(0.7), cos_inner, cos_outer) == doctest::Approx(0.5).epsilon(1e-6));
    // cos_s = 0.6: t = 1/4, smoothstep = 1/16 x (3 - 1/2) = 5/32.
    CHECK(shade::spot_cone_factor(T(0.6), cos_inner, cos_outer) == doctest::Approx(5.0 / 32).epsilon(1e-5));
    // Equal cosines: a hard edge.
    CHECK(shade::spot_cone_factor(T(0.5), T(0.5), T(0.5)) == T(1));
    CHECK(shade::spot_cone_factor(T(0.49), T(0.5), T(0.5)) == T(0));
}

TEST_CASE_TEMPLATE("spot_light inside, outside and on the edge of the cone", T, float, double) {
    using v = shade::vec3<T>;
    const auto spot = down_spot<T>();
    CHECK(spot.axis() == v(0, 0, -1));
    // On the axis, 4 below: cone factor 1, falloff 1/16, l straight up.
    const auto on_axis = spot.sample(v(0));
    CHECK(on_axis.l == v(0, 0, 1));
    CHECK(on_axis.distance == T(4));
    CHECK(on_axis.diffuse == shade::rgb<T>(T(1) / T(16)));
    // (1, 0, 0): angle atan(1/4) = 14 degrees < 30: factor 1, r^2 = 17.
    const auto inside = spot.sample(v(1, 0, 0));
    CHECK(inside.diffuse.x == doctest::Approx(1.0 / 17).epsilon(1e-6));
    CHECK(inside.distance == doctest::Approx(std::sqrt(17.0)).epsilon(1e-6));
    // (8, 0, 0): angle atan(2) = 63 degrees > 45: no light, but l and distance are still
    // reported: r = sqrt(64 + 16) = sqrt(80), l = (8, 0, 4) / sqrt(80).
    const auto outside = spot.sample(v(8, 0, 0));
    CHECK(outside.diffuse == shade::rgb<T>(0));
    CHECK(outside.specular == shade::rgb<T>(0));
    CHECK(outside.distance == doctest::Approx(std::sqrt(80.0)).epsilon(1e-6));
    CHECK(outside.l.z == doctest::Approx(4.0 / std::sqrt(80.0)).epsilon(1e-6));
    // Edge: the angle whose cosine is halfway between cos 30 and cos 45 gives t = 1/2 and
    // smoothstep 1/2; at distance 1 the falloff is 1, so diffuse = 1/2.
    const T cos_mid = (std::cos(shade::pi<T> / T(6)) + std::cos(shade::pi<T> / T(4))) / T(2);
    const auto edge = spot.sample(at_angle(std::acos(cos_mid)));
    CHECK(edge.diffuse.x == doctest::Approx(0.5).epsilon(1e-4));
    CHECK(edge.distance == doctest::Approx(1.0).epsilon(1e-6));
    // Exactly at 30 degrees: full light; just past 45 degrees: none.
    CHECK(spot.sample(at_angle(shade::pi<T> / T(6) * T(0.999))).diffuse.x == doctest::Approx(1.0).epsilon(1e-6));
    CHECK(spot.sample(at_angle(shade::pi<T> / T(4) * T(1.001))).diffuse.x == T(0));
}

TEST_CASE_TEMPLATE("spot_light's cone factor decreases monotonically across the edge", T, float, double) {
    // The pure factor is monotone in the angle and stays in [0, 1].
    const T cos_inner = std::cos(shade::pi<T> / T(6));
    const T cos_outer = std::cos(shade::pi<T> / T(4));
    T previous = T(1);
    const auto spot = down_spot<T>();
    for (int i = 0; i <= 100; ++i) {
        const T theta = shade::pi<T> / T(3) * T(i) / T(100); // 0 .. 60 degrees
        const T factor = shade::spot_cone_factor(std::cos(theta), cos_inner, cos_outer);
        CHECK(factor >= T(0));
        CHECK(factor <= previous);
        previous = factor;
        // The light applies exactly this factor times the falloff 1/r^2 (r = 1 up to
        // rounding, so diffuse x r^2 recovers the factor to a few ulps).
        const auto s = spot.sample(at_angle(theta));
        CHECK(double(s.diffuse.x * s.distance * s.distance) ==
              doctest::Approx(double(factor)).epsilon(1e-5));
    }
}

TEST_CASE_TEMPLATE("spot_light: equal angles make a hard edge; falloff laws apply", T, float, double) {
    using v = shade::vec3<T>;
    const shade::spot_light<T> hard(v(0, 0, 1), v(0, 0, -1), T(0.5), T(0.5), {},
                                    shade::falloff::none);
    CHECK(hard.sample(at_angle(T(0.49)) - v(0, 0, 3)).diffuse.x == T(1));
    CHECK(hard.sample(at_angle(T(0.51)) - v(0, 0, 3)).diffuse.x == T(0));
    // inverse_linear at r = 4 on the axis: 1/4.
    const shade::spot_light<T> linear(v(0, 0, 4), v(0, 0, -1), T(0.1), T(0.2), {},
                                      shade::falloff::inverse_linear);
    CHECK(linear.sample(v(0)).diffuse.x == T(0.25));
}

TEST_CASE_TEMPLATE("spot_light at its own position: ambient only, no NaN", T, float, double) {
    using v = shade::vec3<T>;
    shade::emission<T> e;
    e.ambient = shade::rgb<T>(T(0.5));
    const shade::spot_light<T> spot(v(0, 0, 4), v(0, 0, -1), T(0.3), T(0.6), e);
    const auto s = spot.sample(v(0, 0, 4));
    CHECK(s.diffuse == shade::rgb<T>(0));
    CHECK(s.ambient == shade::rgb<T>(T(0.5)));
    CHECK(shade::is_finite(s.l));
    // Grazing: a point in the plane of the light, perpendicular to the axis: 90 degrees.
    const auto side = spot.sample(v(2, 0, 4));
    CHECK(side.diffuse == shade::rgb<T>(0));
    CHECK(shade::is_finite(side.l));
}

TEST_CASE_TEMPLATE("spot_light rejects bad parameters by name", T, float, double) {
    using v = shade::vec3<T>;
    const T nan = std::numeric_limits<T>::quiet_NaN();
    const v p(0), a(0, 0, -1);
    CHECK_THROWS_WITH_AS(shade::spot_light<T>(p, a, T(0.6), T(0.3)),
                         doctest::Contains("'inner_angle' must be <= outer_angle"),
                         shade::invalid_parameter);
    CHECK_THROWS_WITH_AS(shade::spot_light<T>(p, a, T(-0.1), T(0.3)), doctest::Contains("'inner_angle'"),
                         shade::invalid_parameter);
    CHECK_THROWS_WITH_AS(shade::spot_light<T>(p, a, T(0), T(0)), doctest::Contains("'outer_angle'"),
                         shade::invalid_parameter);
    CHECK_THROWS_WITH_AS(shade::spot_light<T>(p, a, T(0.1), T(4)), doctest::Contains("'outer_angle'"),
                         shade::invalid_parameter);
    CHECK_THROWS_WITH_AS(shade::spot_light<T>(p, a, nan, T(0.3)), doctest::Contains("'inner_angle'"),
                         shade::invalid_parameter);
    CHECK_THROWS_WITH_AS(shade::spot_light<T>(p, v(0), T(0.1), T(0.3)), doctest::Contains("'axis'"),
                         shade::invalid_parameter);
    CHECK_THROWS_WITH_AS(shade::spot_light<T>(v(nan), a, T(0.1), T(0.3)), doctest::Contains("'position'"),
                         shade::invalid_parameter);
    shade::emission<T> e;
    e.intensity = nan;
    CHECK_THROWS_WITH_AS(shade::spot_light<T>(p, a, T(0.1), T(0.3), e), doctest::Contains("'intensity'"),
                         shade::invalid_parameter);
}
