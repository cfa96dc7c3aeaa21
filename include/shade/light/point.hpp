#pragma once
// shade::point_light: a light at a point whose light weakens with distance by a
// selectable law (shade::falloff).

#include <concepts>

#include <shade/core/error.hpp>
#include <shade/core/types.hpp>
#include <shade/light/emission.hpp>
#include <shade/light/falloff.hpp>
#include <shade/light/light_sample.hpp>

namespace shade {

/// A point light at `position`. Its sample at p has l = (position - p) / r, distance
/// r = |position - p|, ambient = intensity x ambient colour, and diffuse/specular =
/// intensity x falloff_factor(f, r) x colour.
///
/// At r = 0 (p at the light) the direction is undefined, and where the falloff overflows
/// (r below ~1e-19 in float for 1/r^2) the light would be infinite: in both cases the
/// sample carries the ambient colour only (no directional light, no Inf/NaN).
template <std::floating_point T>
class point_light {
public:
    using scalar_type = T;

    /// A point light at `position` with emission e and distance law f. Throws
    /// shade::invalid_parameter naming "position" (non-finite), "falloff" or the bad
    /// emission member.
    explicit point_light(const vec3<T>& position, const emission<T>& e = {},
                         falloff f = falloff::inverse_square)
        : position_(require_finite("position", position)), emission_(validated(e)),
          falloff_(detail::require_falloff(f)) {}

    /// The light's position.
    [[nodiscard]] const vec3<T>& position() const noexcept { return position_; }
    /// The emitted intensity and colours.
    [[nodiscard]] const emission<T>& emitted() const noexcept { return emission_; }
    /// The distance law.
    [[nodiscard]] falloff distance_falloff() const noexcept { return falloff_; }

    /// Always true: a point light is a delta light, one sample is exact.
    [[nodiscard]] static constexpr bool is_delta() noexcept { return true; }

    /// The light's sample at point p (see the class comment).
    [[nodiscard]] light_sample<T> sample(const vec3<T>& p) const noexcept {
        return detail::positional_sample(emission_, position_, falloff_, p,
                                         [](const vec3<T>&) noexcept { return T(1); });
    }

    /// As sample(p); u is ignored (shade::light interface, shared with area lights).
    [[nodiscard]] light_sample<T> sample(const vec3<T>& p, const vec2<T>& u) const noexcept {
        (void)u;
        return sample(p);
    }

private:
    vec3<T> position_;
    emission<T> emission_;
    falloff falloff_;
};

} // namespace shade
