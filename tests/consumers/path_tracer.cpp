// A small path tracer written against shade with public API only, the way a renderer
// author would: the consumer tests build it from the installed package (find_package).
// It renders the enclosure: inside a closed box whose every wall is Lambertian of albedo
// 0.8 and emits radiance 1 toward the inside, the radiance is 1 / (1 - 0.8) = 5 in every
// direction (the emission plus its reflections, a geometric series). Exits 0 when the
// estimate agrees with 5 within 4 standard errors.
//
// Used: triangle_bvh (closest, any), triangle_light per wall triangle in any_light (its
// surface: intersect, radiance at a hit, pdf from a hit), power_light_sampler::from_lights,
// light_sample_context, the Lambertian BRDF's sample and pdf, power_heuristic (MIS),
// spawn_ray / spawn_ray_to (no epsilon) and sobol_sampler.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <span>
#include <vector>

#include <shade/shade.hpp>
#include <shade/geometry/triangle_bvh.hpp>
#include <shade/light/light_sampler.hpp>

namespace {

using T = double;
using vec3 = shade::vec3<T>;
using rgb = shade::rgb<T>;

// The box [-1, 1]^3 as 12 triangles wound so that their normals point inside.
std::vector<shade::triangle<T>> inward_box() {
    const vec3 c[8] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                       {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
    const int faces[6][4] = {{0, 1, 2, 3}, {4, 7, 6, 5}, {0, 4, 5, 1}, {3, 2, 6, 7}, {0, 3, 7, 4}, {1, 5, 6, 2}};
    std::vector<shade::triangle<T>> out;
    for (const auto& f : faces) {
        for (const auto& [a, b, d] : {std::array<int, 3>{f[0], f[1], f[2]}, std::array<int, 3>{f[0], f[2], f[3]}}) {
            shade::triangle<T> t{c[a], c[b], c[d]};
            // Point the normal at the centre.
            if (glm::dot(t.normal(), -(t.v0 + t.v1 + t.v2)) < 0) std::swap(t.v1, t.v2);
            out.push_back(t);
        }
    }
    return out;
}

} // namespace

int main() {
    const auto walls = inward_box();
    const shade::triangle_bvh<T> scene(walls);
    std::vector<shade::any_light<T>> lights;
    for (const auto& w : walls)
        lights.emplace_back(shade::triangle_light<T>::from_radiance(w.v0, w.v1, w.v2, rgb(1)));
    const auto choose = shade::power_light_sampler<T>::from_lights(std::span<const shade::any_light<T>>(lights), T(2));
    const shade::lambert<T> wall(rgb(0.8));
    shade::sobol_sampler<T> sampler(2024);

    // Radiance along r, one path: next-event estimation and BRDF sampling with the power
    // heuristic, Russian roulette from the third bounce.
    const auto radiance = [&](shade::ray<T> r) {
        rgb L(0), beta(1);
        T previous_pdf = 0; // 0: a camera ray
        vec3 previous_origin = r.origin;
        for (int bounce = 0; bounce < 256; ++bounce) {
            const auto h = scene.closest(r);
            if (!h) break; // the box is closed: never
            const shade::hit<T>& hit = h->hit;
            const shade::any_light<T>& emitter = lights[h->primitive];
            const vec3 v = -glm::normalize(r.direction);
            const rgb emitted = emitter.radiance(hit, v);
            if (previous_pdf == 0) {
                L += beta * emitted;
            } else {
                const T light_pdf = choose.probability(h->primitive) * emitter.pdf_incident(previous_origin, -v, hit);
                L += beta * emitted * shade::power_heuristic(previous_pdf, light_pdf);
            }
            const auto at = shade::surface_at(hit);
            const shade::light_sample_context<T> ctx{shade::offset_ray_origin(hit.p, hit.p_error, hit.n, at.n()),
                                                     at.n(), at.n()};
            // Next-event estimation toward one light, with a shadow ray from this surface to
            // the light's surface (both ends offset).
            const auto choice = choose.sample(sampler.next_1d());
            const auto u_light = sampler.next_2d();
            if (choice) {
                const auto& light = lights[choice->index];
                if (const auto ls = light.sample_incident(ctx, u_light)) {
                    const auto on_light = light.intersect(shade::spawn_ray(hit, ls->l));
                    if (on_light && !scene.any(shade::spawn_ray_to(hit, *on_light))) {
                        const T pdf = choice->probability * ls->pdf;
                        const T w = shade::power_heuristic(pdf, wall.pdf(ls->l, v, at));
                        L += beta * wall.f(ls->l, v, at) * ls->radiance * (glm::dot(at.n(), ls->l) * w / pdf);
                    }
                }
            }
            // The continuation.
            const T uc = sampler.next_1d();
            const auto u = sampler.next_2d();
            const T u_roulette = sampler.next_1d();
            const auto s = wall.sample(v, uc, u, at);
            if (!s) break;
            beta *= s->weight;
            previous_pdf = s->pdf;
            r = shade::spawn_ray(hit, s->l);
            previous_origin = r.origin;
            if (bounce >= 2) {
                const T q = std::min(T(1), std::max({beta.x, beta.y, beta.z}));
                if (u_roulette >= q) break;
                beta /= q;
            }
        }
        return L;
    };

    // 1024 "pixels": directions from a point off the centre, 64 samples each; each pixel's
    // mean is an independent estimate of 5 (the sampler scrambles each pixel apart).
    const int pixels = 1024, spp = 64;
    double sum = 0, sum2 = 0;
    for (int p = 0; p < pixels; ++p) {
        double mean = 0;
        for (int k = 0; k < spp; ++k) {
            sampler.start_pixel_sample(std::uint32_t(p), 0, std::uint32_t(k));
            const vec3 d = shade::square_to_uniform_sphere(sampler.next_2d());
            mean += radiance(shade::ray<T>{vec3(0.2, -0.3, 0.1), d}).y / spp;
        }
        sum += mean;
        sum2 += mean * mean;
    }
    const double mean = sum / pixels;
    const double se = std::sqrt(std::max(sum2 / pixels - mean * mean, 0.0) / (pixels - 1));
    const bool ok = std::abs(mean - 5) <= 4 * se && se < 0.05;
    std::printf("shade %s path tracer consumer: enclosure radiance %.4f +- %.4f (exact 5): %s\n", SHADE_VERSION_STRING,
                mean, se, ok ? "ok" : "WRONG");
    return ok ? 0 : 1;
}
