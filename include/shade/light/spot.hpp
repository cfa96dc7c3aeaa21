#pragma once
// shade::spot_light: a point light restricted to a cone with a smooth edge.

#include <cmath>
#include <concepts>
#include <optional>

#include <glm/geometric.hpp>

#include <shade/core/error.hpp>
#include <shade/core/math.hpp>
#include <shade/core/types.hpp>
#include <shade/light/delta_light.hpp>
#include <shade/light/emission.hpp>
#include <shade/light/falloff.hpp>
#include <shade/light/incident_sample.hpp>
#include <shade/light/light_sample.hpp>

namespace shade {

/// The smooth cone factor of a spotlight, in [0, 1], given cos_s = cos of the angle between
/// the spot axis and the direction from the light to the shaded point, and the cosines of
/// the inner (full light) and outer (no light) half-angles, cos_inner >= cos_outer:
///
///   t = clamp((cos_s - cos_outer) / (cos_inner - cos_outer), 0, 1)
///   factor = smoothstep(t) = t^2 (3 - 2 t)
///
/// Akenine-Moeller, Haines, Hoffman, Pesce, Iwanicki, Hillaire 2018, "Real-Time Rendering",
/// 4th ed., Section 5.2.2 (spotlights): the smoothstep-of-cosines variant (the book's
/// three.js form; Filament squares t instead). It is 1 inside the inner cone, 0 outside the
/// outer cone, and C1-smooth between them in cos_s. With cos_inner == cos_outer (equal
/// angles) the edge is hard: 1 for cos_s >= cos_outer, else 0.
template <std::floating_point T>
[[nodiscard]] inline T spot_cone_factor(T cos_s, T cos_inner, T cos_outer) noexcept {
    const T width = cos_inner - cos_outer;
    if (!(width > T(0))) return cos_s >= cos_outer ? T(1) : T(0);
    T t = (cos_s - cos_outer) / width;
    t = t < T(0) ? T(0) : (t > T(1) ? T(1) : t);
    return t * t * (T(3) - T(2) * t);
}

/// A spotlight: a point light at `position` shining along the unit `axis`, with full
/// light inside the inner half-angle, none outside the outer half-angle and a smoothstep
/// edge between (shade::spot_cone_factor). Its sample at p has l = (position - p) / r,
/// distance r, ambient = intensity x ambient colour and diffuse/specular = intensity x
/// falloff_factor(f, r) x cone factor x colour. At r = 0 or where the falloff overflows the
/// sample carries the ambient colour only (as for shade::point_light).
///
/// Physical mode: the radiant intensity toward p is I = emitted().physical() in W/sr
/// times the cone factor, the irradiance at normal incidence I x cone / r^2 (always the
/// inverse-square law), and the power, integrating the cone factor over the sphere
/// (the smoothstep averages 1/2 over the edge),
///     Phi = 2 pi I (1 - (cos_inner + cos_outer) / 2)   W.
template <std::floating_point T>
class spot_light : public detail::delta_light<spot_light<T>, T> {
public:
    using scalar_type = T;
    using detail::delta_light<spot_light<T>, T>::sample;
    using detail::delta_light<spot_light<T>, T>::sample_incident;

    /// A spotlight at `position` pointing along `axis` (from the light INTO the scene; any
    /// finite non-zero length), with half-angles inner_angle <= outer_angle in radians,
    /// measured from the axis, 0 <= inner_angle <= outer_angle, 0 < outer_angle <= pi.
    /// The default emission is the classic model's light (I = pi W/sr on the axis);
    /// from_intensity and from_power say their units. Throws shade::invalid_parameter
    /// naming "position", "axis", "outer_angle", "inner_angle", "falloff" or the bad
    /// emission member.
    spot_light(const vec3<T>& position, const vec3<T>& axis, T inner_angle, T outer_angle,
               const emission<T>& e = {}, falloff f = falloff::inverse_square)
        : position_(require_finite("position", position)),
          axis_(require_direction("axis", axis)),
          inner_angle_(inner_angle), outer_angle_(outer_angle), emission_(validated(e)),
          falloff_(detail::require_falloff(f)) {
        (void)require_in_range("outer_angle", outer_angle, T(0), pi<T>);
        if (!(outer_angle > T(0)))
            throw invalid_parameter("outer_angle", "must be > 0", detail::to_text(outer_angle));
        (void)require_in_range("inner_angle", inner_angle, T(0), pi<T>);
        if (!(inner_angle <= outer_angle))
            throw invalid_parameter("inner_angle",
                                    "must be <= outer_angle (" + detail::to_text(outer_angle) + ")",
                                    detail::to_text(inner_angle));
        cos_inner_ = std::cos(inner_angle);
        cos_outer_ = std::cos(outer_angle);
    }

