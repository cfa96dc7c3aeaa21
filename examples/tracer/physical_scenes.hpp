#pragma once
// The reference tracer's scenes in physical units, for the path integrator:
//   furnace:           a white Lambert sphere (k_d = 1) in a uniform white environment
//                      (radiance 1): every pixel is 1, whatever the number of bounces;
//   furnace-conductor: the same with a rough GGX conductor of F = 1 (single-scattering
//                      microfacets lose energy at high roughness: pixels below 1);
//   energy:            rough gold spheres (GGX alpha 0.05, 0.25, 0.5, 0.75, 1, left to
//                      right) in the same white environment: single scattering on top,
//                      compensated for multiple scattering (shade::kulla_conty) below;
//                      the top row darkens with roughness, the bottom one does not;
//   enclosure:         the camera inside a closed sphere whose inside is a Lambert of
//                      albedo 0.8 that also emits radiance 1: every pixel is
//                      1 + 0.8 + 0.8^2 + ... = 1 / (1 - 0.8) = 5;
//   veach:             four glossy plates, rough to near-mirror, lit by four spherical
//                      lights of equal power and very different sizes (Veach 1997,
//                      fig. 9.2), for comparing light sampling, BRDF sampling and MIS;
//   cornell:           a Cornell-box-like room (white floor, ceiling and back wall, red
//                      left and green right wall, Lambert) holding the square pyramid of
//                      examples/data/pyramid.obj, lit by a small spherical area light under
//                      the ceiling;
//   glass-furnace:     a smooth glass sphere behind a thin pane and a compensated rough
//                      glass sphere in the white furnace (all 1);
//   glass:             the cornell room with a rough glass pyramid, a smooth glass sphere
//                      and a thin glass pane.

#include <array>
#include <cmath>
#include <string>
#include <utility>

#include <glm/geometric.hpp>

#include <shade/brdf/aliases.hpp>
#include <shade/brdf/any_brdf.hpp>
#include <shade/brdf/lambert.hpp>
#include <shade/light/environment.hpp>
#include <shade/light/sphere.hpp>

#include "obj.hpp"
#include "scene.hpp"

