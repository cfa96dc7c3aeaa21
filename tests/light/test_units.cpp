// The lights' unit-naming factories (from_power, from_intensity, from_irradiance,
// from_radiance): each gives the light the physical quantity it names, checked against
// what the light reports (intensity(), radiance(), power()) and against irradiances
// derived by hand; bad arguments are named.

#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include <doctest/doctest.h>

#include <shade/core/sampling.hpp>
#include <shade/light/any_light.hpp>
#include <shade/light/environment_map.hpp>

namespace {

template <class T>
using v3 = shade::vec3<T>;
template <class T>
using v2 = shade::vec2<T>;
template <class T>
using rgb = shade::rgb<T>;

constexpr double pi = std::numbers::pi;

// |a - b| <= tolerance x |b| in every channel (b's channels are non-zero here).
template <class T>
bool near(const rgb<T>& a, const rgb<T>& b, double tolerance) {
    for (int c = 0; c < 3; ++c)
        if (!(std::fabs(double(a[c]) - double(b[c])) <= tolerance * std::fabs(double(b[c])))) return false;
    return true;
}

// Relative tolerance of a few roundings in T (a quantity divided by pi and multiplied back).
template <class T>
constexpr double rounding = std::numeric_limits<T>::epsilon() * 8;

// The irradiance at p on a surface with unit normal n from an emitter, estimated from
// its physical samples on an n_grid x n_grid stratified grid (cell centres): the average
// of L cos / pdf, in double.
template <class T, class E>
double irradiance(const E& light, const v3<T>& p, const v3<T>& n, int n_grid) {
    double sum = 0;
    for (int j = 0; j < n_grid; ++j)
        for (int i = 0; i < n_grid; ++i) {
            const auto s = light.sample_incident(p, shade::stratified_u<T>(i, j, n_grid, shade::cell_centre<T>{}(i, j)));
            if (!s) continue;
            const double cos = double(glm::dot(n, s->l));
            if (cos > 0) sum += double(s->radiance.y) * cos / double(s->pdf);
        }
    return sum / (double(n_grid) * n_grid);
}

// The parameter an invalid_parameter thrown by make() names, or "(accepted)".
template <class F>
std::string parameter_of(F&& make) {
    try {
        make();
    } catch (const shade::invalid_parameter& e) {
        return e.parameter();
    }
    return "(accepted)";
}

} // namespace

TEST_CASE_TEMPLATE("point_light::from_power(4 pi W) has I = 1 W/sr: 1 W/m^2 at 1 m, normal incidence", T, float,
                   double) {
    // An isotropic source of power Phi has intensity Phi / (4 pi) (the sphere is 4 pi sr),
    // and at distance r facing it gives the irradiance I / r^2.
    const auto bulb = shade::point_light<T>::from_power(v3<T>(1, 2, 3), rgb<T>(T(4 * pi)));
    CHECK(near(bulb.intensity(), rgb<T>(1), rounding<T>));
    CHECK(near(bulb.power(), rgb<T>(T(4 * pi)), rounding<T>));
    const auto s = bulb.sample_incident(v3<T>(1, 2, 2), v2<T>(T(0.5)));
    REQUIRE(s);
    CHECK(s->delta);
    CHECK(near(s->radiance, rgb<T>(1), rounding<T>));
    // At 2 m: a quarter.
    CHECK(near(bulb.sample_incident(v3<T>(1, 4, 3), v2<T>(T(0.5)))->radiance, rgb<T>(T(0.25)), rounding<T>));
    CHECK(bulb.distance_falloff() == shade::falloff::inverse_square);
    CHECK(bulb.emitted().ambient == rgb<T>(0));

    const auto coloured = shade::point_light<T>::from_intensity(v3<T>(0), rgb<T>(1, 2, 3));
    CHECK(near(coloured.intensity(), rgb<T>(1, 2, 3), rounding<T>));
    CHECK(near(coloured.power(), T(4 * pi) * rgb<T>(1, 2, 3), rounding<T>));
    // I / r^2 at r = 2.
    CHECK(near(coloured.sample_incident(v3<T>(0, 0, -2), v2<T>(T(0.5)))->radiance, rgb<T>(0.25, 0.5, 0.75), rounding<T>));
}

