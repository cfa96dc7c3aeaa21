#pragma once
// shade::falloff: how the light of a point or spot light weakens with distance, and the
// one body both lights compute their samples with.

#include <concepts>
#include <optional>
#include <string>

#include <shade/core/error.hpp>
#include <shade/core/types.hpp>
#include <shade/light/emission.hpp>
#include <shade/light/incident_sample.hpp>
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

/// The light_sample at p of a positional light at `position` (point or spot): l =
/// (position - p) / r, distance r = |position - p|, ambient = intensity x ambient colour,
/// diffuse/specular = intensity x falloff_factor(f, r) x directional(l) x colour, where
/// directional(l) >= 0 is the light's angular factor (1 for a point light, the cone factor
/// for a spot). At r = 0 the direction is undefined and the sample carries the ambient
/// colour only, as it does where the product overflows (detail::make_sample).
template <std::floating_point T, class Directional>
[[nodiscard]] light_sample<T> positional_sample(const emission<T>& e, const vec3<T>& position,
                                                falloff f, const vec3<T>& p,
                                                const Directional& directional) noexcept {
    const auto [l, r] = split_direction(vec3<T>(position - p));
    if (!(r > T(0))) return ambient_only_sample(e);
    return make_sample(e, l, r, falloff_factor(f, r) * directional(l));
}

/// The physical incident sample at p of a positional light at `position` whose radiant
/// intensity toward p is e.physical() x directional(l) (W/sr): the irradiance at normal
/// incidence E = I / r^2 (the inverse-square law, whatever the classic falloff), as a
/// delta sample. Nothing at r = 0, where E is zero or where it overflows.
template <std::floating_point T, class Directional>
[[nodiscard]] std::optional<incident_sample<T>>
positional_incident(const emission<T>& e, const vec3<T>& position, const vec3<T>& p,
                    const Directional& directional) noexcept {
    const auto [l, r] = split_direction(vec3<T>(position - p));
    if (!(r > T(0))) return std::nullopt;
    return delta_incident(l, r, rgb<T>(e.physical() * (directional(l) / (r * r))));
}

} // namespace detail

} // namespace shade
