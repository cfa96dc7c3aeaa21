#pragma once
// shade::detail::area_emitter: what the area lights (rectangle, disk, sphere) answer the
// same way, written once: they are visible, uniformly emitting surfaces.

#include <concepts>

#include <shade/core/math.hpp>
#include <shade/core/types.hpp>
#include <shade/geometry/hit.hpp>
#include <shade/geometry/ray.hpp>
#include <shade/light/incident_sample.hpp>

namespace shade::detail {

/// Base of the area lights (CRTP). Light provides intersect(ray) -> std::optional<hit<T>>
/// (the light as geometry), area(), sides() and emitted(). Each point of the surface
/// emits the same radiance L = emitted().physical() (W/(m^2 sr)) into every direction on
/// its emitting side(s): a diffuse (Lambertian) emitter.
template <class Light, std::floating_point T>
class area_emitter {
public:
    using scalar_type = T;

    /// Always false: an area light is sampled many times (sample(p, u) for several u).
    [[nodiscard]] static constexpr bool is_delta() noexcept { return false; }

    /// The emitted radiance L in W/(m^2 sr) (physical mode).
    [[nodiscard]] rgb<T> radiance() const noexcept { return self().emitted().physical(); }

    /// The radiant power in W: a Lambertian emitter of radiance L and area A sends
    /// pi L A from each emitting side (integrating L cos over the hemisphere gives pi L).
    [[nodiscard]] rgb<T> power() const noexcept {
        const T sides = self().sides() == sidedness::two_sided ? T(2) : T(1);
        return (pi<T> * self().area() * sides) * radiance();
    }

    /// The radiance the light emits from its surface point h (a hit on it) toward the
    /// unit direction w (pointing away from the surface): L on an emitting side, else 0.
    [[nodiscard]] rgb<T> radiance(const hit<T>& h, const vec3<T>& w) const noexcept {
        return emitting_cosine(h.n, w, self().sides()) > T(0) ? radiance() : rgb<T>(0);
    }

    /// The radiance arriving at p along the unit direction l from this light alone
    /// (nothing else occluding): that of the light's first point on the ray (p, l), or 0
    /// when the ray misses it or meets a side that does not emit.
    [[nodiscard]] rgb<T> incident_radiance(const vec3<T>& p, const vec3<T>& l) const noexcept {
        const auto h = self().intersect(ray<T>{p, l});
        return h ? radiance(*h, -l) : rgb<T>(0);
    }

    /// The solid-angle density (1/sr) with which sample_incident(p, u) chooses the
    /// direction l, for uniform sampling by area: r^2 / (A cos_light) at the light's first
    /// point on the ray (p, l), 0 when the ray misses it or meets a side that does not
    /// emit (such samples are never returned).
    [[nodiscard]] T pdf_incident(const vec3<T>& p, const vec3<T>& l) const noexcept {
        const auto h = self().intersect(ray<T>{p, l});
        if (!h) return T(0);
        return solid_angle_pdf(h->t, emitting_cosine(h->n, vec3<T>(-l), self().sides()), self().area());
    }

    /// pdf_incident(p, l) for a ray from p along the unit direction l that the caller has
    /// already intersected with this light: h = intersect(ray{p, l}) (so h.t is the
    /// distance). The same density, without intersecting again.
    [[nodiscard]] T pdf_incident(const vec3<T>& p, const vec3<T>& l, const hit<T>& h) const noexcept {
        (void)p;
        return solid_angle_pdf(h.t, emitting_cosine(h.n, vec3<T>(-l), self().sides()), self().area());
    }

private:
    [[nodiscard]] const Light& self() const noexcept { return static_cast<const Light&>(*this); }
};

} // namespace shade::detail
