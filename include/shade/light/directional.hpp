#pragma once
// shade::directional_light: a light infinitely far away (the sun), same direction everywhere.

#include <concepts>

#include <shade/core/error.hpp>
#include <shade/core/types.hpp>
#include <shade/light/emission.hpp>
#include <shade/light/light_sample.hpp>

namespace shade {

/// A directional light: every shaded point receives light from the same unit direction,
/// with no falloff. Its sample has l = direction(), distance = +inf, ambient = intensity x
/// ambient colour and diffuse/specular = intensity x colour.
template <std::floating_point T>
class directional_light {
public:
    using scalar_type = T;

    /// A light shining from `direction` (pointing from the scene TOWARD the light; any
    /// finite non-zero length, normalised here) with emission e. Throws
    /// shade::invalid_parameter naming "direction" (zero or non-finite) or the bad
    /// emission member (see shade::validated).
    explicit directional_light(const vec3<T>& direction, const emission<T>& e = {})
        : direction_(require_direction("direction", direction)), emission_(validated(e)) {}

    /// The unit direction toward the light.
    [[nodiscard]] const vec3<T>& direction() const noexcept { return direction_; }
    /// The emitted intensity and colours.
    [[nodiscard]] const emission<T>& emitted() const noexcept { return emission_; }

    /// Always true: a directional light is a delta light, one sample is exact.
    [[nodiscard]] static constexpr bool is_delta() noexcept { return true; }

    /// The light's sample at point p (p is not used: the light is the same everywhere).
    [[nodiscard]] light_sample<T> sample(const vec3<T>& p) const noexcept {
        (void)p;
        return detail::make_sample(emission_, direction_, infinity<T>, T(1));
    }

    /// As sample(p); u is ignored (shade::light interface, shared with area lights).
    [[nodiscard]] light_sample<T> sample(const vec3<T>& p, const vec2<T>& u) const noexcept {
        (void)u;
        return sample(p);
    }

private:
    vec3<T> direction_;
    emission<T> emission_;
};

} // namespace shade
