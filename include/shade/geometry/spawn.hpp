#pragma once
// Starting a ray on a surface without hitting that surface again: the origin is moved off
// the surface along its normal by the hit point's rounding bound (hit::p_error), to the
// side the ray leaves by, and then one more ulp in each coordinate (Pharr, Jakob, Humphreys
// 2023, "Physically Based Rendering", 4th ed., sec. 6.8.6). No absolute epsilon: the
// offset scales with the coordinates, so it works for geometry near the origin and 10^5
// units away alike.
//
//   const auto h = mesh.closest(r);                       // a primitive_hit<triangle_hit<T>>
//   const ray<T> next = spawn_ray(h->hit, l);             // continue a path along l
//   const ray<T> shadow = spawn_ray_to(h->hit, light_p);  // toward a point light
//   const ray<T> between = spawn_ray_to(h->hit, other);   // toward a point on a surface
//
// spawn_ray_to's segment ends at the target (t_max = 1); toward a point on a surface (an
// area light's sample, another hit) its end is offset the same way, back toward the origin,
// so the target's own surface is not reported as an occluder.

#include <cmath>
#include <concepts>
#include <limits>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <shade/core/types.hpp>
#include <shade/geometry/hit.hpp>
#include <shade/geometry/ray.hpp>

namespace shade {

/// The origin of a ray leaving point p (of a surface with unit normal n and rounding bound
/// p_error, see shade::hit) in direction w: p + s d n with d = dot(|n|, p_error), the
/// largest distance from the surface the error allows along n, and s = +1 when w leaves on
/// the side n points to (dot(w, n) >= 0), -1 otherwise; each coordinate that moved is then
/// rounded one step further (the sum p + d n is rounded to nearest, which could give back
/// up to half an ulp). A zero p_error returns p.
template <std::floating_point T>
[[nodiscard]] inline vec3<T> offset_ray_origin(const vec3<T>& p, const vec3<T>& p_error, const vec3<T>& n,
                                               const vec3<T>& w) noexcept {
    const T d = glm::dot(glm::abs(n), p_error);
    const vec3<T> offset = glm::dot(w, n) < T(0) ? -d * n : d * n;
    vec3<T> origin = p + offset;
    for (int k = 0; k < 3; ++k) {
        if (offset[k] > T(0)) origin[k] = std::nextafter(origin[k], std::numeric_limits<T>::infinity());
        else if (offset[k] < T(0)) origin[k] = std::nextafter(origin[k], -std::numeric_limits<T>::infinity());
    }
    return origin;
}

/// A ray leaving the hit's surface along direction w (any length; not normalised here):
/// origin offset_ray_origin(h.p, h.p_error, h.n, w), t in [0, +infinity).
template <std::floating_point T>
[[nodiscard]] inline ray<T> spawn_ray(const hit<T>& h, const vec3<T>& w) noexcept {
    return ray<T>{offset_ray_origin(h.p, h.p_error, h.n, w), w};
}

/// A shadow ray from the hit's surface to the point `to` that lies on no surface (a point
/// light, a camera): origin offset as by spawn_ray, direction to - origin, t in [0, 1], so
/// t = 1 is `to`.
template <std::floating_point T>
[[nodiscard]] inline ray<T> spawn_ray_to(const hit<T>& from, const vec3<T>& to) noexcept {
    const vec3<T> origin = offset_ray_origin(from.p, from.p_error, from.n, to - from.p);
    return ray<T>{origin, to - origin, T(0), T(1)};
}

/// A shadow ray from the hit's surface to point `to` on another surface (normal to_n,
/// rounding bound to_error): both ends offset off their surfaces toward each other, t in
/// [0, 1]. Use it toward an area light's sampled point, or between two hits.
///
/// The guarantee holds for the intersector that produced to_error: the shadow ray is then
/// tested against the target's surface with that same routine, whose own rounding of t
/// to_error bounds. When the target point comes from one routine (say a light's sampler on
/// a sphere) and the scene tests the same surface with another (the scene's sphere test),
/// the second may round t by more than to_error covers and report the target's surface as
/// the occluder; decide visibility then by identity (is the first surface along
/// spawn_ray(from, to - from) the target?) rather than by an unoccluded segment.
template <std::floating_point T>
[[nodiscard]] inline ray<T> spawn_ray_to(const hit<T>& from, const vec3<T>& to, const vec3<T>& to_error,
                                         const vec3<T>& to_n) noexcept {
    const vec3<T> origin = offset_ray_origin(from.p, from.p_error, from.n, to - from.p);
    const vec3<T> end = offset_ray_origin(to, to_error, to_n, origin - to);
    return ray<T>{origin, end - origin, T(0), T(1)};
}

/// A shadow ray between two hits: spawn_ray_to(from, to.p, to.p_error, to.n).
template <std::floating_point T>
[[nodiscard]] inline ray<T> spawn_ray_to(const hit<T>& from, const hit<T>& to) noexcept {
    return spawn_ray_to(from, to.p, to.p_error, to.n);
}

} // namespace shade
