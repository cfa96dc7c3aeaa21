// The usage example of README.md, compiled and run, so the README cannot rot.
#include <doctest/doctest.h>

#include <cstdio>

// --- README example begins ---
#include <shade/shade.hpp>
using namespace shade;

rgb<double> readme_example() {
    const ray<double> r{{0, 1, 5}, {0, 0, -1}};                       // origin, direction
    const auto h = intersect(r, sphere<double>({0, 1, 0}, 1.0));        // std::optional<hit>
    if (!h) return rgb<double>(0);
    const auto at = surface_point<double>::at(h->p, h->facing_normal());
    const cook_torrance<ggx<double>, schlick<double>, smith_ggx<double>> gold(
        ggx<double>(0.3), schlick<double>({1.0, 0.71, 0.29}));
    const directional_light<double> sun({1, 1, 1});
    return lit{gold}.shade(at, -r.direction, sun.sample(h->p, {}));   // radiance toward the eye
}
// In physical units: a 100 W bulb 2 m above a Lambertian floor of albedo 0.8.
rgb<double> readme_physical_example() {
    const auto bulb = point_light<double>::from_power({0, 2, 0}, rgb<double>(100)); // watts
    const auto at = surface_point<double>::at({0, 0, 0}, {0, 1, 0});
    const auto s = bulb.sample_incident(vec3<double>(0), {}); // toward the bulb; W/m^2
    const lambert<double> floor(rgb<double>(0.8));
    return floor.f(s->l, {0, 1, 0}, at) * s->radiance * glm::dot(at.n(), s->l); // W/(m^2 sr)
}
// --- README example ends ---

TEST_CASE("the README example hits the sphere and returns a positive, finite radiance") {
    // The ray from (0,1,5) along -z meets the unit sphere at (0,1,1) (t = 4), normal +z;
    // the sun direction (1,1,1)/sqrt(3) is above that surface, so the gold lobe reflects
    // some light toward +z; gold's Schlick F0 is reddest, so red >= green >= blue.
    const rgb<double> L = readme_example();
    CHECK(L.r > 0);
    CHECK(L.r >= L.g);
    CHECK(L.g >= L.b);
    CHECK(std::isfinite(L.r));
}

TEST_CASE("the README's physical example: 100 W at 2 m on a Lambertian floor") {
    // I = 100 / (4 pi) W/sr, E = I / 2^2 at normal incidence, and the floor reflects
    // 0.8 / pi x E = 0.8 x 100 / (16 pi^2) W/(m^2 sr) toward the zenith.
    const double expected = 0.8 * 100 / (16 * pi<double> * pi<double>);
    const rgb<double> L = readme_physical_example();
    CHECK(L.r == doctest::Approx(expected).epsilon(1e-12));
    CHECK(L.g == doctest::Approx(expected).epsilon(1e-12));
    CHECK(L.b == doctest::Approx(expected).epsilon(1e-12));
}
