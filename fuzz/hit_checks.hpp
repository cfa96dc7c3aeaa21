#pragma once
// The guarantees every intersection routine of shade/geometry gives, checked on one
// result: a hit only for a valid ray, with finite t inside [t_min, t_max], a finite point
// and a unit normal, and never a back face when back faces are culled.

#include <cmath>
#include <concepts>
#include <limits>
#include <optional>

#include <glm/geometric.hpp>

#include <shade/geometry/hit.hpp>
#include <shade/geometry/ray.hpp>

#include "expect.hpp"

namespace shade::fuzz {

/// Prints the ray (context for a failing expect).
template <std::floating_point T>
void show(const ray<T>& r) {
    show("ray.origin", r.origin);
    show("ray.direction", r.direction);
    show("ray.t_min", r.t_min);
    show("ray.t_max", r.t_max);
}

/// Aborts unless the (possibly absent) hit h of ray r obeys the common hit rules.
template <std::floating_point T, class Hit>
void check_hit(const ray<T>& r, const std::optional<Hit>& h, culling cull = culling::none) {
    if (!h) return;
    const bool t_ok = std::isfinite(h->t) && h->t >= r.t_min && h->t <= r.t_max;
    // normalize_or_zero's result: a few roundings away from length 1.
    const T n_error = std::abs(glm::length(h->n) - T(1));
    const bool n_ok = is_finite(h->n) && n_error <= T(8) * std::numeric_limits<T>::epsilon();
    if (!r.valid() || !t_ok || !is_finite(h->p) || !n_ok) {
        show(r);
        show("hit.t", h->t);
        show("hit.p", h->p);
        show("hit.n", h->n);
    }
    expect(r.valid(), "a ray that is not valid() produced a hit");
    expect(t_ok, "a hit's t is not finite or lies outside [t_min, t_max]");
    expect(is_finite(h->p), "a hit's point is not finite");
    expect(n_ok, "a hit's normal is not a finite unit vector");
    expect(cull == culling::none || h->front_face, "a back face was reported while culled");
}

/// Aborts unless ray::checked agrees with ray::valid: it either throws exactly
/// shade::invalid_parameter, or returns a ray that is valid(). Any other exception escapes
/// and libFuzzer reports it.
template <std::floating_point T>
void check_ray_checked(const ray<T>& r) {
    try {
        const ray<T> c = ray<T>::checked(r.origin, r.direction, r.t_min, r.t_max);
        expect(c.valid(), "ray::checked accepted a ray that is not valid()");
    } catch (const invalid_parameter&) {
        // Rejected input; the only exception a validating factory may throw.
    }
}

} // namespace shade::fuzz