    /// The spotlight (geometry as for the constructor) of radiant intensity I in W/sr on its
    /// axis (from_intensity), or of power Phi in W (from_power: I = Phi / Omega, Omega =
    /// 2 pi (1 - (cos_inner + cos_outer) / 2) sr, see the class comment); no ambient, 1/r^2.
    /// Throw shade::invalid_parameter naming what the constructor names, "intensity",
    /// "power", or "outer_angle" for a cone whose Omega rounds to 0 in T.
    [[nodiscard]] static spot_light from_intensity(const vec3<T>& position, const vec3<T>& axis, T inner_angle,
                                                   T outer_angle, const rgb<T>& intensity) {
        return spot_light(position, axis, inner_angle, outer_angle, detail::physical_emission("intensity", intensity));
    }
    [[nodiscard]] static spot_light from_power(const vec3<T>& position, const vec3<T>& axis, T inner_angle,
                                               T outer_angle, const rgb<T>& power) {
        spot_light out(position, axis, inner_angle, outer_angle);
        if (!(out.cone_solid_angle() > T(0)))
            throw invalid_parameter("outer_angle", "must give a cone of non-zero solid angle", detail::to_text(outer_angle));
        out.emission_ = detail::physical_emission("power", power, out.cone_solid_angle());
        return out;
    }

    /// The light's position.
    [[nodiscard]] const vec3<T>& position() const noexcept { return position_; }
    /// The unit axis the spot points along (from the light into the scene).
    [[nodiscard]] const vec3<T>& axis() const noexcept { return axis_; }
    /// The inner half-angle in radians (full light inside).
    [[nodiscard]] T inner_angle() const noexcept { return inner_angle_; }
    /// The outer half-angle in radians (no light outside).
    [[nodiscard]] T outer_angle() const noexcept { return outer_angle_; }
    /// The emitted intensity and colours.
    [[nodiscard]] const emission<T>& emitted() const noexcept { return emission_; }
    /// The distance law.
    [[nodiscard]] falloff distance_falloff() const noexcept { return falloff_; }

    /// The radiant intensity I on the axis in W/sr (physical mode).
    [[nodiscard]] rgb<T> intensity() const noexcept { return emission_.physical(); }
    /// The radiant power in W (physical mode; see the class comment).
    [[nodiscard]] rgb<T> power() const noexcept { return cone_solid_angle() * intensity(); }
    using detail::delta_light<spot_light<T>, T>::power;

    /// The light's classic sample at point p (see the class comment).
    [[nodiscard]] light_sample<T> sample(const vec3<T>& p) const noexcept {
        return detail::positional_sample(emission_, position_, falloff_, p, cone_toward(this));
    }

    /// The physical sample at p: toward the light, irradiance I x cone / r^2 at normal
    /// incidence (W/m^2), delta. Nothing at r = 0, outside the cone or on overflow.
    [[nodiscard]] std::optional<incident_sample<T>> sample_incident(const vec3<T>& p) const noexcept {
        return detail::positional_incident(emission_, position_, p, cone_toward(this));
    }

private:
    /// The cone factor integrated over the sphere, 2 pi (1 - (cos_inner + cos_outer) / 2) sr.
    [[nodiscard]] T cone_solid_angle() const noexcept {
        return T(2) * pi<T> * (T(1) - (cos_inner_ + cos_outer_) / T(2));
    }

    /// The cone factor as a function of l, the unit direction from p toward the light:
    /// -l points from the light to p, and its cosine with the axis is cos_s.
    [[nodiscard]] static auto cone_toward(const spot_light* light) noexcept {
        return [light](const vec3<T>& l) noexcept {
            return spot_cone_factor(-glm::dot(light->axis_, l), light->cos_inner_, light->cos_outer_);
        };
    }

    vec3<T> position_;
    vec3<T> axis_;
    T inner_angle_;
    T outer_angle_;
    emission<T> emission_;
    falloff falloff_;
    T cos_inner_ = T(1);
    T cos_outer_ = T(-1);
};

} // namespace shade
