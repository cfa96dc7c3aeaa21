#pragma once
// The reference tracer's built-in scenes, built in code:
//   gallery: one sphere per shading model on a checker plane, lit by a sun, a point light
//            with falloff, a spot light and an area light;
//   mesh:    a tessellated torus three times: flat, Gouraud and Phong shading;
//   lights:  hard shadows from a point and a directional light, soft ones from an area light.

#include <stdexcept>
#include <string>

#include <shade/brdf/ashikhmin_shirley.hpp>
#include <shade/brdf/blinn_phong.hpp>
#include <shade/brdf/cook_torrance.hpp>
#include <shade/brdf/lambert.hpp>
#include <shade/brdf/oren_nayar.hpp>
#include <shade/brdf/phong.hpp>
#include <shade/shading/checker.hpp>
#include <shade/shading/gooch.hpp>
#include <shade/shading/gradient.hpp>
#include <shade/shading/toon.hpp>

#include "openpbr_scenes.hpp"
#include "physical_scenes.hpp"
#include "scene.hpp"

namespace tracer {

/// The names make_scene accepts, comma-separated (for messages).
inline std::string scene_names() { return "gallery, mesh, lights, furnace, furnace-conductor, glass-furnace, energy, enclosure, veach, cornell, glass, openpbr, openpbr-furnace"; }

/// True when make_scene knows `name`.
inline bool is_scene_name(const std::string& name) {
    return name == "gallery" || name == "mesh" || name == "lights" || name == "furnace" ||
           name == "furnace-conductor" || name == "glass-furnace" || name == "energy" || name == "enclosure" || name == "veach" || name == "cornell" || name == "glass" ||
           name == "openpbr" || name == "openpbr-furnace";
}

namespace detail {

inline shade::emission<real> light_colour(real intensity, rgb diffuse, rgb specular, rgb ambient = rgb(0)) {
    shade::emission<real> e;
    e.intensity = intensity;
    e.diffuse = diffuse;
    e.specular = specular;
    e.ambient = ambient;
    return e;
}

/// The checker floor: two Lambert greys in unit cells. The plane y = 0 lies exactly on
/// cell boundaries in y; the checker's bias (0.5) moves them half a cell away, so the
/// floor shows a clean pattern instead of noise.
inline material checker_floor() {
    using L = shade::lambert<real>;
    return make_material(shade::checker<L, L>(L(rgb(0.75)), L(rgb(0.25)), real(1)));
}

inline shade::pinhole_camera<real> camera(vec3 position, vec3 look_at, real fov_degrees, real aspect) {
    return {position, look_at, vec3(0, 1, 0), fov_degrees * shade::pi<real> / 180, aspect};
}

} // namespace detail

/// One sphere per model, two rows of six, on a checker floor.
inline scene make_gallery(real aspect) {
    using namespace shade;
    scene s;
    s.name = "gallery";
    s.camera = detail::camera({0, 4.6, 8}, {0, 0.2, 0}, 38, aspect);
    s.add_plane(plane<real>({0, 0, 0}, {0, 1, 0}), detail::checker_floor());

    const rgb red(0.7, 0.12, 0.1), blue(0.1, 0.25, 0.7), gold(1.0, 0.71, 0.29), white(1);
    std::vector<material> models = {
        make_material(lambert<real>(red)),
        make_material(classic_phong<real>(red * 0.8, rgb(0.2), 40)),
        make_material(normalized_phong<real>(blue * 0.8, rgb(0.2), 40)),
        make_material(blinn_phong<real>(blue * 0.8, rgb(0.2), 80)),
        make_material(cook_torrance<beckmann<real>, schlick<real>, v_groove<real>>(
            beckmann<real>(0.3), schlick<real>(gold), white)),
        make_material(cook_torrance<ggx<real>, schlick<real>, smith_ggx<real>>(
            ggx<real>(0.2), schlick<real>(rgb(0.04)), white, rgb(0.1, 0.5, 0.2))),
        make_material(oren_nayar<real>(rgb(0.8, 0.6, 0.4), 0.5)),
        make_material(ashikhmin_shirley<real>(rgb(0.2, 0.1, 0.3), rgb(0.3), 10, 400)),
        make_material(toon<real>(toon_params<real>{rgb(0.2, 0.6, 0.9), rgb(1), rgb(0), 40, 4, 3})),
        make_material(gooch<real>(gooch_params<real>{})),
        make_material(checker<lambert<real>, blinn_phong<real>>(
            lambert<real>(rgb(0.9)), blinn_phong<real>(red, rgb(0.3), 60), real(0.2))),
        make_material(gradient<lambert<real>, normalized_phong<real>>(
            lambert<real>(rgb(0.9, 0.8, 0.2)), normalized_phong<real>(blue, rgb(0.3), 30),
            vec3(0, 1, 0), real(0.6))),
    };
    for (std::size_t i = 0; i < models.size(); ++i) {
        const real x = -3.25 + 1.3 * real(i % 6);
        const real z = i < 6 ? 0.9 : -0.9;
        s.add_sphere(sphere<real>({x, 0.5, z}, 0.5), models[i]);
    }

    s.lights.push_back(directional_light<real>({-0.4, 1, 0.6}, detail::light_colour(0.55, rgb(1, 0.97, 0.9), rgb(1), rgb(0.06))));
    s.lights.push_back(point_light<real>({2.5, 2.5, 2.5}, detail::light_colour(5, rgb(1, 0.85, 0.7), rgb(1)), falloff::inverse_square));
    s.lights.push_back(spot_light<real>({-3, 4, 3}, {0.4, -1, -0.5}, 0.25, 0.4, detail::light_colour(10, rgb(0.6, 0.8, 1), rgb(1)), falloff::inverse_square));
    s.lights.push_back(area_light<real>({-1, 4, -2}, {2, 0, 0}, {0, 0, 1}, detail::light_colour(1.2, rgb(1), rgb(1))));
    return s;
}

/// Smooth-shading comparison: the same coarse torus, flat, Gouraud and Phong shaded.
inline scene make_mesh_scene(real aspect) {
    using namespace shade;
    scene s;
    s.name = "mesh";
    s.camera = detail::camera({0, 3.5, 6.5}, {0, 0.45, 0}, 40, aspect);
    s.add_plane(plane<real>({0, 0, 0}, {0, 1, 0}), detail::checker_floor());
    const auto surface = make_material(blinn_phong<real>(rgb(0.7, 0.3, 0.15), rgb(0.35), 60));
    const mesh_shading modes[] = {mesh_shading::flat, mesh_shading::gouraud, mesh_shading::phong};
    for (int i = 0; i < 3; ++i) {
        const vec3 centre(-2.4 + 2.4 * real(i), 0.35, 0);
        s.add_mesh(make_torus(centre, 0.75, 0.35, 28, 14), modes[i], surface);
    }
    s.lights.push_back(directional_light<real>({-0.5, 1, 0.8}, detail::light_colour(0.8, rgb(1), rgb(1), rgb(0.05))));
    s.lights.push_back(point_light<real>({2, 3, 2}, detail::light_colour(4, rgb(1, 0.9, 0.8), rgb(1)), falloff::inverse_square));
    return s;
}

/// Shadows: a point light over the left sphere, a low sun from the right, and an area
/// light over the right sphere.
inline scene make_lights_scene(real aspect) {
    using namespace shade;
    scene s;
    s.name = "lights";
    s.camera = detail::camera({0, 5, 7}, {0, 0.3, 0}, 40, aspect);
    s.add_plane(plane<real>({0, 0, 0}, {0, 1, 0}), make_material(lambert<real>(rgb(0.8))));
    const auto grey = make_material(lambert<real>(rgb(0.6)));
    s.add_sphere(sphere<real>({-2, 0.6, 0}, 0.6), grey);
    s.add_sphere(sphere<real>({0, 0.6, 0}, 0.6), grey);
    s.add_sphere(sphere<real>({2, 0.6, 0}, 0.6), grey);
    s.lights.push_back(point_light<real>({-2, 2.5, 0}, detail::light_colour(2.5, rgb(1, 0.8, 0.6), rgb(1)), falloff::inverse_square));
    s.lights.push_back(directional_light<real>({1, 0.8, 0.3}, detail::light_colour(0.35, rgb(0.7, 0.8, 1), rgb(1), rgb(0.04))));
    s.lights.push_back(area_light<real>({1.25, 2.2, -0.75}, {1.5, 0, 0}, {0, 0, 1.5}, detail::light_colour(1.0, rgb(1), rgb(1))));
    return s;
}

/// The scene called `name` for an image of the given aspect ratio (width / height).
/// Throws std::invalid_argument for an unknown name.
inline scene make_scene(const std::string& name, real aspect) {
    if (name == "gallery") return make_gallery(aspect);
    if (name == "mesh") return make_mesh_scene(aspect);
    if (name == "lights") return make_lights_scene(aspect);
    if (name == "furnace") return make_furnace(aspect, false);
    if (name == "furnace-conductor") return make_furnace(aspect, true);
    if (name == "glass-furnace") return make_glass_furnace(aspect);
    if (name == "glass") return make_glass(aspect);
    if (name == "energy") return make_energy(aspect);
    if (name == "enclosure") return make_enclosure(aspect);
    if (name == "veach") return make_veach(aspect);
    if (name == "cornell") return make_cornell(aspect);
    if (name == "openpbr") return make_openpbr(aspect);
    if (name == "openpbr-furnace") return make_openpbr_furnace(aspect);
    throw std::invalid_argument("unknown scene '" + name + "' (known: " + scene_names() + ")");
}

} // namespace tracer
