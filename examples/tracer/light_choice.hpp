#pragma once
// How the path integrator chooses the light it samples at a vertex: uniformly, in
// proportion to power, or by the light BVH (shade::bvh_light_sampler, which weighs each
// light by what it can send to the shading point). One light_chooser is built per render
// and shared by every path.

#include <cmath>
#include <optional>
#include <span>
#include <variant>
#include <vector>

#include <shade/geometry/aabb.hpp>
#include <shade/light/bvh_light_sampler.hpp>
#include <shade/light/environment_map.hpp>
#include <shade/light/light_bounds_of.hpp>
#include <shade/light/light_sampler.hpp>
#include <shade/light/sample_context.hpp>

#include "scene.hpp"

namespace tracer {

/// The light-selection strategies of the path integrator.
///   uniform: every light with probability 1 / N;
///   power:   in proportion to emitted power (shade::power_light_sampler);
///   bvh:     the light BVH (shade::bvh_light_sampler; Conty Estevez, Kulla 2018), which
///            also weighs distance and orientation at the shading point (the default).
enum class light_selection { uniform, power, bvh };

namespace detail {

/// The radius of a sphere around the scene's bounded objects (spheres and meshes; planes
/// are infinite and left out), at least 1: what the power of lights at infinity is measured
/// through (shade::any_light::power).
inline real scene_radius(const scene& s) {
    shade::aabb<real> box;
    for (const object& o : s.objects) {
        if (o.sphere) {
            box.grow(o.sphere->center() - vec3(o.sphere->radius()));
            box.grow(o.sphere->center() + vec3(o.sphere->radius()));
        }
        if (o.mesh)
            for (const vec3& p : o.mesh->positions) box.grow(p);
    }
    if (box.empty()) return 1;
    return std::max(real(1), real(0.5) * glm::length(box.hi - box.lo));
}

} // namespace detail

/// The scene's lights (scene::lights, then the environment map as index lights.size() when
/// there is one) with one selection strategy. sample() and probability() agree: the
/// probability of the index sample() returns is probability(ctx, index).
class light_chooser {
public:
    /// The chooser of the given strategy over s's lights. Throws shade::invalid_parameter
    /// (from the samplers) for lights of negative or non-finite power.
    light_chooser(const scene& s, light_selection strategy) {
        const std::size_t count = s.lights.size() + (s.environment_map ? 1 : 0);
        if (strategy == light_selection::uniform) {
            sampler_.emplace<shade::uniform_light_sampler<real>>(count);
            return;
        }
        const real radius = detail::scene_radius(s);
        if (strategy == light_selection::power) {
            std::vector<rgb> powers;
            powers.reserve(count);
            for (const auto& l : s.lights) powers.push_back(l.power(radius));
            if (s.environment_map) powers.push_back(s.environment_map->power(radius));
            sampler_ = shade::power_light_sampler<real>::from_rgb(std::span<const rgb>(powers));
            return;
        }
        std::vector<shade::light_bounds<real>> bounds;
        bounds.reserve(count);
        for (const auto& l : s.lights) bounds.push_back(shade::light_bounds_of(l, radius));
        if (s.environment_map)
            bounds.push_back(
                shade::light_bounds<real>::infinite(shade::detail::power_luminance(s.environment_map->power(radius))));
        sampler_.emplace<shade::bvh_light_sampler<real>>(std::span<const shade::light_bounds<real>>(bounds));
    }

    /// A light for the shading point ctx from u in [0, 1), with its probability; nothing when
    /// no light can be chosen (no lights, or the light BVH finds none that can reach ctx.p).
    [[nodiscard]] std::optional<shade::light_choice<real>> sample(const shade::light_sample_context<real>& ctx,
                                                                  real u) const {
        return std::visit(
            [&](const auto& s) -> std::optional<shade::light_choice<real>> {
                if constexpr (requires { s.sample(ctx, u); })
                    return s.sample(ctx, u);
                else
                    return s.sample(u);
            },
            sampler_);
    }

    /// The probability that sample(ctx, .) chooses light i.
    [[nodiscard]] real probability(const shade::light_sample_context<real>& ctx, std::size_t i) const {
        return std::visit(
            [&](const auto& s) -> real {
                if constexpr (requires { s.probability(ctx, i); })
                    return s.probability(ctx, i);
                else
                    return s.probability(i);
            },
            sampler_);
    }

private:
    std::variant<shade::uniform_light_sampler<real>, shade::power_light_sampler<real>, shade::bvh_light_sampler<real>>
        sampler_{shade::uniform_light_sampler<real>(0)};
};

} // namespace tracer
