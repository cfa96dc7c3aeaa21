#pragma once
// shade::emission: the intensity and the three classic colours every light carries, and
// the one place where they are validated and turned into a light_sample.

#include <cmath>
#include <concepts>
#include <string_view>

#include <shade/core/error.hpp>
#include <shade/core/math.hpp>
#include <shade/core/types.hpp>
#include <shade/light/light_sample.hpp>

namespace shade {

/// What a light emits, in the units of shade::light_sample: a scalar intensity and separate
/// ambient, diffuse and specular colours (linear RGB). A light sample's colours are these
/// colours times the intensity (ambient) or times intensity x falloff x cone factor
/// (diffuse, specular). All values must be finite and >= 0; lights check this on
/// construction with shade::validated.
///
/// The same emission gives the light's physical quantity (the physical mode,
/// shade::incident_sample): physical() = pi x intensity x diffuse, which is the radiant
/// intensity in W/sr of a point or spot light, the irradiance in W/m^2 at normal incidence
/// of a directional light, and the radiance in W/(m^2 sr) of an area or environment
/// light. The factor pi makes both modes agree on a Lambertian surface: the classic
/// diffuse colour is the radiance a white Lambertian surface facing the light reflects,
/// E / pi. The ambient and specular colours belong to the classic mode only. The lights'
/// factories that name a unit (from_power, from_radiance, ...) build it with from_physical.
template <std::floating_point T>
struct emission {
    using scalar_type = T;

    T intensity = T(1);          ///< scalar multiplier of all three colours, >= 0
    rgb<T> ambient{0, 0, 0};     ///< ambient colour I_a, per channel >= 0
    rgb<T> diffuse{1, 1, 1};     ///< diffuse colour I_d, per channel >= 0
    rgb<T> specular{1, 1, 1};    ///< specular colour I_s, per channel >= 0

    /// The emission whose physical quantity is q (W/sr, W/m^2 or W/(m^2 sr) by light, see
    /// above): intensity 1, diffuse = specular = q / pi, no ambient.
    [[nodiscard]] static constexpr emission from_physical(const rgb<T>& q) noexcept {
        return emission{T(1), rgb<T>(0), q / pi<T>, q / pi<T>};
    }

