#pragma once
// The direction pairs the pointwise property checks evaluate a model on: seeded random pairs
// over the upper hemisphere plus the configurations where models typically break, and the
// same placed on both sides of the surface for a BSDF.

#include <cmath>
#include <concepts>
#include <cstdint>
#include <vector>

#include <glm/geometric.hpp>

#include <shade/core/random.hpp>
#include <shade/core/sampling.hpp>
#include <shade/core/surface_point.hpp>

namespace shade::check {

/// A pair of unit directions in world space.
template <std::floating_point T>
struct direction_pair {
    vec3<T> l;
    vec3<T> v;
};

/// Returns `count` pairs of upper-hemisphere directions around at.shading (all with
/// n·w > 0), deterministic for a given seed. The first pairs are the hard cases, in the
/// local frame: l = v = n; l = v near grazing; l = n with v near grazing (both orders);
/// mirror pairs (h parallel to n) at several angles; near-opposite azimuths at grazing.
/// "Near grazing" means cos(theta) = 1e-4 (float) or 1e-7 (double): above the horizon by
/// a margin the scalar type can represent after normalisation. The rest are uniformly
/// distributed over the hemisphere (independently for l and v).
template <std::floating_point T>
std::vector<direction_pair<T>> hemisphere_pairs(const surface_point<T>& at, std::size_t count,
                                                std::uint64_t seed) {
    const T graze = sizeof(T) <= 4 ? T(1e-4) : T(1e-7);
    const T sin_graze = std::sqrt(T(1) - graze * graze);
    const vec3<T> n_local(0, 0, 1);
    const auto local = [&](T cos_theta, T phi) {
        const T s = std::sqrt(T(1) - cos_theta * cos_theta);
        return vec3<T>(s * std::cos(phi), s * std::sin(phi), cos_theta);
    };
    std::vector<direction_pair<T>> local_pairs = {
        {n_local, n_local},
        {vec3<T>(sin_graze, 0, graze), vec3<T>(sin_graze, 0, graze)},
        {n_local, vec3<T>(sin_graze, 0, graze)},
        {vec3<T>(0, sin_graze, graze), n_local},
        {vec3<T>(sin_graze, 0, graze), vec3<T>(-sin_graze, 0, graze)},
        {vec3<T>(sin_graze, 0, graze), local(T(0.9), T(1))},
    };
    // Mirror configurations: v is l reflected about n, so h is parallel to n.
    for (const T cos_theta : {T(0.99), T(0.7), T(0.3), T(0.05)}) {
        for (const T phi : {T(0), T(1.2), T(2.5)}) {
            const vec3<T> l = local(cos_theta, phi);
            local_pairs.push_back({l, vec3<T>(-l.x, -l.y, l.z)});
        }
    }
    rng random(seed);
    while (local_pairs.size() < count) {
        const vec2<T> ul(random.uniform<T>(), random.uniform<T>());
        const vec2<T> uv(random.uniform<T>(), random.uniform<T>());
        vec3<T> l = square_to_uniform_hemisphere(ul);
        vec3<T> v = square_to_uniform_hemisphere(uv);
        // z = 0 exactly (u.x = 0) is on the horizon, not above it: nudge it up.
        if (!(l.z > T(0))) l = glm::normalize(vec3<T>(l.x, l.y, graze));
        if (!(v.z > T(0))) v = glm::normalize(vec3<T>(v.x, v.y, graze));
        local_pairs.push_back({l, v});
    }
    local_pairs.resize(count);
    std::vector<direction_pair<T>> world;
    world.reserve(count);
    for (const auto& p : local_pairs)
        world.push_back({glm::normalize(at.shading.to_world(p.l)),
                         glm::normalize(at.shading.to_world(p.v))});
    return world;
}

/// Returns `count` pairs of unit directions over the whole sphere around at.shading: the
/// pairs of hemisphere_pairs (hard cases first), each placed in turn on the four
/// combinations of sides (l and v outside; l inside; v inside; both inside) by negating
/// the local z of l, of v or of both, so that reflection from outside, transmission both
/// ways and reflection from inside are tried equally often. Deterministic for a seed.
template <std::floating_point T>
std::vector<direction_pair<T>> sphere_pairs(const surface_point<T>& at, std::size_t count, std::uint64_t seed) {
    const std::vector<direction_pair<T>> upper = hemisphere_pairs(at, (count + 3) / 4, seed);
    const vec3<T> n = at.n();
    // w mirrored through the tangent plane: its local z negated.
    const auto below = [&](const vec3<T>& w) { return w - T(2) * glm::dot(w, n) * n; };
    std::vector<direction_pair<T>> out;
    out.reserve(count);
    for (const auto& p : upper) {
        out.push_back(p);
        out.push_back({below(p.l), p.v});
        out.push_back({p.l, below(p.v)});
        out.push_back({below(p.l), below(p.v)});
    }
    if (out.size() > count) out.resize(count);
    return out;
}

} // namespace shade::check
