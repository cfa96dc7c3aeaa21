#pragma once
// shade::light_bounds: what a light tree knows of one light or of a cluster of lights (where
// it is, how much it emits, toward which directions), the union of two such bounds, and the
// importance of a bounded cluster for a shading point. Used by shade::bvh_light_sampler
// (shade/light/bvh_light_sampler.hpp); shade/light/light_bounds_of.hpp makes them from
// shade's lights.
//
// Conty Estevez, Kulla 2018, "Importance Sampling of Many Lights with Adaptive Tree
// Splitting", Proc. ACM Comput. Graph. Interact. Tech. 1(2) (HPG 2018): a cluster is bounded
// by a box, its total power Phi and an orientation cone (axis, theta_o, theta_e): every
// emitter's normal lies within theta_o of the axis, and each emits only within theta_e of its
// normal (pi/2 for a Lambertian surface). Angles are kept as angles (not cosines) because the
// cone union and the importance add and subtract them.

#include <cmath>
#include <concepts>
#include <limits>

#include <glm/geometric.hpp>

#include <shade/core/math.hpp>
#include <shade/core/types.hpp>
#include <shade/geometry/aabb.hpp>
#include <shade/light/sample_context.hpp>

namespace shade {

/// The bounds of a light or of a cluster of lights. For a light at a finite place:
/// `box` holds every emitting point, `power` is its power as one number (e.g. the luminance of
/// its RGB power in W), and every direction it emits into lies within theta_o + theta_e of
/// `axis` (theta_o bounds the spread of its normals around the axis, theta_e the spread of the
/// emission around each normal):
///   one-sided triangle, rectangle or disk: axis = normal, theta_o = 0,  theta_e = pi/2;
///   two-sided one:                         axis = normal, theta_o = pi, theta_e = pi/2;
///   point light or sphere:                 any axis,      theta_o = pi, theta_e = pi/2;
///   spot light:                            axis = its axis, theta_o = outer angle,
///                                          theta_e = 0 (it is a point: its cone is
///                                          the set of directions it lights).
/// A light at infinity (directional, environment) has no place: `at_infinity` is then true and
/// only `power` counts (shade::bvh_light_sampler keeps such lights out of its tree).
template <std::floating_point T>
struct light_bounds {
    using scalar_type = T;

    aabb<T> box{};             ///< every emitting point (empty for a light at infinity)
    T power = T(0);            ///< Phi, >= 0, on any scale common to all lights
    vec3<T> axis{0, 0, 1};     ///< unit axis of the orientation cone
    T theta_o = pi<T>;         ///< normals within theta_o of axis, in [0, pi]
    T theta_e = pi<T> / T(2);  ///< emission within theta_e of each normal, in [0, pi/2]
    bool at_infinity = false;  ///< a directional or environment light: no box, no cone