TEST_CASE_TEMPLATE("spot_light::from_power divides the power by the cone's solid angle", T, float, double) {
    // Hard-edged hemisphere (inner = outer = pi/2): Omega = 2 pi (1 - (0 + 0) / 2) = 2 pi sr,
    // so 2 pi W give 1 W/sr on the axis (cos(pi/2) rounds to ~1e-8 in float, ~6e-17 in
    // double, far below the tolerance).
    const T half_pi = T(pi / 2);
    const auto hemi = shade::spot_light<T>::from_power(v3<T>(0), v3<T>(0, 0, -1), half_pi, half_pi, rgb<T>(T(2 * pi)));
    CHECK(near(hemi.intensity(), rgb<T>(1), 1e-6));
    // On the axis at 1 m: I / r^2 = 1 W/m^2.
    CHECK(near(hemi.sample_incident(v3<T>(0, 0, -1), v2<T>(T(0.5)))->radiance, rgb<T>(1), 1e-6));

    // A smooth edge: Omega = 2 pi (1 - (cos 0.3 + cos 0.7) / 2) (the class comment's
    // formula; the smoothstep averages 1/2 over the edge), and power() gives Phi back.
    const rgb<T> phi(3, 5, 7);
    const auto spot = shade::spot_light<T>::from_power(v3<T>(0), v3<T>(1, 0, 0), T(0.3), T(0.7), phi);
    const double omega = 2 * pi * (1 - (std::cos(0.3) + std::cos(0.7)) / 2);
    CHECK(double(spot.intensity().x) == doctest::Approx(3 / omega).epsilon(1e-5));
    CHECK(near(spot.power(), phi, 1e-5));
    CHECK(spot.inner_angle() == T(0.3));
    CHECK(spot.outer_angle() == T(0.7));

    const auto by_intensity = shade::spot_light<T>::from_intensity(v3<T>(0), v3<T>(1, 0, 0), T(0.3), T(0.7), rgb<T>(2));
    CHECK(near(by_intensity.intensity(), rgb<T>(2), rounding<T>));
    CHECK(double(by_intensity.power().x) == doctest::Approx(2 * omega).epsilon(1e-5));
}

TEST_CASE_TEMPLATE("directional_light::from_irradiance gives E at normal incidence", T, float, double) {
    const auto sun = shade::directional_light<T>::from_irradiance(v3<T>(0, 3, 4), rgb<T>(1, 2, 3));
    CHECK(near(sun.irradiance(), rgb<T>(1, 2, 3), rounding<T>));
    const auto s = sun.sample_incident(v3<T>(5), v2<T>(T(0.5)));
    REQUIRE(s);
    CHECK(near(s->radiance, rgb<T>(1, 2, 3), rounding<T>));
    // Through a scene of radius 2: E times the cross-section pi 2^2.
    CHECK(near(sun.power(T(2)), T(4 * pi) * rgb<T>(1, 2, 3), rounding<T>));
    CHECK(sun.power(T(0)) == rgb<T>(0));
}

TEST_CASE_TEMPLATE("area lights from_power: power() == Phi, radiance Phi / (pi A) per emitting side", T, float,
                   double) {
    using shade::sidedness;
    const rgb<T> phi(T(6 * pi), T(12 * pi), T(18 * pi));
    // Rectangle 2 x 3: A = 6, so Phi = 6 pi (1, 2, 3) W gives L = (1, 2, 3) one-sided,
    // half that two-sided.
    const auto rect = shade::area_light<T>::from_power(v3<T>(0), v3<T>(2, 0, 0), v3<T>(0, 3, 0), phi);
    CHECK(near(rect.radiance(), rgb<T>(1, 2, 3), rounding<T>));
    CHECK(near(rect.power(), phi, rounding<T>));
    const auto rect2 =
        shade::area_light<T>::from_power(v3<T>(0), v3<T>(2, 0, 0), v3<T>(0, 3, 0), phi, sidedness::two_sided);
    CHECK(near(rect2.radiance(), rgb<T>(0.5, 1, 1.5), rounding<T>));
    CHECK(near(rect2.power(), phi, rounding<T>));
    CHECK(rect2.sides() == sidedness::two_sided);
    // Right triangle with legs 2 and 3: A = 3, L = 2 (1, 2, 3).
    const auto tri = shade::triangle_light<T>::from_power(v3<T>(0), v3<T>(2, 0, 0), v3<T>(0, 3, 0), phi);
    CHECK(near(tri.radiance(), rgb<T>(2, 4, 6), rounding<T>));
    CHECK(near(tri.power(), phi, rounding<T>));
    // Two-sided disk of radius 1: A = pi, L = Phi / (2 pi A) = (1, 2, 3) x 3 / pi.
    const auto disk = shade::disk_light<T>::from_power(v3<T>(0), v3<T>(0, 0, 1), T(1), phi, sidedness::two_sided);
    CHECK(near(disk.radiance(), T(3 / pi) * rgb<T>(1, 2, 3), rounding<T>));
    CHECK(near(disk.power(), phi, rounding<T>));
    // Sphere of radius 1: A = 4 pi, L = Phi / (4 pi^2) = (1, 2, 3) x 6 / (4 pi) one-sided.
    const auto ball = shade::sphere_light<T>::from_power(v3<T>(0), T(1), phi);
    CHECK(near(ball.radiance(), T(6 / (4 * pi)) * rgb<T>(1, 2, 3), rounding<T>));
    CHECK(near(ball.power(), phi, rounding<T>));
    // And through any_light.
    CHECK(near(shade::any_light<T>(ball).power(T(100)), phi, rounding<T>));
}

