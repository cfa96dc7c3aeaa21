#pragma once
// shade::incident_sample: what a light sends to a shaded point in the physical mode, in
// physical units, with the density it was drawn with; and the conversions between area
// and solid-angle densities that the area lights share.

#include <cmath>
#include <concepts>
#include <optional>
#include <string>

#include <glm/geometric.hpp>

#include <shade/core/error.hpp>
#include <shade/core/math.hpp>
#include <shade/core/types.hpp>
#include <shade/light/emission.hpp>
#include <shade/light/light_sample.hpp>

namespace shade {

/// Which side of an area light emits: the side its normal points to, or both.
enum class sidedness { one_sided, two_sided };

/// One sample of the light arriving at a shaded point p, in physical units (the physical
/// mode; see docs/conventions.md).
///
/// For a light with extent (area and environment lights) `radiance` is the radiance L_i
/// arriving at p from direction l, in W/(m^2 sr), and `pdf` the solid-angle density with
/// which l was drawn, in 1/sr: L_i cos / pdf, averaged over samples, estimates the
/// irradiance. A delta light (point, spot, directional) has a single direction: `delta`
/// is true, `pdf` is 1 and `radiance` is the irradiance at normal incidence, in W/m^2,
/// which then takes the place of L_i / pdf in the same estimator.
template <std::floating_point T>
struct incident_sample {
    using scalar_type = T;

    vec3<T> l{0, 0, 1};        ///< unit direction from p toward the light
    T distance = infinity<T>;  ///< distance to the sampled light point (+inf: at infinity)
    rgb<T> radiance{0, 0, 0};  ///< W/(m^2 sr); for a delta light W/m^2 (see above)
    T pdf = T(0);              ///< solid-angle density of l, 1/sr (1 for delta lights)
    bool delta = false;        ///< true for point, spot and directional lights
};

namespace detail {

/// Returns sides; throws invalid_parameter naming "sides" unless it is an enumerator.
inline sidedness require_sidedness(sidedness sides) {
    if (sides != sidedness::one_sided && sides != sidedness::two_sided)
        throw invalid_parameter("sides", "must be one_sided or two_sided",
                                std::to_string(static_cast<int>(sides)));
    return sides;
}

/// The incident sample of a delta light: direction l, distance r, irradiance E at normal
/// incidence (W/m^2), pdf 1. Nothing when E is zero or not finite.
template <std::floating_point T>
[[nodiscard]] std::optional<incident_sample<T>> delta_incident(const vec3<T>& l, T r,
                                                               const rgb<T>& E) noexcept {
    if (!is_finite(E) || E == rgb<T>(0)) return std::nullopt;
    incident_sample<T> s;
    s.l = l;
    s.distance = r;
    s.radiance = E;
    s.pdf = T(1);
    s.delta = true;
    return s;
}

/// Whether the emitter with unit normal n sends light toward unit direction w (pointing
/// away from its surface), and the cosine it does so with: dot(n, w) for one-sided
/// emitters, |dot(n, w)| for two-sided ones; 0 when it does not.
template <std::floating_point T>
[[nodiscard]] inline T emitting_cosine(const vec3<T>& n, const vec3<T>& w, sidedness sides) noexcept {
    const T c = glm::dot(n, w);
    const T cos_out = sides == sidedness::two_sided ? std::fabs(c) : c;
    return cos_out > T(0) ? cos_out : T(0);
}

/// The solid-angle density at p of a point x chosen on a surface with area density
/// 1 / area (uniform), at distance r, whose surface makes cosine cos_light with the
/// direction toward p: pdf_w = r^2 / (area cos_light) (the change of variables
/// dw = cos_light dA / r^2, e.g. Veach 1997, "Robust Monte Carlo Methods for Light
/// Transport Simulation", PhD thesis, Stanford, eq. 8.10). 0 where cos_light is 0 or the
/// density overflows.
template <std::floating_point T>
[[nodiscard]] inline T solid_angle_pdf(T r, T cos_light, T area) noexcept {
    if (!(cos_light > T(0))) return T(0);
    const T pdf = r * r / (area * cos_light);
    return std::isfinite(pdf) ? pdf : T(0);
}

/// The incident sample at p from point x of a uniformly emitting surface (unit normal
/// n_x, total area `area`, radiance L) that was chosen with area density 1 / area.
/// Nothing when x coincides with p, when the side facing p does not emit (the sample is
/// then worth zero), or when the density is not finite.
template <std::floating_point T>
[[nodiscard]] std::optional<incident_sample<T>> area_incident(const vec3<T>& p, const vec3<T>& x,
                                                              const vec3<T>& n_x, T area,
                                                              const rgb<T>& L, sidedness sides) noexcept {
    const auto [l, r] = split_direction(vec3<T>(x - p));
    if (!(r > T(0))) return std::nullopt;
    const T pdf = solid_angle_pdf(r, emitting_cosine(n_x, vec3<T>(-l), sides), area);
    if (!(pdf > T(0))) return std::nullopt;
    incident_sample<T> s;
    s.l = l;
    s.distance = r;
    s.radiance = L;
    s.pdf = pdf;
    return s;
}

/// The classic light_sample of a non-delta light from its physical sample: the classic
/// colours are intensity x colour / pdf (one Monte Carlo sample of the light, so that
/// averaging a linear classic shader over samples estimates the light's contribution,
/// as shade::area_light documents). Ambient only where there is no sample.
template <std::floating_point T>
[[nodiscard]] light_sample<T> classic_from(const emission<T>& e,
                                           const std::optional<incident_sample<T>>& s) noexcept {
    if (!s) return ambient_only_sample(e);
    return make_sample(e, s->l, s->distance, T(1) / s->pdf);
}

} // namespace detail

} // namespace shade
