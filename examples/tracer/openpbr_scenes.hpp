#pragma once
// The reference tracer's OpenPBR Surface scenes (shade::openpbr_surface), for the path
// integrator:
//   openpbr:         the twelve presets of shade/material/openpbr_presets.hpp as spheres in
//                    two rows of six on a grey floor, in a studio: a gradient sky (an
//                    environment map) and a square key light above the left front;
//   openpbr-furnace: the same twelve in their white-furnace variant (white colours, no
//                    absorbing medium, no emission) in the uniform white environment of
//                    radiance 1: a material that conserves energy is invisible there (its
//                    pixels are 1), one that loses energy shows darker.

#include <cmath>
#include <memory>
#include <span>
#include <vector>

#include <shade/brdf/lambert.hpp>
#include <shade/light/area.hpp>
#include <shade/light/environment_map.hpp>
#include <shade/material/openpbr_presets.hpp>

#include "physical_scenes.hpp"
#include "scene.hpp"

namespace tracer {

namespace detail {

/// The centre of preset k (0 to 11) of the OpenPBR scenes: two rows of six, k < 6 in front
/// (z = 0.9), the rest behind (z = -0.9), 1.3 apart in x, centred on x = 0, at height y.
inline vec3 openpbr_grid_centre(std::size_t k, real y) {
    return vec3(real(-3.25) + real(1.3) * real(k % 6), y, k < 6 ? real(0.9) : real(-0.9));
}

/// The radius of the OpenPBR scenes' spheres.
inline constexpr real openpbr_sphere_radius = 0.5;

/// The studio sky of the openpbr scene as a latitude-longitude map (64 x 32 texels, row 0
/// at the zenith; see shade::environment_map_light): above the horizon a grey gradient from
/// radiance 1 at the horizon to 0.4 at the zenith (1 - 0.6 cos(theta)); below it a dark
/// grey 0.1 (seen only where the floor does not hide it). Radiance in W/(m^2 sr).
inline std::shared_ptr<const shade::environment_map_light<real>> studio_sky() {
    constexpr int width = 64, height = 32;
    std::vector<rgb> texels;
    texels.reserve(std::size_t(width * height));
    for (int y = 0; y < height; ++y) {
        const real cos_theta = std::cos(shade::pi<real> * (real(y) + real(0.5)) / real(height));
        const rgb radiance = cos_theta > 0 ? rgb(1 - real(0.6) * cos_theta) : rgb(0.1);
        for (int x = 0; x < width; ++x) texels.push_back(radiance);
    }
    const auto orientation = shade::frame<real>::from_normal_tangent({0, 1, 0}, {0, 0, -1});
    return std::make_shared<const shade::environment_map_light<real>>(width, height, std::span<const rgb>(texels),
                                                                     real(1), orientation);
}

} // namespace detail

/// openpbr: see the file comment. Object 0 is the floor (a Lambert of albedo 0.4, a 40 x 40
/// quad at y = 0), object 1 the key light (a 2.5 x 2.5 quad at height 5 facing down,
/// radiance 12), objects 2 + k preset k of shade::openpbr::presets, in the order listed
/// there, at detail::openpbr_grid_centre(k, 0.5).
inline scene make_openpbr(real aspect) {
    scene s;
    s.name = "openpbr";
    s.camera = detail::look(vec3(0, 3.3, 6.6), vec3(0, 0.4, -0.1), 37, aspect);
    s.background = rgb(0);
    s.environment_map = detail::studio_sky();
    s.add_physical_mesh(detail::quad(vec3(-20, 0, -20), vec3(0, 0, 40), vec3(40, 0, 0)),
                        shade::lambert<real>(rgb(0.4)));
    s.add_emitting_quad(shade::area_light<real>::from_radiance(vec3(-4.25, 5, 0.75), vec3(2.5, 0, 0),
                                                               vec3(0, 0, 2.5), rgb(12)),
                        std::nullopt);
    const auto presets = shade::openpbr::presets<real>();
    for (std::size_t k = 0; k < presets.size(); ++k)
        s.add_openpbr_sphere(shade::sphere<real>(detail::openpbr_grid_centre(k, detail::openpbr_sphere_radius),
                                                 detail::openpbr_sphere_radius),
                             presets[k].parameters);
    return s;
}

/// openpbr-furnace: see the file comment. Object k is preset k's white-furnace variant
/// (shade::openpbr::white_furnace_variant) at detail::openpbr_grid_centre(k, 0).
inline scene make_openpbr_furnace(real aspect) {
    scene s = detail::white_furnace("openpbr-furnace", aspect);
    s.camera = detail::look(vec3(0, 3.6, 7.5), vec3(0), 38, aspect);
    const auto presets = shade::openpbr::presets<real>();
    for (std::size_t k = 0; k < presets.size(); ++k)
        s.add_openpbr_sphere(shade::sphere<real>(detail::openpbr_grid_centre(k, 0), detail::openpbr_sphere_radius),
                             shade::openpbr::white_furnace_variant(presets[k].parameters));
    return s;
}

} // namespace tracer