    /// The bounds of a light at infinity of the given power.
    [[nodiscard]] static light_bounds infinite(T phi) noexcept {
        light_bounds b;
        b.power = phi;
        b.at_infinity = true;
        return b;
    }
};

namespace detail {

/// A unit vector perpendicular to the unit vector a (any one).
template <std::floating_point T>
[[nodiscard]] vec3<T> any_perpendicular(const vec3<T>& a) noexcept {
    // Cross with the coordinate axis least aligned with a, so the product is not tiny.
    const vec3<T> e = std::fabs(a.x) < T(0.5) ? vec3<T>(1, 0, 0) : vec3<T>(0, 1, 0);
    return glm::normalize(glm::cross(a, e));
}

/// acos(c) with c clamped into [-1, 1] (a dot product of unit vectors may round past 1).
template <std::floating_point T>
[[nodiscard]] T safe_acos(T c) noexcept {
    return std::acos(c < T(-1) ? T(-1) : (c > T(1) ? T(1) : c));
}

/// The half-angle theta_u of a cone from p around c - p (c the box's centre) that holds
/// the box: the largest angle to a corner's direction, or pi when p is in the box or a
/// corner is at 90 degrees or more (see importance()).
template <std::floating_point T>
[[nodiscard]] T box_half_angle(const aabb<T>& box, const vec3<T>& p, const vec3<T>& c) noexcept {
    if (box.contains(p)) return pi<T>;
    const vec3<T> w = glm::normalize(c - p);
    T cos_u = T(1);
    for (int corner = 0; corner < 8; ++corner) {
        const vec3<T> x((corner & 1) ? box.hi.x : box.lo.x, (corner & 2) ? box.hi.y : box.lo.y,
                        (corner & 4) ? box.hi.z : box.lo.z);
        const T cos_corner = glm::dot(w, glm::normalize(x - p));
        cos_u = cos_corner < cos_u ? cos_corner : cos_u;
    }
    if (!(cos_u > T(0))) return pi<T>; // also NaN from a p at infinity
    return safe_acos(cos_u);
}

} // namespace detail

/// The union of two clusters' bounds: the box holding both boxes, the summed power, and the
/// cone of Conty Estevez and Kulla's union of orientation bounds (2018, their section on
/// orientation bounds; pbrt-v4's Union of two DirectionCones is the same): with a the
/// bounds of the wider normal cone and theta_d the angle between the axes, a's cone is kept
/// when it already holds b's (theta_d + theta_o(b) <= theta_o(a)); otherwise the new cone
/// spans both, theta_o = (theta_o(a) + theta_d + theta_o(b)) / 2 (pi when that reaches pi),
/// its axis a's rotated toward b's by theta_o - theta_o(a). theta_e is the larger of the
/// two. Neither may be at infinity; a side of power 0 still widens the box and the cone (a
/// tree built by shade::bvh_light_sampler has none: it drops lights of power 0).
template <std::floating_point T>
[[nodiscard]] light_bounds<T> merge(const light_bounds<T>& x, const light_bounds<T>& y) noexcept {
    const bool x_wider = x.theta_o >= y.theta_o;
    const light_bounds<T>& a = x_wider ? x : y;
    const light_bounds<T>& b = x_wider ? y : x;
    light_bounds<T> u;
    u.box = a.box;
    u.box.grow(b.box);
    u.power = a.power + b.power;
    u.theta_e = a.theta_e > b.theta_e ? a.theta_e : b.theta_e;
    u.axis = a.axis;
    u.theta_o = a.theta_o;
    const T cos_theta_d = glm::dot(a.axis, b.axis);
    const T theta_d = detail::safe_acos(cos_theta_d);
    if (theta_d + b.theta_o <= a.theta_o) return u;
    const T theta_o = (a.theta_o + theta_d + b.theta_o) / T(2);
    if (theta_o >= pi<T>) {
        u.theta_o = pi<T>;
        return u;
    }
    // Rotate a's axis by theta_r toward b's within their common plane; the in-plane
    // direction b - (a.b) a vanishes for opposite axes, where any perpendicular serves.
    const T theta_r = theta_o - a.theta_o;
    const vec3<T> toward = b.axis - cos_theta_d * a.axis;
    const T toward_length = glm::length(toward);
    const vec3<T> t = toward_length > T(0) ? toward / toward_length : detail::any_perpendicular(a.axis);
    u.axis = glm::normalize(std::cos(theta_r) * a.axis + std::sin(theta_r) * t);
    u.theta_o = theta_o;
    return u;
}

/// The importance of the cluster bounded by `b` for the shading point ctx.p with geometric
/// normal ctx.n (zero: no surface): an estimate, up to a constant, of the irradiance the
/// cluster sends to the point, which is 0 only where no light of the cluster can reach the
/// point from above its surface (so a sampler that skips such clusters loses nothing).
///
/// Conty Estevez, Kulla 2018, the cluster importance measure:
///   I = Phi cos(theta') max(0, cos(theta'_i)) / d^2,  0 when theta' > theta_e,
/// where d is the distance from p to the box's centre c, theta_u the half-angle of a cone
/// around c - p that holds the box as seen from p, theta the angle between the cone's axis
/// and p - c, theta' = max(0, theta - theta_o - theta_u) the smallest angle any emitter's
/// normal can make with the direction to p, and theta'_i = max(0, theta_i - theta_u) the
/// smallest angle the direction to any emitter can make with n (theta_i measured to c). The
/// cosine factor of the receiver is left out when n is zero.
///
/// theta_u is the largest angle between c - p and the direction from p to a corner of the
/// box (pi for p in the box, or when a corner is 90 degrees or more away): the directions to
/// the box's points are the cone spanned by the corners' directions, and a circular cone of
/// half-angle <= pi/2 that holds the corners' directions is convex, so it holds them all.
/// The paper and pbrt-v4 bound the box by its bounding sphere instead (asin(r / d)), which
/// for a flat cluster of lights (a ceiling, a floor) seen from close by is pi even where the
/// lights cannot reach.
///
/// d^2 is raised to at least r^2 / 3, r the half-diagonal of the box, as pbrt-v4's
/// BVHLightSampler raises it by the box's extent (Pharr, Jakob, Humphreys 2023, "Physically
/// Based Rendering", 4th ed., sec. 12.6.3): near the centre 1 / |p - c|^2 grows without
/// bound, while the cluster's lights are spread around it. r^2 / 3 is the effective squared
/// distance at the centre of lights spread evenly through a ball of radius r (the mean of
/// 1 / |x|^2 over the ball is 3 / r^2). pbrt-v4's max(d^2, |diagonal| / 2) mixes a length
/// with an area, so its effect changes with the scene's units; this floor does not. A floor
/// much above r^2 / 3 underrates clusters seen from close by. The result is capped at a
/// quarter of T's largest value, so that the sum of two siblings' importances stays finite
/// (p on a point light gives Phi / 0).
template <std::floating_point T>
[[nodiscard]] T importance(const light_bounds<T>& b, const light_sample_context<T>& ctx) noexcept {
    if (!(b.power > T(0)) || b.at_infinity || b.box.empty()) return T(0);
    const vec3<T> c = b.box.center();
    const T r2 = T(0.25) * glm::dot(b.box.hi - b.box.lo, b.box.hi - b.box.lo);
    const vec3<T> to_p = ctx.p - c;
    const T dist2 = glm::dot(to_p, to_p);
    const T d2 = dist2 > r2 / T(3) ? dist2 : r2 / T(3);
    const T theta_u = detail::box_half_angle(b.box, ctx.p, c);
    // Emitter side: theta between the axis and the direction from c to p.
    const T dist = std::sqrt(dist2);
    const T cos_theta = dist > T(0) ? glm::dot(b.axis, to_p) / dist : T(1);
    const T theta = detail::safe_acos(cos_theta);
    const T gap = theta - b.theta_o - theta_u;
    const T theta_p = gap > T(0) ? gap : T(0);
    if (theta_p > b.theta_e) return T(0); // theta_e <= pi/2: cos(theta') >= 0 below
    T result = b.power * std::cos(theta_p);
    // Receiver side: theta_i between n and the direction from p to c.
    if (ctx.n != vec3<T>(0)) {
        const T cos_theta_i = dist > T(0) ? -glm::dot(ctx.n, to_p) / dist : T(1);
        const T gap_i = detail::safe_acos(cos_theta_i) - theta_u;
        const T cos_theta_ip = gap_i > T(0) ? std::cos(gap_i) : T(1);
        if (!(cos_theta_ip > T(0))) return T(0);
        result *= cos_theta_ip;
    }
    result /= d2;
    constexpr T cap = std::numeric_limits<T>::max() / T(4);
    if (!(result > T(0))) return T(0); // also a NaN from a NaN point
    return result < cap ? result : cap;
}

} // namespace shade
