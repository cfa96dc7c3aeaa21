#pragma once
// What the light fuzz targets (rectangle, disk, sphere, environment) share: decoding the
// light's emission and the shaded situation, and the checks every emitter must pass.
//
// Input layout after the target's own parameters (input.hpp decodes the scalars): the
// shaded point p (vector), the sample numbers u = (u_x, u_y) (two scalars mapped into
// [0, 1) with to_unit_interval), a direction w (vector, normalised; a zero or non-finite w
// skips the checks that use it).
//
// Checked, for a light built by its validating constructor (parameters it rejects must
// throw exactly shade::invalid_parameter, caught by the target), at a finite p:
//   * sample_incident(p, u), when it returns a sample: l a finite unit vector, !delta,
//     pdf finite and > 0, distance > 0 and not NaN, radiance finite and >= 0 (validated
//     emissions have a finite physical quantity);
//   * pdf_incident(p, w) and pdf_incident(p, l) finite and >= 0; incident_radiance(p, w)
//     finite and >= 0;
//   * the classic sample(p, u) never NaN nor negative in any colour;
//   * sample and pdf agree: pdf_incident(p, l) equals the sample's pdf (relative 1e-2 in
//     float, 1e-6 in double) and incident_radiance(p, l) equals its radiance, whenever the
//     situation is well conditioned (the target says when: moderate numbers, p not close
//     to the light's surface, u away from the edge of the sampled domain, the sampled
//     direction not grazing the light); elsewhere rounding may legitimately put the
//     direction's ray just past the light's edge;
//   * shade::any_light holding the light forwards all three calls unchanged (bit for bit).

#include <cmath>
#include <concepts>
#include <cstdio>
#include <cstring>
#include <limits>
#include <optional>

#include <glm/geometric.hpp>

#include <shade/core/math.hpp>
#include <shade/light/any_light.hpp>
#include <shade/light/emission.hpp>

#include "brdf_target.hpp"
#include "expect.hpp"
#include "input.hpp"

