#pragma once
// shade::point_light: a light at a point whose light weakens with distance by a
// selectable law (shade::falloff).

#include <concepts>
#include <optional>

#include <shade/core/error.hpp>
#include <shade/core/math.hpp>
#include <shade/core/types.hpp>
#include <shade/light/delta_light.hpp>
#include <shade/light/emission.hpp>
#include <shade/light/falloff.hpp>
#include <shade/light/incident_sample.hpp>
#include <shade/light/light_sample.hpp>

namespace shade {

/// A point light at `position`. Its sample at p has l = (position - p) / r, distance
/// r = |position - p|, ambient = intensity x ambient colour, and diffuse/specular =
/// intensity x falloff_factor(f, r) x colour.
///
/// At r = 0 (p at the light) the direction is undefined, and where the falloff overflows
/// (r below ~1e-19 in float for 1/r^2) the light would be infinite: in both cases the
/// sample carries the ambient colour only (no directional light, no Inf/NaN).
///
/// Physical mode: the light's radiant intensity is I = emitted().physical() in W/sr in
/// every direction, its power 4 pi I in W, and the irradiance it gives at normal incidence
/// at distance r is I / r^2 (the inverse-square law always: the falloff law belongs to
/// the classic mode).
template <std::floating_point T>
class point_light : public detail::delta_light<point_light<T>, T> {
public:
    using scalar_type = T;
    using detail::delta_light<point_light<T>, T>::sample;
    using detail::delta_light<point_light<T>, T>::sample_incident;

    /// A point light at `position` with emission e and distance law f (the classic
    /// model's light: the default emission has I = pi W/sr; from_intensity and from_power
    /// say their units). Throws
    /// shade::invalid_parameter naming "position" (non-finite), "falloff" or the bad
    /// emission member.
    explicit point_light(const vec3<T>& position, const emission<T>& e = {},
                         falloff f = falloff::inverse_square)
        : position_(require_finite("position", position)), emission_(validated(e)),
          falloff_(detail::require_falloff(f)) {}

    /// The point light at `position` of radiant intensity I in W/sr (from_intensity), or of
    /// power Phi in W (from_power: I = Phi / (4 pi), an isotropic source over 4 pi sr); no
    /// ambient, 1/r^2. Throw shade::invalid_parameter naming "position", "intensity" or
    /// "power" (negative or not finite in a channel).
    [[nodiscard]] static point_light from_intensity(const vec3<T>& position, const rgb<T>& intensity) {
        return point_light(position, detail::physical_emission("intensity", intensity));
    }
    [[nodiscard]] static point_light from_power(const vec3<T>& position, const rgb<T>& power) {
        return point_light(position, detail::physical_emission("power", power, T(4) * pi<T>));
    }

    /// The light's position.
    [[nodiscard]] const vec3<T>& position() const noexcept { return position_; }
    /// The emitted intensity and colours.
    [[nodiscard]] const emission<T>& emitted() const noexcept { return emission_; }
    /// The distance law.
    [[nodiscard]] falloff distance_falloff() const noexcept { return falloff_; }

    /// The radiant intensity I in W/sr (physical mode).
    [[nodiscard]] rgb<T> intensity() const noexcept { return emission_.physical(); }
    /// The radiant power 4 pi I in W (physical mode).
    [[nodiscard]] rgb<T> power() const noexcept { return (T(4) * pi<T>) * intensity(); }
    using detail::delta_light<point_light<T>, T>::power;

    /// The light's classic sample at point p (see the class comment).
    [[nodiscard]] light_sample<T> sample(const vec3<T>& p) const noexcept {
        return detail::positional_sample(emission_, position_, falloff_, p, unit_factor);
    }

    /// The physical sample at p: toward the light, at its distance r, irradiance I / r^2
    /// at normal incidence (W/m^2), delta. Nothing at r = 0 or where I / r^2 overflows.
    [[nodiscard]] std::optional<incident_sample<T>> sample_incident(const vec3<T>& p) const noexcept {
        return detail::positional_incident(emission_, position_, p, unit_factor);
    }

private:
    static constexpr T unit_factor(const vec3<T>&) noexcept { return T(1); }

    vec3<T> position_;
    emission<T> emission_;
    falloff falloff_;
};

} // namespace shade
