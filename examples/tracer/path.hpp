#pragma once
// The reference tracer's path-tracing integrator: next-event estimation (a light sampled at
// every vertex) and BSDF sampling, combined by multiple importance sampling with the power
// heuristic, Russian roulette, any number of bounces. Physical units throughout (lights
// through shade::emitter, materials through shade::any_brdf, glass through shade's BSDFs).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <variant>

#include <glm/exponential.hpp>
#include <glm/geometric.hpp>

#include <shade/bsdf/bsdf.hpp>
#include <shade/core/mis.hpp>
#include <shade/core/sampler.hpp>
#include <shade/geometry/ray.hpp>
#include <shade/geometry/spawn.hpp>
#include <shade/light/light_sampler.hpp>
#include <shade/light/sample_context.hpp>

#include "light_choice.hpp"
#include "scene.hpp"

namespace tracer {

/// Which strategies estimate the light arriving at each vertex.
///   mis:   both, weighted by the power heuristic (the default);
///   light: light sampling only (emitters that a BSDF-sampled ray hits count nothing,
///          except after the camera or a delta lobe);
///   brdf:  BSDF sampling only (no shadow rays toward lights; delta lights are then
///          invisible, since no sampled direction can hit them).
enum class strategy { mis, light, brdf };

/// Settings of the path integrator.
struct path_options {
    int max_bounces = 1024;     ///< scattering events at most (1: direct lighting only)
    int roulette_after = 3;     ///< Russian roulette from this bounce on
    strategy sampling = strategy::mis;
    light_selection lights = light_selection::bvh; ///< how next-event estimation picks its light
};

namespace detail {

/// Largest channel.
inline real max_channel(const rgb& c) { return std::max(c.x, std::max(c.y, c.z)); }

/// The surface point an OpenPBR object is evaluated at: the surface's own (outward) normal,
/// and a tangent running around the vertical axis (cross(+y, n), a sphere's dp/dphi about
/// +y: the direction anisotropic roughness stretches along); where that is zero (at the
/// poles) the arbitrary frame of surface_point::at.
inline surface_point openpbr_point(const scene_hit& h) {
    return surface_point::at(h.p, h.outward_n, glm::cross(vec3(0, 1, 0), h.outward_n), vec2(0));
}

} // namespace detail

/// The radiance arriving along camera ray r (W/(m^2 sr)), estimated by one path. Objects
/// without a physical material (object::brdf, object::glass, object::rough_glass or
/// object::openpbr) absorb everything.
///
/// At every vertex with a density (a BRDF, or rough glass) the direct light is estimated
/// twice and the two combined by MIS (Veach 1997, ch. 9; shade::power_heuristic): (a)
/// next-event estimation: one light chosen by `lights` (uniformly, by power or by the light
/// BVH; probability P(i | vertex)), sample_incident toward it, a shadow ray
/// (scene::light_visible: for lights that are scene geometry, whether the first surface
/// along it is the light), weight w_l = power_heuristic(P_l, P_f); (b) the BSDF-sampled
/// continuation ray: when it hits an emitter (or leaves the scene into an environment
/// light), its radiance counts with weight power_heuristic(P_f, P_l),
/// P_l = pdf_incident x P(i | previous vertex). Delta lights
/// are reached by (a) alone, with weight 1; the camera ray's first hit counts with weight 1.
/// Above a BRDF, light and continuation stay above the geometric normal. At rough glass
/// (shade::rough_dielectric, evaluated with the surface's outward normal, so that the side
/// of v says whether the path is inside the medium) both go to either side: a light behind
/// the interface contributes f |n·l| with f the transmission in radiance mode, the shadow
/// ray and the continuation start on l's side, and lights are sampled without a surface
/// (the whole sphere of directions). Throughput beta is multiplied by each sample's weight
/// f |cos| / pdf; from bounce roulette_after on, the path continues with probability
/// q = min(1, max channel of beta times eta_scale, the product of eta^2 over its
/// refractions) and beta is divided by q (Russian roulette, Arvo, Kirk 1990, "Particle
/// Transport and Image Synthesis", SIGGRAPH), which keeps the estimate unbiased. Smooth
/// glass and thin panes (object::glass) scatter by their delta lobes alone: no light
/// sampling there, and emission found after them counts whole.
///
/// An OpenPBR surface (object::openpbr, shade::openpbr_surface, evaluated at
/// detail::openpbr_point) is a vertex with a density like rough glass when light passes
/// through it (object::openpbr_two_sided: lights sampled on both sides, the continuation on
/// either), like a BRDF otherwise (but with the outward normal). Its emission toward the ray
/// counts whole wherever a ray hits it (it is not among the sampled lights). A sample from
/// one of its delta lobes (bsdf_flags::specular) has no density: the emission the next ray
/// finds then counts whole, as after smooth glass. A transmission sample that enters it (l
/// against the outward normal, not thin-walled) puts the path inside its interior medium,
/// one that leaves takes it out; inside, each segment of length t multiplies beta by
/// exp(-object::openpbr_absorption t) (absorption only: the medium's scattering is not
/// simulated).
///
/// The random numbers come from `sampler`, in the same order at every vertex (the
/// dimensions of a shade::sampler): the light's index (1D), the point on it (2D), the
/// BSDF's lobe (1D) and direction (2D), Russian roulette (1D); a strategy that skips a
/// draw still takes its numbers, so each decision keeps its dimension.
template <shade::sampler S>
rgb trace_path(const scene& s, const light_chooser& lights, shade::ray<real> r, S& sampler,
               const path_options& options) {
    rgb radiance(0);
    rgb beta(1);
    // The scene's lights and, when it has one, its environment map (index lights.size()).
    const std::size_t map_index = s.lights.size();
    real previous_brdf_pdf = 0; // 0: the ray came from the camera or a specular bounce
    // The product of eta^2 over the refractions so far: radiance-mode weights scale by
    // 1 / eta^2 entering a denser medium, which Russian roulette must not mistake for lost
    // energy (pbrt-v4's etaScale: Pharr, Jakob, Humphreys 2023, sec. 13.4.3).
    real eta_scale = 1;
    shade::light_sample_context<real> previous{};   // the vertex the ray left (for light pdfs)
    rgb absorption(0); // of the OpenPBR interior medium the ray travels in (0: none)
    for (int bounce = 0;; ++bounce) {
        const bool from_camera = previous_brdf_pdf == 0;
        // The weight of emission found by this ray, against light sampling at its origin,
        // for the light of index light_index that would have drawn the ray's direction with
        // density light_pdf.
        const auto weight = [&](std::size_t light_index, real light_pdf) -> real {
            if (from_camera || options.sampling == strategy::brdf) return 1;
            if (options.sampling == strategy::light) return 0;
            return shade::power_heuristic(previous_brdf_pdf, lights.probability(previous, light_index) * light_pdf);
        };
        const auto emission_weight = [&](std::size_t light_index) -> real {
            return weight(light_index, s.lights[light_index].pdf_incident(previous, r.direction));
        };
        const auto h = s.intersect(r);
        if (!h) {
            for (std::size_t i = 0; i < s.lights.size(); ++i)
                if (std::holds_alternative<shade::environment_light<real>>(s.lights[i].get()))
                    radiance += beta * emission_weight(i) * s.lights[i].incident_radiance(r.origin, r.direction);
            if (s.environment_map) {
                const auto& map = *s.environment_map;
                radiance += beta * weight(map_index, map.pdf_incident(previous.p, r.direction)) *
                            map.incident_radiance(r.origin, r.direction);
            }
            break;
        }
        if (absorption != rgb(0)) beta *= glm::exp(-absorption * h->t);
        const object& o = s.objects[h->object];
        if (const int emitter = o.light_at(h->triangle); emitter >= 0) {
            const auto i = std::size_t(emitter);
            radiance += beta * emission_weight(i) * s.lights[i].incident_radiance(r.origin, r.direction);
        }
        if (o.openpbr) radiance += beta * o.openpbr->emission(-r.direction, detail::openpbr_point(*h));
        if (o.glass) {
            // A delta dielectric (smooth interface or thin pane): delta lobes only, so no light
            // sampling here (no direction of it has a density), and the emission the next
            // ray finds counts whole (previous_brdf_pdf = 0, as after the camera). The
            // sample's weight carries the Fresnel term and, in radiance mode, the (eta_v /
            // eta_l)^2 of a refraction; the new ray leaves on l's side of the surface,
            // inside or outside. The light-sampling numbers are drawn and not used, so that
            // every vertex takes the same dimensions.
            if (bounce >= options.max_bounces) break;
            (void)sampler.next_1d();
            (void)sampler.next_2d();
            const real uc = sampler.next_1d();
            const vec2 u = sampler.next_2d();
            const real u_roulette = sampler.next_1d();
            const auto outside = surface_point::at(h->p, h->outward_n);
            const auto bs = std::visit(
                [&](const auto& glass) {
                    return shade::sample_bsdf(glass, vec3(-r.direction), uc, u, outside, shade::transport_mode::radiance);
                },
                *o.glass);
            if (!bs) break;
            beta *= bs->weight;
            if (shade::is_transmission(bs->flags)) eta_scale *= bs->eta * bs->eta;
            previous_brdf_pdf = 0;
            previous = {};
            r = shade::ray<real>{shade::offset_ray_origin(h->p, h->p_error, h->outward_n, bs->l), bs->l};
            if (bounce + 1 >= options.roulette_after) {
                const real q = std::min(real(1), detail::max_channel(beta) * eta_scale);
                if (!(q > 0) || u_roulette >= q) break;
                beta /= q;
            }
            continue;
        }
        if ((!o.brdf && !o.rough_glass && !o.openpbr) || bounce >= options.max_bounces) break;

        // A vertex with a density: a BRDF or an opaque OpenPBR surface (light arrives and
        // leaves above the geometric normal), or rough glass or an OpenPBR surface that
        // light passes through (either side of the interface).
        const bool rough = o.rough_glass.has_value() || (o.openpbr && o.openpbr_two_sided);
        const vec3 v = -r.direction;
        // Rough glass and OpenPBR are evaluated with the surface's own normal, whose side
        // (outside of the medium) says on which side v and l are, so the path's medium
        // follows from the hit; a BRDF with the shading normal on the viewer's side.
        const auto at = o.openpbr ? detail::openpbr_point(*h) : surface_point::at(h->p, rough ? h->outward_n : h->shading_n);
        // Rays leave on the side of their direction, off the surface by the hit point's
        // rounding bound (shade/geometry/spawn.hpp); after a BRDF always above the geometric
        // normal (the path ends below it).
        const vec3 above = shade::offset_ray_origin(h->p, h->p_error, h->geometric_n, h->geometric_n);
        const auto origin_toward = [&](const vec3& l) {
            return rough ? shade::offset_ray_origin(h->p, h->p_error, h->outward_n, l) : above;
        };
        const auto can_leave = [&](const vec3& l) {
            return rough ? glm::dot(l, h->outward_n) != 0 : glm::dot(l, h->geometric_n) > 0;
        };
        const auto f_at = [&](const vec3& l) {
            if (o.openpbr) return o.openpbr->f(l, v, at);
            return o.rough_glass ? o.rough_glass->f(l, v, at) : o.brdf->f(l, v, at);
        };
        const auto pdf_at = [&](const vec3& l) {
            if (o.openpbr) return o.openpbr->pdf(l, v, at);
            return o.rough_glass ? o.rough_glass->pdf(l, v, at) : o.brdf->pdf(l, v, at);
        };

        // (a) Next-event estimation.
        // The lights see the surface (shade::light_sample_context): above a BRDF the
        // environment samples only the hemisphere the path can continue into; at rough
        // glass every direction is wanted (zero normals: no surface), since light arriving
        // from behind the interface is transmitted toward v.
        const shade::light_sample_context<real> here =
            rough ? shade::light_sample_context<real>{h->p, vec3(0), vec3(0)}
                  : shade::light_sample_context<real>{above, h->geometric_n, h->shading_n};
        const real u_light = sampler.next_1d();
        const vec2 u_point = sampler.next_2d();
        const auto choice = lights.sample(here, u_light);
        if (options.sampling != strategy::brdf && choice) {
            const real pick = choice->probability;
            const auto ls = choice->index == map_index ? s.environment_map->sample_incident(here.p, u_point)
                                                       : s.lights[choice->index].sample_incident(here, u_point);
            if (ls && can_leave(ls->l)) {
                // In radiance mode: through rough glass f carries the (eta_v / eta_l)^2 of a
                // refraction (shade/bsdf/bsdf.hpp).
                const rgb f = f_at(ls->l);
                const real cos_l = std::abs(glm::dot(at.n(), ls->l));
                if (f != rgb(0) && s.light_visible(choice->index, origin_toward(ls->l), ls->l, ls->distance)) {
                    if (ls->delta) {
                        radiance += beta * f * ls->radiance * (cos_l / pick);
                    } else {
                        const real pdf_l = pick * ls->pdf;
                        const real w = options.sampling == strategy::mis ? shade::power_heuristic(pdf_l, pdf_at(ls->l))
                                                                         : real(1);
                        radiance += beta * f * ls->radiance * (cos_l * w / pdf_l);
                    }
                }
            }
        }

        // (b) BSDF sampling: the continuation, which also finds emitters.
        const real uc = sampler.next_1d();
        const vec2 u = sampler.next_2d();
        const real u_roulette = sampler.next_1d();
        const auto bs = o.openpbr       ? o.openpbr->sample(v, uc, u, at, shade::transport_mode::radiance)
                        : o.rough_glass ? shade::sample_bsdf(*o.rough_glass, v, uc, u, at, shade::transport_mode::radiance)
                                        : shade::sample_bsdf(*o.brdf, v, uc, u, at, shade::transport_mode::radiance);
        if (!bs || !can_leave(bs->l)) break;
        beta *= bs->weight;
        if (shade::is_transmission(bs->flags)) {
            eta_scale *= bs->eta * bs->eta;
            if (o.openpbr) absorption = glm::dot(bs->l, h->outward_n) < 0 ? o.openpbr_absorption : rgb(0);
        }
        const bool delta = shade::is_specular(bs->flags);
        previous_brdf_pdf = delta ? real(0) : bs->pdf;
        previous = delta ? shade::light_sample_context<real>{} : here;
        r = shade::ray<real>{origin_toward(bs->l), bs->l};
        if (bounce + 1 >= options.roulette_after) {
            const real q = std::min(real(1), detail::max_channel(beta) * eta_scale);
            if (!(q > 0) || u_roulette >= q) break;
            beta /= q;
        }
    }
    return radiance;
}

} // namespace tracer
