#pragma once
// The reference tracer's render loop: primary rays through the camera, direct lighting
// with shadow rays, several samples per pixel, rows shared between threads, and the
// linear-radiance -> exposure -> tone map -> sRGB 8-bit chain.
//
// Determinism: every pixel sample draws its numbers from a sampler started at (pixel,
// sample index) and the classic integrator from a generator seeded by the pixel's index
// (both with the render seed), so the image does not depend on which thread rendered which
// row, nor on the number of threads.

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <thread>
#include <vector>

#include <shade/color/srgb.hpp>
#include <shade/core/sampler.hpp>
#include <shade/core/sobol.hpp>

#include "support/image.hpp"
#include "support/progress.hpp"

#include "path.hpp"
#include "scene.hpp"

namespace tracer {

/// How radiance is estimated: direct lighting in the classic mode (shade::lit, area lights
/// sampled n x n), or path tracing in physical units (tracer::trace_path).
enum class integrator { direct, path };

/// Where the path integrator's random numbers come from (the classic direct integrator
/// always uses a PCG32 stream per pixel for its area-light strata):
///   independent: shade::independent_sampler, independent uniform numbers (the default);
///   sobol:       shade::sobol_sampler, Owen-scrambled Sobol points (Burley 2020), lower
///                error at the same spp for the smooth parts of the integrand; use spp
///                that are powers of two.
enum class sampler_kind { independent, sobol };

/// Settings of one render.
struct render_options {
    int width = 480;
    int height = 270;
    int spp = 4;            ///< samples per pixel (jittered within the pixel)
    int threads = 0;        ///< 0: all hardware threads
    std::uint64_t seed = 1; ///< seed of all per-pixel generators
    lighting_options lighting{};
    integrator method = integrator::direct;
    path_options path{};    ///< settings of the path integrator
    sampler_kind sampler = sampler_kind::independent; ///< the path integrator's numbers (and the pixel jitter)
    /// Whether samples are spread over the pixel (true) or all go through its centre
    /// (false: the estimate is then of the radiance along one ray, without the variance of
    /// integrating over the pixel's area, e.g. to compare light-transport estimators).
    bool jitter = true;
    bool progress = false;  ///< a progress bar on stderr, when it is a terminal, once a render passes 1 s
};

/// A linear-radiance image, row-major from the top row.
struct radiance_image {
    int width = 0;
    int height = 0;
    std::vector<rgb> pixels;
    [[nodiscard]] const rgb& at(int x, int y) const { return pixels[std::size_t(y) * std::size_t(width) + std::size_t(x)]; }
};

/// Radiance along one camera ray: the shaded closest hit, or the background.
inline rgb trace(const scene& s, const shade::ray<real>& r, shade::rng& random, const lighting_options& options) {
    const auto h = s.intersect(r);
    if (!h) return s.background;
    const vec3 v = -glm::normalize(r.direction);
    return s.shade_hit(*h, v, random, options);
}

/// Sample `k` of pixel (x, y): a camera ray through a point of the pixel (its centre when
/// spp is 1 or options.jitter is false, else jittered by the sampler's first 2D draw) and
/// the radiance the chosen integrator estimates along it. The path integrator draws its
/// numbers from `sampler` (started here at (x, y, k)); the classic one from `random`.
template <shade::sampler S>
rgb sample_pixel(const scene& s, const light_chooser& lights, const render_options& options, int x, int y, int k,
                 S& sampler, shade::rng& random) {
    sampler.start_pixel_sample(std::uint32_t(x), std::uint32_t(y), std::uint32_t(k));
    const bool centre = options.spp == 1 || !options.jitter;
    const vec2 jitter = sampler.next_2d();
    const real jx = centre ? real(0.5) : jitter.x;
    const real jy = centre ? real(0.5) : jitter.y;
    const auto r = s.camera->ray_for_raster(real(x) + jx, real(y) + jy, options.width, options.height);
    if (options.method == integrator::path) return trace_path(s, lights, r, sampler, options.path);
    return trace(s, r, random, options.lighting);
}

namespace detail {

/// Calls f with the sampler options.sampler names, seeded by options.seed.
template <class F>
decltype(auto) with_sampler(const render_options& options, F&& f) {
    if (options.sampler == sampler_kind::sobol) {
        shade::sobol_sampler<real> sampler(options.seed);
        return f(sampler);
    }
    shade::independent_sampler<real> sampler(options.seed);
    return f(sampler);
}

} // namespace detail

/// Renders the scene with its camera. Throws std::invalid_argument for a scene without a
/// camera or non-positive sizes.
inline radiance_image render(const scene& s, const render_options& options) {
    if (!s.camera) throw std::invalid_argument("scene '" + s.name + "' has no camera");
    if (options.width <= 0 || options.height <= 0 || options.spp <= 0)
        throw std::invalid_argument("width, height and spp must be positive");
    radiance_image image;
    image.width = options.width;
    image.height = options.height;
    image.pixels.assign(std::size_t(options.width) * std::size_t(options.height), rgb(0));

    const unsigned hardware = std::max(1u, std::thread::hardware_concurrency());
    const unsigned threads = options.threads > 0 ? unsigned(options.threads) : hardware;
    const light_chooser lights(s, options.path.lights);
    std::atomic<int> next_row{0};
    // Rows are the bar's steps; it draws only on a terminal (support/progress.hpp).
    shade::examples::progress bar("trace", std::uint64_t(options.height), options.progress);

    const auto work = [&] {
        detail::with_sampler(options, [&](auto& sampler) {
            for (int y = next_row++; y < options.height; y = next_row++) {
                for (int x = 0; x < options.width; ++x) {
                    const std::uint64_t index = std::uint64_t(y) * std::uint64_t(options.width) + std::uint64_t(x);
                    shade::rng random(options.seed, index);
                    rgb sum(0);
                    for (int k = 0; k < options.spp; ++k) sum += sample_pixel(s, lights, options, x, y, k, sampler, random);
                    image.pixels[std::size_t(index)] = sum / real(options.spp);
                }
                bar.advance();
            }
        });
    };

    std::vector<std::thread> pool;
    for (unsigned t = 1; t < threads; ++t) pool.emplace_back(work);
    work();
    for (auto& t : pool) t.join();
    return image;
}

/// Exposure and tone mapping: c' = c * exposure, then Reinhard's global operator on
/// luminance with a white point (Reinhard, Stark, Shirley, Ferwerda 2002, "Photographic
/// Tone Reproduction for Digital Images", SIGGRAPH, eq. 4): L_d = L (1 + L / L_white^2) /
/// (1 + L), applied by scaling the colour by L_d / L so hues are kept. Returns linear RGB
/// in [0, 1] for values up to L_white.
inline rgb tone_map(const rgb& c, real exposure, real white = 4) {
    const rgb e = c * exposure;
    // Rec. 709 / sRGB luminance weights (IEC 61966-2-1, the Y row of the RGB->XYZ matrix).
    const real L = 0.2126 * e.x + 0.7152 * e.y + 0.0722 * e.z;
    if (!(L > 0)) return rgb(0);
    const real Ld = L * (1 + L / (white * white)) / (1 + L);
    return glm::clamp(e * (Ld / L), rgb(0), rgb(1));
}

/// The 8-bit sRGB image of a radiance image after exposure and tone map.
inline shade::examples::image to_srgb8(const radiance_image& radiance, real exposure = 1) {
    auto out = shade::examples::image::filled(radiance.width, radiance.height);
    for (int y = 0; y < radiance.height; ++y)
        for (int x = 0; x < radiance.width; ++x)
            out.set(x, y, shade::encode_srgb8(tone_map(radiance.at(x, y), exposure)));
    return out;
}

} // namespace tracer
