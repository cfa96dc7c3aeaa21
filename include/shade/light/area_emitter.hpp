#pragma once
// shade::detail::area_emitter: what the area lights (rectangle, disk, sphere) answer the
// same way, written once: they are visible, uniformly emitting surfaces.

#include <cmath>
#include <concepts>
#include <optional>

#include <shade/core/error.hpp>
#include <shade/core/math.hpp>
#include <shade/core/types.hpp>
#include <shade/geometry/hit.hpp>
#include <shade/geometry/ray.hpp>
#include <shade/light/emission.hpp>
#include <shade/light/incident_sample.hpp>
#include <shade/light/sample_context.hpp>

namespace shade::detail {

/// Base of the area lights (CRTP). Light provides intersect(ray) -> std::optional<hit<T>>
/// (the light as geometry), area(), sides(), emitted() and sample_incident(p, u), and
/// brings the base's sample_incident and pdf_incident into scope with using-declarations
/// (the forms that take a shade::light_sample_context). Each point of the surface
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
    [[nodiscard]] rgb<T> power() const noexcept { return emitting_area_factor() * radiance(); }

    /// power(), the same for every scene_radius (shade::emitter's uniform form). Throws
    /// shade::invalid_parameter naming "scene_radius" unless it is finite and >= 0.
    [[nodiscard]] rgb<T> power(T scene_radius) const {
        (void)require_scene_radius(scene_radius);
        return power();
    }

    /// sample_incident(ctx.p, u): the surface at ctx.p does not change the sampling.
    [[nodiscard]] std::optional<incident_sample<T>> sample_incident(const light_sample_context<T>& ctx,
                                                                    const vec2<T>& u) const noexcept {
        return self().sample_incident(ctx.p, u);
    }

    /// pdf_incident(ctx.p, l), the density of sample_incident(ctx, .).
    [[nodiscard]] T pdf_incident(const light_sample_context<T>& ctx, const vec3<T>& l) const noexcept {
        return self().pdf_incident(ctx.p, l);
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

protected:
    /// pi A per emitting side: power() / radiance() (integrating L cos over the hemisphere
    /// gives pi L).
    [[nodiscard]] T emitting_area_factor() const noexcept {
        return pi<T> * self().area() * (self().sides() == sidedness::two_sided ? T(2) : T(1));
    }

    /// The emission of radiance Phi / emitting_area_factor(), for from_power; throws
    /// invalid_parameter naming "power" (detail::physical_emission, or a factor that overflows).
    [[nodiscard]] emission<T> emission_of_power(const rgb<T>& power) const {
        if (!std::isfinite(emitting_area_factor()))
            throw invalid_parameter("power", "needs a finite pi x area per side", to_text(self().area()));
        return physical_emission("power", power, emitting_area_factor());
    }

private:
    [[nodiscard]] const Light& self() const noexcept { return static_cast<const Light&>(*this); }
};

} // namespace shade::detail
