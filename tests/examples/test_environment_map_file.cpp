// An environment map read from a file: the tracer's PFM and EXR readers return linear
// radiance, rows from the top, which is what shade::environment_map_light takes, so a
// file becomes a light in one line, with its rows and columns where the header says.

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/core/random.hpp>
#include <shade/light/environment_map.hpp>

#include "tracer/exr.hpp"
#include "tracer/pfm.hpp"

namespace {

using tracer::real;
using tracer::rgb;
namespace fs = std::filesystem;

// A 16 x 8 sky of radiance 1 with a sun of 500 in column 4, row 1 (theta from 22.5 to 45
// degrees, u from 1/4 to 5/16: phi from pi/2 down to 3 pi/8, toward +y), and the top row
// tinted red, so that an upside-down or mirrored read shows.
tracer::radiance_image sun_map() {
    tracer::radiance_image image{16, 8, std::vector<rgb>(16 * 8, rgb(1))};
    for (int x = 0; x < 16; ++x) image.pixels[std::size_t(x)] = rgb(2, 1, 1);
    image.pixels[1 * 16 + 4] = rgb(500);
    return image;
}

void check_light(const shade::environment_map_light<real>& light) {
    const shade::vec3<real> origin(0);
    // The sun's centre: theta = 33.75 degrees, phi = pi/2 - pi/16 (u = 9/32).
    const real theta = shade::pi<real> * 1.5 / 8, phi = shade::pi<real> * (0.5 - 1.0 / 16);
    const shade::vec3<real> sun(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
    CHECK(light.incident_radiance(origin, sun) == rgb(500));
    CHECK(light.incident_radiance(origin, shade::vec3<real>(0, 0, 1)) == rgb(2, 1, 1));
    CHECK(light.incident_radiance(origin, shade::vec3<real>(0, 0, -1)) == rgb(1));
    // Most samples go to the sun: its share of luminance x solid angle.
    int on_sun = 0;
    shade::rng random(5);
    for (int k = 0; k < 1000; ++k) {
        const auto s = light.sample_incident(origin, {random.uniform<real>(), random.uniform<real>()});
        REQUIRE(s);
        if (s->radiance == rgb(500)) ++on_sun;
    }
    CHECK(on_sun > 700);
}

} // namespace

TEST_CASE("environment map from a PFM or an EXR file: rows from the top, columns as the header says") {
    for (const bool exr : {false, true}) {
        CAPTURE(exr);
        const fs::path path = fs::temp_directory_path() / (exr ? "shade_test_envmap.exr" : "shade_test_envmap.pfm");
        if (exr) tracer::save_exr(path, sun_map());
        else tracer::save_pfm(path, sun_map());
        const tracer::radiance_image image = exr ? tracer::load_exr(path) : tracer::load_pfm(path);
        check_light(shade::environment_map_light<real>(image.width, image.height, image.pixels));
        fs::remove(path);
    }
}