TEST_CASE_TEMPLATE("area lights from_radiance: radiance() is L", T, float, double) {
    const rgb<T> L(1, 2, 3);
    CHECK(near(shade::area_light<T>::from_radiance(v3<T>(0), v3<T>(1, 0, 0), v3<T>(0, 1, 0), L).radiance(), L, rounding<T>));
    CHECK(near(shade::triangle_light<T>::from_radiance(v3<T>(0), v3<T>(1, 0, 0), v3<T>(0, 1, 0), L).radiance(), L,
               rounding<T>));
    CHECK(near(shade::disk_light<T>::from_radiance(v3<T>(0), v3<T>(0, 0, 1), T(2), L).radiance(), L, rounding<T>));
    const auto ball = shade::sphere_light<T>::from_radiance(v3<T>(0), T(2), L, shade::sidedness::two_sided);
    CHECK(near(ball.radiance(), L, rounding<T>));
    // Two-sided sphere of radius 2: 2 x pi L x 4 pi 2^2.
    CHECK(near(ball.power(), T(2 * pi * 16 * pi) * L, rounding<T>));
    const auto sky = shade::environment_light<T>::from_radiance(L);
    CHECK(near(sky.radiance(), L, rounding<T>));
    // Onto a scene of radius 3: 4 pi 3^2 x pi L.
    CHECK(near(sky.power(T(3)), T(36 * pi * pi) * L, rounding<T>));
}

TEST_CASE_TEMPLATE("from_power gives the irradiance derived for a disk and a sphere", T, float, double) {
    // Disk of radius R and radiance L, on its axis at height d, facing it: E = pi L R^2 /
    // (d^2 + R^2) (the view factor of a parallel coaxial disk, R^2 / (R^2 + d^2); e.g. Howell,
    // "A Catalog of Radiation Heat Transfer Configuration Factors", B-13). With
    // L = Phi / (pi pi R^2): E = Phi / (pi (d^2 + R^2)); Phi = 2 pi W, R = d = 1: E = 1 W/m^2.
    const auto disk = shade::disk_light<T>::from_power(v3<T>(0, 0, 1), v3<T>(0, 0, -1), T(1), rgb<T>(T(2 * pi)));
    CHECK(irradiance<T>(disk, v3<T>(0), v3<T>(0, 0, 1), 64) == doctest::Approx(1.0).epsilon(2e-3));
    // Sphere of radius R, radiance L, seen from distance d > R: E = pi L (R / d)^2 (pi L
    // sin^2 theta_max, the irradiance from a uniform cone of half-angle theta_max); with
    // L = Phi / (4 pi^2 R^2): E = Phi / (4 pi d^2), as from a point light of the same
    // power. Phi = 4 pi W at d = 2: E = 1/4 W/m^2.
    const auto ball = shade::sphere_light<T>::from_power(v3<T>(0, 0, 2), T(0.5), rgb<T>(T(4 * pi)));
    CHECK(irradiance<T>(ball, v3<T>(0), v3<T>(0, 0, 1), 64) == doctest::Approx(0.25).epsilon(2e-3));
}