namespace shade::fuzz {

/// An emission: intensity, ambient, diffuse, specular (any values; validated() judges).
template <std::floating_point T>
[[nodiscard]] emission<T> decode_emission(tracking_reader<T>& r) {
    emission<T> e;
    e.intensity = r.scalar();
    e.ambient = r.vector();
    e.diffuse = r.vector();
    e.specular = r.vector();
    return e;
}

/// Sidedness from a byte: 0 one-sided, 1 two-sided, 2 an invalid value on purpose.
[[nodiscard]] inline sidedness decode_sides(input& in) noexcept { return static_cast<sidedness>(in.choice(3)); }

/// The reader of the light targets: moderate means every number within 1e2, where the
/// agreement check applies (the bounded verdict is unused).
template <std::floating_point T>
[[nodiscard]] tracking_reader<T> light_reader(input& in) noexcept {
    return tracking_reader<T>{in, T(1e2), std::numeric_limits<T>::max()};
}

/// The situation the checks run in.
template <std::floating_point T>
struct light_situation {
    vec3<T> p{0, 0, 0};
    vec2<T> u{0, 0};
    std::optional<vec3<T>> w; ///< a unit direction, if the decoded one was usable
};

template <std::floating_point T>
[[nodiscard]] light_situation<T> decode_light_situation(tracking_reader<T>& r) {
    light_situation<T> s;
    s.p = r.vector();
    s.u.x = to_unit_interval(r.in.template scalar<T>());
    s.u.y = to_unit_interval(r.in.template scalar<T>());
    s.w = unit_or_nothing(r.in.template vector<T>());
    return s;
}

template <std::floating_point T>
[[nodiscard]] bool not_nan_non_negative(const rgb<T>& c) noexcept {
    return c.x >= T(0) && c.y >= T(0) && c.z >= T(0); // false for NaN
}

template <std::floating_point T>
[[nodiscard]] bool same_bits(const rgb<T>& a, const rgb<T>& b) noexcept {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

template <std::floating_point T>
[[nodiscard]] bool same_bits(T a, T b) noexcept {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

/// Runs the checks at the top of this file. `well_conditioned(sample)` says whether the
/// agreement check applies to a returned sample (the target's own geometry test).
template <class L, std::floating_point T, class Condition>
void check_light(const L& light, const light_situation<T>& s, Condition&& well_conditioned) {
    if (!is_finite(s.p)) {
        // Evaluated for the sanitizers only; nothing is promised off finite points.
        (void)light.sample_incident(s.p, s.u);
        if (s.w) (void)light.pdf_incident(s.p, *s.w);
        return;
    }
    const auto x = light.sample_incident(s.p, s.u);
    const light_sample<T> classic = light.sample(s.p, s.u);
    const bool classic_ok = not_nan_non_negative(classic.ambient) && not_nan_non_negative(classic.diffuse) &&
                            not_nan_non_negative(classic.specular);
    if (!classic_ok) {
        show("p", s.p);
        show("classic diffuse", classic.diffuse);
        show("classic specular", classic.specular);
    }
    expect(classic_ok, "classic light sample has a NaN or negative colour");

    if (s.w) {
        const T pdf_w = light.pdf_incident(s.p, *s.w);
        const rgb<T> L_w = light.incident_radiance(s.p, *s.w);
        const bool pdf_ok = std::isfinite(pdf_w) && pdf_w >= T(0);
        const bool L_ok = finite_non_negative(L_w);
        if (!pdf_ok || !L_ok) {
            show("p", s.p);
            show("w", *s.w);
            show("pdf_incident", pdf_w);
            show("incident_radiance", L_w);
        }
        expect(pdf_ok, "pdf_incident of a unit direction is not finite and >= 0");
        expect(L_ok, "incident_radiance of a unit direction is not finite and >= 0");
    }

    // any_light forwards unchanged.
    const any_light<T> any(light);
    const auto y = any.sample_incident(s.p, s.u);
    bool forwards = x.has_value() == y.has_value();
    if (forwards && x)
        forwards = same_bits(x->l.x, y->l.x) && same_bits(x->l.y, y->l.y) && same_bits(x->l.z, y->l.z) &&
                   same_bits(x->distance, y->distance) && same_bits(x->radiance, y->radiance) &&
                   same_bits(x->pdf, y->pdf) && x->delta == y->delta;
    if (s.w)
        forwards = forwards && same_bits(any.pdf_incident(s.p, *s.w), light.pdf_incident(s.p, *s.w)) &&
                   same_bits(any.incident_radiance(s.p, *s.w), light.incident_radiance(s.p, *s.w));
    expect(forwards, "any_light does not forward sample_incident, pdf_incident or incident_radiance");

    if (!x) return;
    const T length = glm::length(x->l);
    const bool l_ok = is_finite(x->l) && std::abs(length - T(1)) <= T(1e-4);
    const bool pdf_ok = std::isfinite(x->pdf) && x->pdf > T(0) && !x->delta;
    const bool distance_ok = x->distance > T(0); // false for NaN
    const bool radiance_ok = finite_non_negative(x->radiance);
    const T pdf_l = light.pdf_incident(s.p, x->l);
    const rgb<T> L_l = light.incident_radiance(s.p, x->l);
    const bool pdf_l_ok = std::isfinite(pdf_l) && pdf_l >= T(0);
    bool agree = true;
    if (l_ok && pdf_ok && distance_ok && well_conditioned(*x)) {
        const T tolerance = sizeof(T) == 4 ? T(1e-2) : T(1e-6);
        agree = std::abs(pdf_l - x->pdf) <= tolerance * x->pdf && L_l == x->radiance;
    }
    if (!l_ok || !pdf_ok || !distance_ok || !radiance_ok || !pdf_l_ok || !agree) {
        show("p", s.p);
        show("u.x", s.u.x);
        show("u.y", s.u.y);
        show("sampled l", x->l);
        show("sampled distance", x->distance);
        show("sampled pdf", x->pdf);
        show("sampled radiance", x->radiance);
        show("pdf_incident(p, l)", pdf_l);
        show("incident_radiance(p, l)", L_l);
    }
    expect(l_ok, "sampled l is not a finite unit vector");
    expect(pdf_ok, "sampled pdf is not finite and > 0, or the sample says delta");
    expect(distance_ok, "sampled distance is not > 0");
    expect(radiance_ok, "sampled radiance is not finite and >= 0");
    expect(pdf_l_ok, "pdf_incident at the sampled direction is not finite and >= 0");
    expect(agree, "sample_incident and pdf_incident / incident_radiance disagree at the sampled direction");
}

} // namespace shade::fuzz
