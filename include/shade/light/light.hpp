#pragma once
// The light contract: shade::light, what every light (shade's or yours) provides. The
// lights themselves live in their own headers, and shade::any_light, the closed set of
// shade's lights, in shade/light/any_light.hpp.

#include <concepts>

#include <shade/core/scalar.hpp>
#include <shade/core/types.hpp>
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

} // namespace shade
