#pragma once
// The reference tracer's path-tracing integrator: next-event estimation (a light sampled at
// every vertex) and BRDF sampling, combined by multiple importance sampling with the power
// heuristic, Russian roulette, any number of bounces. Physical units throughout (lights
// through shade::emitter, materials through shade::any_brdf).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

#include <glm/geometric.hpp>

#include <shade/core/random.hpp>
#include <shade/geometry/ray.hpp>

#include "scene.hpp"

namespace tracer {

/// Which strategies estimate the light arriving at each vertex.
///   mis:   both, weighted by the power heuristic (the default);
///   light: light sampling only (emitters that a BRDF-sampled ray hits count nothing);
///   brdf:  BRDF sampling only (no shadow rays toward lights; delta lights are then
///          invisible, since no sampled direction can hit them).
enum class strategy { mis, light, brdf };

/// Settings of the path integrator.
struct path_options {
    int max_bounces = 1024;     ///< scattering events at most (1: direct lighting only)
    int roulette_after = 3;     ///< Russian roulette from this bounce on
    strategy sampling = strategy::mis;
};

namespace detail {

/// The power heuristic with exponent 2 (Veach 1997, "Robust Monte Carlo Methods for Light
/// Transport Simulation", PhD thesis, Stanford, eq. 9.13, beta = 2): the weight of a
/// sample drawn with density pdf_a when the other strategy would have drawn it with
/// pdf_b, pdf_a^2 / (pdf_a^2 + pdf_b^2). Both densities are in 1/sr and include the
/// probability of choosing the light.
inline real power_heuristic(real pdf_a, real pdf_b) {
    const real a = pdf_a * pdf_a;
    const real b = pdf_b * pdf_b;
    if (!(a > 0)) return 0;
    return a / (a + b);
}

/// The origin of rays leaving surface point p on the side of the unit normal n, pushed off
/// the surface by 2^-32 relative to |p| (the scene's self-intersection margin, see
/// scene::visible).
inline vec3 offset_origin(const vec3& p, const vec3& n) {
    const real scale = std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z), real(1)});
    return p + n * (scale * 0x1p-32);
}

/// Largest channel.
inline real max_channel(const rgb& c) { return std::max(c.x, std::max(c.y, c.z)); }

} // namespace detail

/// The radiance arriving along camera ray r (W/(m^2 sr)), estimated by one path. Objects
/// without a physical material (object::brdf) absorb everything.
///
/// At every vertex the direct light is estimated twice and the two combined by MIS
/// (Veach 1997, ch. 9): (a) next-event estimation: one light chosen uniformly (probability
/// 1/N), sample_incident toward it, a shadow ray, weight w_l = power_heuristic(P_l, P_f);
/// (b) the BRDF-sampled continuation ray: when it hits an emitter (or leaves the scene
/// into an environment light), its radiance counts with weight power_heuristic(P_f, P_l),
/// P_l = pdf_incident / N at the previous vertex. Delta lights are reached by (a) alone,
/// with weight 1; the camera ray's first hit counts with weight 1. Throughput beta is
/// multiplied by each BRDF sample's weight f |cos| / pdf; from bounce roulette_after on,
/// the path continues with probability q = min(1, max channel of beta) and beta is
/// divided by q (Russian roulette, Arvo, Kirk 1990, "Particle Transport and Image
/// Synthesis", SIGGRAPH), which keeps the estimate unbiased.
inline rgb trace_path(const scene& s, shade::ray<real> r, shade::rng& random, const path_options& options) {
    rgb radiance(0);
    rgb beta(1);
    const std::size_t light_count = s.lights.size();
    const real pick = light_count > 0 ? real(1) / real(light_count) : real(0);
    real previous_brdf_pdf = 0; // 0: the ray came from the camera
    for (int bounce = 0;; ++bounce) {
        const bool from_camera = previous_brdf_pdf == 0;
        // The weight of emission found by this ray, against light sampling at its origin.
        const auto emission_weight = [&](const shade::any_light<real>& light) -> real {
            if (from_camera || options.sampling == strategy::brdf) return 1;
            if (options.sampling == strategy::light) return 0;
            return detail::power_heuristic(previous_brdf_pdf, pick * light.pdf_incident(r.origin, r.direction));
        };
        const auto h = s.intersect(r);
        if (!h) {
            for (const auto& light : s.lights)
                if (std::holds_alternative<shade::environment_light<real>>(light.get()))
                    radiance += beta * emission_weight(light) * light.incident_radiance(r.origin, r.direction);
            break;
        }
        const object& o = s.objects[h->object];
        if (o.emitter >= 0) {
            const auto& light = s.lights[std::size_t(o.emitter)];
            radiance += beta * emission_weight(light) * light.incident_radiance(r.origin, r.direction);
        }
        if (!o.brdf || bounce >= options.max_bounces) break;

        const auto at = surface_point::at(h->p, h->shading_n);
        const vec3 v = -r.direction;
        const vec3 origin = detail::offset_origin(h->p, h->geometric_n);

        // (a) Next-event estimation.
        if (options.sampling != strategy::brdf && light_count > 0) {
            const std::size_t k = std::min(light_count - 1, std::size_t(random.uniform<real>() * real(light_count)));
            const auto& light = s.lights[k];
            const vec2 u(random.uniform<real>(), random.uniform<real>());
            const auto ls = light.sample_incident(origin, u);
            if (ls && glm::dot(ls->l, h->geometric_n) > 0) {
                const rgb f = o.brdf->f(ls->l, v, at);
                const real cos_l = std::abs(glm::dot(at.n(), ls->l));
                const shade::ray<real> shadow{origin, ls->l, 0,
                                              std::isinf(ls->distance) ? ls->distance : ls->distance * (1 - 1e-9)};
                if (f != rgb(0) && !s.occluded(shadow)) {
                    if (ls->delta) {
                        radiance += beta * f * ls->radiance * (cos_l / pick);
                    } else {
                        const real pdf_l = pick * ls->pdf;
                        const real w = options.sampling == strategy::mis
                                           ? detail::power_heuristic(pdf_l, o.brdf->pdf(ls->l, v, at))
                                           : real(1);
                        radiance += beta * f * ls->radiance * (cos_l * w / pdf_l);
                    }
                }
            }
        }

        // (b) BRDF sampling: the continuation, which also finds emitters.
        const real uc = random.uniform<real>();
        const vec2 u(random.uniform<real>(), random.uniform<real>());
        const auto bs = o.brdf->sample(v, uc, u, at);
        if (!bs || !(glm::dot(bs->l, h->geometric_n) > 0)) break;
        beta *= bs->weight;
        previous_brdf_pdf = bs->pdf;
        r = shade::ray<real>{origin, bs->l};
        if (bounce + 1 >= options.roulette_after) {
            const real q = std::min(real(1), detail::max_channel(beta));
            if (!(q > 0) || random.uniform<real>() >= q) break;
            beta /= q;
        }
    }
    return radiance;
}

} // namespace tracer
