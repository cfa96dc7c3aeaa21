#pragma once
// shade::directional_light: a light infinitely far away (the sun), same direction everywhere.

#include <concepts>
#include <optional>

#include <shade/core/error.hpp>
#include <shade/core/math.hpp>
#include <shade/core/types.hpp>
#include <shade/light/delta_light.hpp>
#include <shade/light/emission.hpp>
#include <shade/light/incident_sample.hpp>
#include <shade/light/light_sample.hpp>

namespace shade {

/// A directional light: every shaded point receives light from the same unit direction,
/// with no falloff. Its sample has l = direction(), distance = +inf, ambient = intensity x
/// ambient colour and diffuse/specular = intensity x colour.
///
/// Physical mode: emitted().physical() is the irradiance E in W/m^2 on a surface facing
/// the light (its power is not finite: the light covers all of space).
template <std::floating_point T>
class directional_light : public detail::delta_light<directional_light<T>, T> {
public:
    using scalar_type = T;
    using detail::delta_light<directional_light<T>, T>::sample;
    using detail::delta_light<directional_light<T>, T>::sample_incident;

    /// A light shining from `direction` (pointing from the scene TOWARD the light; any
    /// finite non-zero length, normalised here) with emission e (the classic model's
    /// light: the default gives E = pi W/m^2; from_irradiance says its unit). Throws
    /// shade::invalid_parameter naming "direction" (zero or non-finite) or the bad
    /// emission member (see shade::validated).
    explicit directional_light(const vec3<T>& direction, const emission<T>& e = {})
        : direction_(require_direction("direction", direction)), emission_(validated(e)) {}

    /// The light shining from `direction` (as for the constructor) of irradiance E in W/m^2
    /// at normal incidence; no ambient. Throws shade::invalid_parameter naming "direction"
    /// or "irradiance" (negative or not finite in a channel).
    [[nodiscard]] static directional_light from_irradiance(const vec3<T>& direction, const rgb<T>& irradiance) {
        return directional_light(direction, detail::physical_emission("irradiance", irradiance));
    }

    /// The unit direction toward the light.
    [[nodiscard]] const vec3<T>& direction() const noexcept { return direction_; }
    /// The emitted intensity and colours.
    [[nodiscard]] const emission<T>& emitted() const noexcept { return emission_; }

    /// The irradiance E at normal incidence in W/m^2 (physical mode).
    [[nodiscard]] rgb<T> irradiance() const noexcept { return emission_.physical(); }

    /// The power in W sent through a scene within a sphere of radius scene_radius: pi r^2 E
    /// (the light itself, covering all space, has no finite power). Throws
    /// shade::invalid_parameter naming "scene_radius" unless it is finite and >= 0.
    [[nodiscard]] rgb<T> power(T scene_radius) const {
        const T r = detail::require_scene_radius(scene_radius);
        return (pi<T> * r * r) * irradiance();
    }

    /// The light's classic sample at point p (p is not used: the light is the same everywhere).
    [[nodiscard]] light_sample<T> sample(const vec3<T>& p) const noexcept {
        (void)p;
        return detail::make_sample(emission_, direction_, infinity<T>, T(1));
    }

    /// The physical sample at p: along direction(), at infinity, irradiance E (delta).
    [[nodiscard]] std::optional<incident_sample<T>> sample_incident(const vec3<T>& p) const noexcept {
        (void)p;
        return detail::delta_incident(direction_, infinity<T>, irradiance());
    }

private:
    vec3<T> direction_;
    emission<T> emission_;
};

} // namespace shade
