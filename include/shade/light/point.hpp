#pragma once
// shade::point_light and shade::falloff: a light at a point whose light weakens with
// distance by a selectable law.

#include <concepts>
#include <string>

#include <shade/core/error.hpp>
#include <shade/core/math.hpp>
#include <shade/core/types.hpp>
#include <shade/light/emission.hpp>
#include <shade/light/light_sample.hpp>

namespace shade {

/// How a positional light's diffuse and specular colours decrease with the distance r from
/// the light. The reference distance is 1 (one world unit): at r = 1 every law gives 1, so
/// a light's intensity is the one measured at unit distance.
///   none            1             (no attenuation; handy for stylised scenes)
///   inverse_linear  1 / r
///   inverse_square  1 / r^2       (physical: radiant intensity / r^2, the inverse-square
///                                  law of photometry, e.g. Akenine-Moeller, Haines,
///                                  Hoffman et al. 2018, Real-Time Rendering 4th ed.,
///                                  Section 5.2.2)
enum class falloff { none, inverse_linear, inverse_square };

/// The attenuation factor of law f at distance r (see shade::falloff). Precondition:
/// r > 0. For r so small that the factor overflows, the result is +inf; lights never pass
/// it on (detail::make_sample then drops the directional part).
template <std::floating_point T>
[[nodiscard]] constexpr T falloff_factor(falloff f, T r) noexcept {
    switch (f) {
    case falloff::none: return T(1);
    case falloff::inverse_linear: return T(1) / r;
    case falloff::inverse_square: return T(1) / (r * r);
    }
    return T(1);
}

namespace detail {

/// Throws invalid_parameter naming "falloff" unless f is one of the enumerators.
inline falloff require_falloff(falloff f) {
    if (f != falloff::none && f != falloff::inverse_linear && f != falloff::inverse_square)
        throw invalid_parameter("falloff", "must be none, inverse_linear or inverse_square",
                                std::to_string(static_cast<int>(f)));
    return f;
}

} // namespace detail

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
        const auto [l, r] = detail::split_direction(vec3<T>(position_ - p));
        if (!(r > T(0))) return detail::ambient_only_sample(emission_);
        return detail::make_sample(emission_, l, r, falloff_factor(falloff_, r));
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
