#pragma once
// shade::light_bounds_of: the shade::light_bounds of each of shade's lights, which
// shade::bvh_light_sampler (shade/light/bvh_light_sampler.hpp) builds its tree from. Powers
// are luminances of the lights' RGB powers in W (Rec. 709 / sRGB weights 0.2126, 0.7152,
// 0.0722, as shade::power_light_sampler::from_rgb weighs them).

#include <cmath>
#include <concepts>
#include <type_traits>

#include <shade/core/math.hpp>
#include <shade/core/types.hpp>
#include <shade/geometry/aabb.hpp>
#include <shade/geometry/sphere.hpp>
#include <shade/geometry/triangle.hpp>
#include <shade/light/any_light.hpp>
#include <shade/light/incident_sample.hpp>
#include <shade/light/light_bounds.hpp>
#include <shade/light/triangle.hpp>

namespace shade {

namespace detail {

/// The luminance Y of an RGB power (Rec. 709 primaries: the Y row of IEC 61966-2-1's
/// RGB-to-XYZ matrix).
template <std::floating_point T>
[[nodiscard]] constexpr T power_luminance(const rgb<T>& p) noexcept {
    return T(0.2126) * p.x + T(0.7152) * p.y + T(0.0722) * p.z;
}

/// The bounds of a flat Lambertian emitter with the given box, unit normal and sides:
/// the normal with theta_o = 0 if one-sided, pi if two-sided; theta_e = pi/2.
template <std::floating_point T>
[[nodiscard]] light_bounds<T> flat_emitter_bounds(const aabb<T>& box, const rgb<T>& power,
                                                  const vec3<T>& normal, sidedness sides) noexcept {
    light_bounds<T> b;
    b.box = box;
    b.power = power_luminance(power);
    b.axis = normal;
    b.theta_o = sides == sidedness::two_sided ? pi<T> : T(0);
    b.theta_e = pi<T> / T(2);
    return b;
}

/// The bounds of a light that emits every way from the given box (theta_o = pi).
template <std::floating_point T>
[[nodiscard]] light_bounds<T> omni_bounds(const aabb<T>& box, const rgb<T>& power) noexcept {
    light_bounds<T> b;
    b.box = box;
    b.power = power_luminance(power);
    return b;
}

} // namespace detail

/// The bounds of a triangle light: its vertices' box, its power's luminance, its normal with
/// theta_o = 0 (one-sided) or pi (two-sided), theta_e = pi/2 (Lambertian).
template <std::floating_point T>
[[nodiscard]] light_bounds<T> light_bounds_of(const triangle_light<T>& l) noexcept {
    return detail::flat_emitter_bounds(bounds(l.shape()), l.power(), l.normal(), l.sides());
}

/// The bounds of any of shade's lights. Triangles, rectangles and disks: see above (a
/// disk's box is its exact one, the centre +- radius sqrt(1 - n_k^2) on axis k). Point
/// lights and spheres: their box, theta_o = pi. Spot lights: their point, the spot's axis,
/// theta_o = outer angle, theta_e = 0. Directional and environment lights:
/// light_bounds::infinite with the luminance of power(scene_radius) (see
/// shade::any_light::power for what the radius is).
template <std::floating_point T>
[[nodiscard]] light_bounds<T> light_bounds_of(const any_light<T>& light, T scene_radius) {
    return light.visit([&](const auto& l) -> light_bounds<T> {
        using L = std::decay_t<decltype(l)>;
        if constexpr (std::is_same_v<L, directional_light<T>> || std::is_same_v<L, environment_light<T>>) {
            return light_bounds<T>::infinite(detail::power_luminance(light.power(scene_radius)));
        } else if constexpr (std::is_same_v<L, triangle_light<T>>) {
            return light_bounds_of(l);
        } else if constexpr (std::is_same_v<L, area_light<T>>) {
            aabb<T> box;
            box.grow(l.corner());
            box.grow(l.corner() + l.edge_u());
            box.grow(l.corner() + l.edge_v());
            box.grow(l.corner() + l.edge_u() + l.edge_v());
            return detail::flat_emitter_bounds(box, l.power(), l.normal(), l.sides());
        } else if constexpr (std::is_same_v<L, disk_light<T>>) {
            const vec3<T>& n = l.normal();
            const vec3<T> half = l.radius() * vec3<T>(std::sqrt(std::fmax(T(0), T(1) - n.x * n.x)),
                                                      std::sqrt(std::fmax(T(0), T(1) - n.y * n.y)),
                                                      std::sqrt(std::fmax(T(0), T(1) - n.z * n.z)));
            aabb<T> box;
            box.grow(l.center() - half);
            box.grow(l.center() + half);
            return detail::flat_emitter_bounds(box, l.power(), n, l.sides());
        } else if constexpr (std::is_same_v<L, sphere_light<T>>) {
            return detail::omni_bounds(bounds(l.shape()), l.power());
        } else if constexpr (std::is_same_v<L, spot_light<T>>) {
            aabb<T> box;
            box.grow(l.position());
            light_bounds<T> b = detail::omni_bounds(box, l.power());
            b.axis = l.axis();
            b.theta_o = l.outer_angle();
            b.theta_e = T(0);
            return b;
        } else {
            static_assert(std::is_same_v<L, point_light<T>>, "light_bounds_of: a light type without bounds");
            aabb<T> box;
            box.grow(l.position());
            return detail::omni_bounds(box, l.power());
        }
    });
}

} // namespace shade