    /// pi x intensity x diffuse: the light's physical quantity (see above). The product
    /// intensity x diffuse is formed first, so a zero colour channel gives 0 whatever the
    /// intensity (pi x intensity alone may overflow to +inf, and inf x 0 is NaN).
    [[nodiscard]] constexpr rgb<T> physical() const noexcept { return pi<T> * (intensity * diffuse); }
};

/// Returns e unchanged after checking it; throws shade::invalid_parameter naming
/// "intensity", "ambient", "diffuse" or "specular" if that member is negative or not
/// finite, or "intensity" if intensity x ambient or the physical quantity
/// pi x intensity x diffuse overflows.
template <std::floating_point T>
[[nodiscard]] emission<T> validated(const emission<T>& e) {
    (void)require_non_negative("intensity", e.intensity);
    (void)require_non_negative("ambient", e.ambient);
    (void)require_non_negative("diffuse", e.diffuse);
    (void)require_non_negative("specular", e.specular);
    // The ambient colour is scaled by the intensity alone, so that product must stay
    // finite; diffuse and specular products are checked per sample (make_sample).
    if (!is_finite(e.intensity * e.ambient))
        throw invalid_parameter("intensity", "times the ambient colour must be finite",
                                detail::to_text(e.intensity));
    // The physical mode hands out pi x intensity x diffuse as it is (a radiance, an
    // intensity or an irradiance), so it must be finite too.
    if (!is_finite(e.physical()))
        throw invalid_parameter("intensity", "times pi times the diffuse colour (the physical quantity) must be finite",
                                detail::to_text(e.intensity));
    return e;
}

namespace detail {

/// emission::from_physical(q / divisor), for the lights' unit-naming factories: q is what
/// the caller gave (a power, intensity, irradiance or radiance) and divisor what turns it
/// into the light's physical quantity (1, 4 pi, pi A, ...). Throws invalid_parameter
/// naming `name` if q is negative or not finite in a channel or q / divisor overflows.
/// Precondition: divisor finite and > 0.
template <std::floating_point T>
[[nodiscard]] emission<T> physical_emission(std::string_view name, const rgb<T>& q, T divisor = T(1)) {
    (void)require_non_negative(name, q);
    const emission<T> e = emission<T>::from_physical(q / divisor);
    if (!is_finite(e.diffuse) || !is_finite(e.physical()))
        throw invalid_parameter(name, "must give a light quantity that is finite in this scalar type",
                                to_text(q));
    return e;
}

/// Returns r; throws invalid_parameter naming "scene_radius" unless finite and >= 0.
template <std::floating_point T>
T require_scene_radius(T r) {
    return require_non_negative("scene_radius", r);
}

/// A sample that brings no directional light: only the ambient colour (which no falloff,
/// cone or occluder affects), l = +z as a placeholder unit vector, distance +inf.
/// Lights return it where the direction is undefined (shaded point at the light).
template <std::floating_point T>
[[nodiscard]] light_sample<T> ambient_only_sample(const emission<T>& e) noexcept {
    light_sample<T> s;
    s.ambient = e.intensity * e.ambient;
    return s;
}

/// The light sample toward unit direction l at the given distance whose diffuse and
/// specular colours are scaled by intensity x attenuation (attenuation: falloff, cone,
/// geometry factor, all >= 0). When that product is zero, NaN (0 x inf) or overflows to a
/// non-finite colour, the diffuse and specular colours are left at zero (no light rather
/// than Inf/NaN downstream); l and distance are set whenever l is finite.
template <std::floating_point T>
[[nodiscard]] inline light_sample<T> make_sample(const emission<T>& e, const vec3<T>& l, T distance,
                                          T attenuation) noexcept {
    light_sample<T> s = ambient_only_sample(e);
    if (!is_finite(l)) return s;
    s.l = l;
    s.distance = distance;
    const T scale = e.intensity * attenuation;
    const rgb<T> diffuse = scale * e.diffuse;
    const rgb<T> specular = scale * e.specular;
    if (!(scale > T(0)) || !is_finite(diffuse) || !is_finite(specular)) return s;
    s.diffuse = diffuse;
    s.specular = specular;
    return s;
}

/// The unit direction and length of d, or length 0 when d is zero or has a NaN or
/// infinite component. d is first divided by its largest component so that squaring
/// neither underflows (tiny d, where glm::length would return 0 or a denormal-rounded
/// value) nor overflows (huge d).
template <std::floating_point T>
struct direction_and_length {
    vec3<T> direction{0, 0, 1}; ///< unit d / |d| (placeholder +z when length == 0)
    T length = T(0);            ///< |d|, 0 for d = 0
};

template <std::floating_point T>
[[nodiscard]] inline direction_and_length<T> split_direction(const vec3<T>& d) noexcept {
    // The largest |component| by comparisons (no libm call, as std::fmax would be); a NaN
    // component, which the comparisons may skip, is caught by the sum.
    const T ax = std::fabs(d.x), ay = std::fabs(d.y), az = std::fabs(d.z);
    const T m_xy = ax < ay ? ay : ax;
    const T m = m_xy < az ? az : m_xy;
    direction_and_length<T> out;
    if (!(m > T(0)) || !std::isfinite(m) || std::isnan(ax + ay + az)) return out;
    const vec3<T> w = d / m;
    const T w_length = std::sqrt(w.x * w.x + w.y * w.y + w.z * w.z); // in [1, sqrt(3)]
    out.direction = w / w_length;
    out.length = m * w_length;
    return out;
}

} // namespace detail

} // namespace shade