namespace tracer {

namespace detail {

inline shade::pinhole_camera<real> look(vec3 position, vec3 target, real fov_degrees, real aspect) {
    return {position, target, vec3(0, 1, 0), fov_degrees * shade::pi<real> / 180, aspect};
}

/// The white furnace without its objects: radiance 1 from every direction (an
/// environment light and background), the camera 4 units from the origin looking at it.
inline scene white_furnace(std::string name, real aspect) {
    scene s;
    s.name = std::move(name);
    s.camera = look(vec3(0, 0, 4), vec3(0), 40, aspect);
    s.lights.emplace_back(shade::environment_light<real>::from_radiance(rgb(1)));
    s.background = rgb(1);
    return s;
}

} // namespace detail

/// furnace (conductor = false) or furnace-conductor (conductor = true).
inline scene make_furnace(real aspect, bool conductor) {
    scene s = detail::white_furnace(conductor ? "furnace-conductor" : "furnace", aspect);
    if (conductor)
        s.add_physical_sphere(shade::sphere<real>(vec3(0), 1), shade::make_ggx_conductor(real(0.6), rgb(1)));
    else
        s.add_physical_sphere(shade::sphere<real>(vec3(0), 1), shade::lambert<real>(rgb(1)));
    return s;
}

/// The GGX roughness of the energy scene's spheres, left to right.
inline constexpr std::array<real, 5> energy_alphas{0.05, 0.25, 0.5, 0.75, 1.0};

/// energy: see the file comment. Objects 2k (top, single scattering) and 2k + 1 (bottom,
/// compensated) have roughness energy_alphas[k].
inline scene make_energy(real aspect) {
    scene s;
    s.name = "energy";
    s.camera = detail::look(vec3(0, 0, 12), vec3(0), 16, aspect);
    s.lights.emplace_back(shade::environment_light<real>::from_radiance(rgb(1)));
    s.background = rgb(1);
    const rgb gold(1.0, 0.71, 0.29);
    for (std::size_t k = 0; k < energy_alphas.size(); ++k) {
        const real x = (real(k) - real(2)) * real(1.2);
        s.add_physical_sphere(shade::sphere<real>(vec3(x, 0.6, 0), 0.5), shade::make_ggx_conductor(energy_alphas[k], gold));
        s.add_physical_sphere(shade::sphere<real>(vec3(x, -0.6, 0), 0.5),
                              shade::make_compensated_ggx_conductor(energy_alphas[k], gold));
    }
    return s;
}

/// enclosure: see the file comment.
inline scene make_enclosure(real aspect) {
    scene s;
    s.name = "enclosure";
    s.camera = detail::look(vec3(0.5, 0.3, 1), vec3(0, 0, -3), 60, aspect);
    s.add_emitting_sphere(shade::sphere_light<real>::from_radiance(vec3(0), 4, rgb(1), shade::sidedness::two_sided),
                          shade::lambert<real>(rgb(0.8)));
    return s;
}

/// The roughness (GGX alpha) of the veach scene's plates, back (top of the image) to front
/// (bottom): from rough to near-mirror, the values of Veach's figure.
inline constexpr std::array<real, 4> veach_alphas{0.1, 0.05, 0.02, 0.005};

/// The radii of the veach scene's sphere lights, left to right (ratio 27 between the
/// largest and the smallest, as in Veach's figure).
inline constexpr std::array<real, 4> veach_light_radii{1.0 / 30, 0.1, 0.3, 0.9};

/// veach: Veach's multiple-importance-sampling test scene (Veach 1997, "Robust Monte Carlo
/// Methods for Light Transport Simulation", PhD thesis, Stanford, fig. 9.2; Veach, Guibas
/// 1995, "Optimally Combining Sampling Techniques for Monte Carlo Rendering", SIGGRAPH,
/// fig. 2), in its usual dimensions: four sphere lights on the x axis at x = -3.75,
/// -1.25, 1.25, 3.75 with the radii veach_light_radii and radiance 1 / R^2 (equal power
/// 4 pi^2 W each); below and in front of them four plates, 8 wide (x in [-4, 4]) and 1
/// deep, stepping down toward the camera, each tilted so that it mirrors the centre of
/// the row of lights into the camera, so every plate reflects all four lights; GGX
/// conductors (f0 = 0.7) with the roughness veach_alphas. The camera at (0, 6, 27.5) looks
/// at (0, -1.5, 2.5) with a horizontal field of view of 25 degrees. Nothing else: the
/// background is black. Objects 0-3 are the plates (back to front), 4-7 the lights.
inline scene make_veach(real aspect) {
    scene s;
    s.name = "veach";
    const vec3 eye(0, 6, 27.5);
    const real tan_half_x = std::tan(real(12.5) * shade::pi<real> / 180);
    const real fov_y = 2 * std::atan(tan_half_x / aspect);
    s.camera = shade::pinhole_camera<real>(eye, vec3(0, -1.5, 2.5), vec3(0, 1, 0), fov_y, aspect);
    s.background = rgb(0);
    // The plates' centres, back to front; each plate's normal halves the angle between the
    // directions to the eye and to the centre of the lights (the origin), so that its
    // mirror direction for the eye passes through the row of lights.
    const std::array<vec3, 4> centres{vec3(0, -2.395, -0.135), vec3(0, -3.063, 0.923), vec3(0, -3.582, 2.223),
                                      vec3(0, -3.908, 3.574)};
    for (std::size_t i = 0; i < 4; ++i) {
        const vec3 c = centres[i];
        const vec3 n = glm::normalize(glm::normalize(eye - c) + glm::normalize(vec3(0) - c));
        const vec3 across(1, 0, 0);
        const vec3 along = glm::normalize(glm::cross(n, across)); // in the plate, across x
        mesh m;
        const real half_x = 4;
        const real half_depth = 0.5;
        for (const real sx : {-1.0, 1.0})
            for (const real sy : {-1.0, 1.0}) {
                m.positions.push_back(c + (sx * half_x) * across + (sy * half_depth) * along);
                m.normals.push_back(n);
            }
        // Corners 0 (-,-), 1 (-,+), 2 (+,-), 3 (+,+): counter-clockwise seen along -n.
        m.indices = {0, 2, 3, 0, 3, 1};
        s.add_physical_mesh(std::move(m), shade::make_ggx_conductor(veach_alphas[i], rgb(0.7)));
    }
    // Equal power: a sphere of radius R and radiance L emits 4 pi^2 R^2 L, so L = 1 / R^2.
    for (std::size_t i = 0; i < 4; ++i) {
        const real R = veach_light_radii[i];
        const vec3 centre(-3.75 + 2.5 * real(i), 0, 0);
        s.add_emitting_sphere(shade::sphere_light<real>::from_radiance(centre, R, rgb(1 / (R * R))), std::nullopt);
    }
    return s;
}

namespace detail {

/// The parallelogram corner, corner + a, corner + a + b, corner + b as two triangles whose
/// normal is normalize(cross(a, b)).
inline mesh quad(vec3 corner, vec3 a, vec3 b) {
    mesh m;
    const vec3 n = glm::normalize(glm::cross(a, b));
    m.positions = {corner, corner + a, corner + a + b, corner + b};
    m.normals.assign(4, n);
    m.indices = {0, 1, 2, 0, 2, 3};
    return m;
}

} // namespace detail

/// The OBJ file the cornell scene places in its room.
inline std::string cornell_mesh_path() { return SHADE_EXAMPLES_DATA_DIR "/pyramid.obj"; }

namespace detail {

/// The cornell room without its pyramid: floor, ceiling, back wall (white), left (red) and
/// right (green) wall, Lambert, then the sphere light under the ceiling (see make_cornell).
inline scene cornell_room(std::string name, real aspect) {
    using L = shade::lambert<real>;
    scene s;
    s.name = std::move(name);
    s.camera = look(vec3(0, 1, 3.6), vec3(0, 1, 0), 38, aspect);
    s.background = rgb(0);
    const rgb white(0.75), red(0.63, 0.065, 0.05), green(0.14, 0.45, 0.091);
    s.add_physical_mesh(quad(vec3(-1, 0, -1), vec3(0, 0, 2), vec3(2, 0, 0)), L(white)); // floor
    s.add_physical_mesh(quad(vec3(-1, 2, -1), vec3(2, 0, 0), vec3(0, 0, 2)), L(white)); // ceiling
    s.add_physical_mesh(quad(vec3(-1, 0, -1), vec3(2, 0, 0), vec3(0, 2, 0)), L(white)); // back
    s.add_physical_mesh(quad(vec3(-1, 0, -1), vec3(0, 2, 0), vec3(0, 0, 2)), L(red));   // left
    s.add_physical_mesh(quad(vec3(1, 0, -1), vec3(0, 0, 2), vec3(0, 2, 0)), L(green));  // right
    return s;
}

/// The area light of the cornell room: a sphere of radius 0.15 and radiance 50 under the
/// ceiling, which gives the floor below it an irradiance of about pi 50 (0.15 / 1.75)^2 ~ 1.2.
inline void add_cornell_light(scene& s) {
    s.add_emitting_sphere(shade::sphere_light<real>::from_radiance(vec3(0, 1.75, 0), 0.15, rgb(50)), std::nullopt);
}

/// The pyramid of cornell_mesh_path() (unit base on y = 0, apex at height 1) scaled by 0.9,
/// turned 30 degrees about y, moved back by 0.2 and up by `lift`. Throws as load_obj.
inline mesh cornell_pyramid(real lift) {
    mesh pyramid = load_obj(cornell_mesh_path());
    const real angle = shade::pi<real> / 6, c = std::cos(angle), sn = std::sin(angle);
    const auto turn = [&](const vec3& p) { return vec3(c * p.x + sn * p.z, p.y, -sn * p.x + c * p.z); };
    for (vec3& p : pyramid.positions) p = turn(real(0.9) * p) + vec3(0, lift, -0.2);
    for (vec3& n : pyramid.normals) n = turn(n);
    return pyramid;
}

} // namespace detail

/// cornell: see the file comment. The room is x in [-1, 1], y in [0, 2], z in [-1, 1],
/// open toward the camera (+z); every wall's normal points into the room. Objects 0-4 are
/// the walls, 5 the pyramid, 6 the light. Throws std::runtime_error naming the OBJ file
/// when it cannot be loaded.
inline scene make_cornell(real aspect) {
    scene s = detail::cornell_room("cornell", aspect);
    s.add_physical_mesh(detail::cornell_pyramid(0), shade::lambert<real>(rgb(0.75, 0.7, 0.6)));
    detail::add_cornell_light(s);
    return s;
}

/// The GGX roughness (alpha) of the glass-furnace scene's compensated rough sphere.
inline constexpr real glass_furnace_alpha = 0.5;

/// glass-furnace: in the white furnace, a sphere of smooth glass (eta 1.5, radius 0.7, on
/// the left) with a thin glass pane (eta 1.5) in front of its left half, and a sphere of
/// compensated rough glass (shade::compensated_rough_dielectric over GGX alpha
/// glass_furnace_alpha, eta 1.5, radius 0.7, on the right). Lossless interfaces neither
/// absorb nor emit, so all three are invisible: every pixel 1 (the (eta_v / eta_l)^2 of
/// radiance through each refraction cancels between entering and leaving; the pane
/// reflects R' and transmits 1 - R'; the rough sphere's multiple-scattering lobe returns
/// what its microfacets lose, up to the error of the compensation's albedo tables).
/// Objects 0 the smooth sphere, 1 the pane, 2 the rough sphere.
inline scene make_glass_furnace(real aspect) {
    scene s = detail::white_furnace("glass-furnace", aspect);
    s.add_glass_sphere(shade::sphere<real>(vec3(-0.8, 0, 0), 0.7), 1.5);
    s.add_glass_pane(detail::quad(vec3(-1.1, -0.6, 1.2), vec3(0.55, 0, 0.3), vec3(0, 1.2, 0)), 1.5);
    s.add_rough_glass_sphere(shade::sphere<real>(vec3(0.8, 0, 0), 0.7), glass_furnace_alpha, 1.5,
                             rough_glass_model::compensated);
    return s;
}

/// The GGX roughness (alpha) of the glass scene's rough pyramid.
inline constexpr real glass_pyramid_alpha = 0.2;

/// glass: the cornell room with its sphere light, its pyramid made of rough glass
/// (shade::rough_dielectric over GGX alpha glass_pyramid_alpha, eta 1.5; a closed mesh
/// whose normals point out), a sphere of smooth glass (eta 1.5) on the floor in front of
/// it and a thin glass pane (eta 1.5) standing across the back left; path integrator only
/// (the caustics under the smooth sphere come from BSDF-sampled paths alone, so they need
/// many samples). The pyramid stands 0.002 above the floor: a base on the floor's plane
/// would tie with it at every hit, and which surface a ray then meets (glass or floor)
/// would be decided by rounding. Objects 0-4 are the walls, 5 the pyramid, 6 the light, 7
/// the sphere, 8 the pane. Throws as make_cornell.
inline scene make_glass(real aspect) {
    scene s = detail::cornell_room("glass", aspect);
    s.add_rough_glass_mesh(detail::cornell_pyramid(0.002), glass_pyramid_alpha, 1.5);
    detail::add_cornell_light(s);
    s.add_glass_sphere(shade::sphere<real>(vec3(0.5, 0.35, 0.35), 0.35), 1.5);
    s.add_glass_pane(detail::quad(vec3(-0.9, 0, -0.3), vec3(0.6, 0, -0.4), vec3(0, 1.2, 0)), 1.5);
    return s;
}

} // namespace tracer