TEST_CASE_TEMPLATE("every light's power(scene_radius), and the factories, name a bad argument", T, float, double) {
    const T nan = std::numeric_limits<T>::quiet_NaN();
    const T inf = std::numeric_limits<T>::infinity();
    using shade::sidedness;
    CHECK(parameter_of([&] { (void)shade::point_light<T>::from_power(v3<T>(0), rgb<T>(-1)); }) == "power");
    CHECK(parameter_of([&] { (void)shade::point_light<T>::from_intensity(v3<T>(0), rgb<T>(1, nan, 1)); }) == "intensity");
    CHECK(parameter_of([&] { (void)shade::point_light<T>::from_power(v3<T>(nan), rgb<T>(1)); }) == "position");
    CHECK(parameter_of([&] { (void)shade::directional_light<T>::from_irradiance(v3<T>(0, 0, 1), rgb<T>(inf)); }) ==
          "irradiance");
    CHECK(parameter_of([&] { (void)shade::directional_light<T>::from_irradiance(v3<T>(0), rgb<T>(1)); }) == "direction");
    CHECK(parameter_of([&] {
              (void)shade::spot_light<T>::from_intensity(v3<T>(0), v3<T>(0, 0, 1), T(0.2), T(0.1), rgb<T>(1));
          }) == "inner_angle");
    // cos(1e-9) rounds to 1 in float and double: the cone has no solid angle, so no
    // intensity gives it a power.
    CHECK(parameter_of([&] {
              (void)shade::spot_light<T>::from_power(v3<T>(0), v3<T>(0, 0, 1), T(0), T(1e-9), rgb<T>(1));
          }) == "outer_angle");
    CHECK(parameter_of([&] {
              (void)shade::spot_light<T>::from_power(v3<T>(0), v3<T>(0, 0, 1), T(0.1), T(0.2), rgb<T>(-1));
          }) == "power");
    CHECK(parameter_of([&] {
              (void)shade::area_light<T>::from_radiance(v3<T>(0), v3<T>(1, 0, 0), v3<T>(0, 1, 0), rgb<T>(-1));
          }) == "radiance");
    CHECK(parameter_of([&] {
              (void)shade::area_light<T>::from_power(v3<T>(0), v3<T>(1, 0, 0), v3<T>(2, 0, 0), rgb<T>(1));
          }) == "edge_v");
    // Phi / (pi A) overflows for the largest power over a 1e-3 x 1e-3 square.
    const T huge = std::numeric_limits<T>::max();
    CHECK(parameter_of([&] {
              (void)shade::area_light<T>::from_power(v3<T>(0), v3<T>(T(1e-3), 0, 0), v3<T>(0, T(1e-3), 0), rgb<T>(huge));
          }) == "power");
    CHECK(parameter_of([&] { (void)shade::disk_light<T>::from_power(v3<T>(0), v3<T>(0, 0, 1), T(0), rgb<T>(1)); }) ==
          "radius");
    CHECK(parameter_of([&] { (void)shade::sphere_light<T>::from_radiance(v3<T>(0), T(1), rgb<T>(nan)); }) == "radiance");
    CHECK(parameter_of([&] {
              (void)shade::triangle_light<T>::from_power(v3<T>(0), v3<T>(1, 0, 0), v3<T>(0, 1, 0), rgb<T>(-2),
                                                         sidedness::two_sided);
          }) == "power");
    CHECK(parameter_of([&] { (void)shade::environment_light<T>::from_radiance(rgb<T>(-1)); }) == "radiance");

    // power(scene_radius) takes a finite radius >= 0 on every light, even those that ignore it.
    const shade::any_light<T> lights[] = {
        shade::point_light<T>::from_power(v3<T>(0), rgb<T>(1)),
        shade::spot_light<T>::from_power(v3<T>(0), v3<T>(0, 0, 1), T(0.1), T(0.2), rgb<T>(1)),
        shade::directional_light<T>::from_irradiance(v3<T>(0, 0, 1), rgb<T>(1)),
        shade::area_light<T>::from_power(v3<T>(0), v3<T>(1, 0, 0), v3<T>(0, 1, 0), rgb<T>(1)),
        shade::disk_light<T>::from_power(v3<T>(0), v3<T>(0, 0, 1), T(1), rgb<T>(1)),
        shade::sphere_light<T>::from_power(v3<T>(0), T(1), rgb<T>(1)),
        shade::environment_light<T>::from_radiance(rgb<T>(1)),
        shade::triangle_light<T>::from_power(v3<T>(0), v3<T>(1, 0, 0), v3<T>(0, 1, 0), rgb<T>(1))};
    for (const auto& l : lights) {
        CHECK(parameter_of([&] { (void)l.power(T(-1)); }) == "scene_radius");
        CHECK(parameter_of([&] { (void)l.power(nan); }) == "scene_radius");
        CHECK(parameter_of([&] { (void)l.power(inf); }) == "scene_radius");
        CHECK(parameter_of([&] { (void)l.power(T(1)); }) == "(accepted)");
    }
}

TEST_CASE_TEMPLATE("environment_map_light::power(r) = pi r^2 x the integral of its radiance", T, float, double) {
    // A constant map of radiance L: the integral is 4 pi L, so the power is 4 pi^2 r^2 L
    // (as environment_light's). One bright row on top of a 2 x 2 map: the top row covers
    // theta in [0, pi/2), each texel Omega = (2 pi / 2)(1 - 0) = pi sr, so texels (3, 0)
    // give the integral 2 pi x 3 and the power pi r^2 x 6 pi.
    const std::vector<rgb<T>> constant(8 * 4, rgb<T>(1, 2, 3));
    const shade::environment_map_light<T> map(8, 4, constant);
    CHECK(near(map.power(T(2)), T(16 * pi * pi) * rgb<T>(1, 2, 3), 1e-5));
    const std::vector<rgb<T>> top = {rgb<T>(3), rgb<T>(3), rgb<T>(0), rgb<T>(0)};
    const shade::environment_map_light<T> half(2, 2, top);
    CHECK(near(half.power(T(1)), rgb<T>(T(6 * pi * pi)), 1e-5));
    CHECK(parameter_of([&] { (void)half.power(T(-1)); }) == "scene_radius");
}
