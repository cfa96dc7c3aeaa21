#pragma once
// The light contracts: shade::emitter, what a light provides in physical units for Monte
// Carlo light transport (the primary contract: shade's lights and yours), and shade::light,
// what the classic lighting model (shade::lit, shade::sum_over_lights) needs. Every
// shade light is both; an emitter of yours gets the classic mode from
// shade::classic_light (shade/light/classic_light.hpp). The lights themselves live in
// their own headers, and shade::any_light, the closed set of shade's lights, in
// shade/light/any_light.hpp.

#include <concepts>
#include <optional>

#include <shade/core/scalar.hpp>
#include <shade/core/types.hpp>
#include <shade/light/incident_sample.hpp>
#include <shade/light/light_sample.hpp>
#include <shade/light/sample_context.hpp>

namespace shade {

/// L is an emitter: a light in physical units (radiance in W/(m^2 sr), densities in 1/sr,
/// power in W; see shade::incident_sample), as a path tracer needs for next-event
/// estimation and multiple importance sampling. It names its scalar type T, and for a
/// point p, a shade::light_sample_context ctx (p with its surface), a sample pair u in
/// [0,1)^2, a unit direction w and a scene radius r >= 0:
///   * `l.sample_incident(p, u)`: a direction toward the light from p, its distance, the
///     radiance arriving along it and the solid-angle pdf it was drawn with (a delta light
///     says so, and ignores u), or nothing when the sample is worth zero;
///   * `l.sample_incident(ctx, u)`: the same for a point on a surface; a light may use the
///     surface to sample better (the constant environment samples the hemisphere above
///     ctx.n), or sample as for ctx.p;
///   * `l.pdf_incident(p, w)` and `l.pdf_incident(ctx, w)`: the density the matching
///     sample_incident has for w (0 for delta lights and directions that miss the light);
///   * `l.incident_radiance(p, w)`: the radiance arriving at p along w from this light
///     alone (0 for delta lights): what a ray from p along w sees of it;
///   * `l.is_delta()`: true when the light has a single direction per point (point, spot,
///     directional): one sample is exact, and no other strategy can hit it;
///   * `l.power(r)`: the radiant power in W, RGB; a light at infinity (directional,
///     environment) has no finite power of its own and gives what it sends into a scene
///     that fits in a sphere of radius r; every other light ignores r. shade's lights
///     throw shade::invalid_parameter naming "scene_radius" for a negative or non-finite r.
/// The classic colours (shade::light) are not part of it: shade::classic_light gives any
/// emitter the classic mode.
template <class L>
concept emitter = has_scalar_type<L> &&
    requires(const L& l, const vec3<typename L::scalar_type>& p, const vec2<typename L::scalar_type>& u,
             const light_sample_context<typename L::scalar_type>& ctx, typename L::scalar_type r) {
        { l.sample_incident(p, u) } -> std::same_as<std::optional<incident_sample<typename L::scalar_type>>>;
        { l.sample_incident(ctx, u) } -> std::same_as<std::optional<incident_sample<typename L::scalar_type>>>;
        { l.pdf_incident(p, p) } -> std::same_as<typename L::scalar_type>;
        { l.pdf_incident(ctx, p) } -> std::same_as<typename L::scalar_type>;
        { l.incident_radiance(p, p) } -> std::same_as<rgb<typename L::scalar_type>>;
        { l.is_delta() } -> std::convertible_to<bool>;
        { l.power(r) } -> std::same_as<rgb<typename L::scalar_type>>;
    };

/// L is a light for the classic lighting model: it names its scalar type, and
///   * `l.sample(p, u)` returns the light_sample it contributes at the shaded point p,
///     for a sample pair u in [0,1)^2 (ignored by delta lights: point, spot,
///     directional); the average over u of a shader's response is the light's
///     contribution (a Monte Carlo estimate for area lights, exact for delta lights);
///   * `l.is_delta()` is true when one sample is exact (u ignored), false when the light
///     should be sampled several times (area lights).
/// Every shade light is one (its classic colours are its shade::emission);
/// shade::classic_light<E> makes one of any shade::emitter E.
template <class L>
concept light = has_scalar_type<L> &&
    requires(const L& l, const vec3<typename L::scalar_type>& p,
             const vec2<typename L::scalar_type>& u) {
        { l.sample(p, u) } -> std::same_as<light_sample<typename L::scalar_type>>;
        { l.is_delta() } -> std::convertible_to<bool>;
    };

} // namespace shade
