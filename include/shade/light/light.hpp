#pragma once
// The light contracts: shade::light, what every light (shade's or yours) provides for
// the classic lighting model, and shade::emitter, what a light provides in physical units
// for Monte Carlo light transport. The lights themselves live in their own headers, and
// shade::any_light, the closed set of shade's lights, in shade/light/any_light.hpp.

#include <concepts>
#include <optional>

#include <shade/core/scalar.hpp>
#include <shade/core/types.hpp>
#include <shade/light/incident_sample.hpp>
#include <shade/light/light_sample.hpp>

namespace shade {

/// L is a light: it names its scalar type, and
///   * `l.sample(p, u)` returns the light_sample it contributes at the shaded point p,
///     for a sample pair u in [0,1)^2 (ignored by delta lights: point, spot,
///     directional); the average over u of a shader's response is the light's
///     contribution (a Monte Carlo estimate for area lights, exact for delta lights);
///   * `l.is_delta()` is true when one sample is exact (u ignored), false when the light
///     should be sampled several times (area lights).
template <class L>
concept light = has_scalar_type<L> &&
    requires(const L& l, const vec3<typename L::scalar_type>& p,
             const vec2<typename L::scalar_type>& u) {
        { l.sample(p, u) } -> std::same_as<light_sample<typename L::scalar_type>>;
        { l.is_delta() } -> std::convertible_to<bool>;
    };

/// L is an emitter: a shade::light that also answers in physical units (radiance in
/// W/(m^2 sr), densities in 1/sr; see shade::incident_sample), as a path tracer needs for
/// next-event estimation and multiple importance sampling:
///   * `l.sample_incident(p, u)`: a direction toward the light from p, its distance, the
///     radiance arriving along it and the solid-angle pdf it was drawn with (a delta light
///     says so), or nothing when the sample is worth zero;
///   * `l.pdf_incident(p, w)`: the density sample_incident(p, .) has for the unit
///     direction w (0 for delta lights and directions that miss the light);
///   * `l.incident_radiance(p, w)`: the radiance arriving at p along w from this light
///     alone (0 for delta lights): what a ray from p along w sees of it.
template <class L>
concept emitter = light<L> &&
    requires(const L& l, const vec3<typename L::scalar_type>& p,
             const vec2<typename L::scalar_type>& u) {
        { l.sample_incident(p, u) } -> std::same_as<std::optional<incident_sample<typename L::scalar_type>>>;
        { l.pdf_incident(p, p) } -> std::same_as<typename L::scalar_type>;
        { l.incident_radiance(p, p) } -> std::same_as<rgb<typename L::scalar_type>>;
    };

} // namespace shade
