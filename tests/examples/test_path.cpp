// The path integrator of the reference tracer: scenes whose every pixel is known exactly
// (furnace 1, enclosure 5), and that the checks catch a biased integrator.

#include <cmath>
#include <cstdint>
#include <vector>

#include <doctest/doctest.h>

#include <shade/core/random.hpp>

#include "tracer/path.hpp"
#include "tracer/physical_scenes.hpp"
#include "tracer/render.hpp"

namespace {

using tracer::real;
using tracer::rgb;

// Per-pixel mean and standard error of the mean, from spp independent samples of each
// pixel (the same generators and jitter as tracer::render).
struct pixel_estimate {
    rgb mean{0};
    rgb standard_error{0};
};

struct image_estimate {
    std::vector<pixel_estimate> pixels;
    rgb mean{0};           ///< mean over every sample of the image
    rgb standard_error{0}; ///< its standard error
};

image_estimate estimate(const tracer::scene& s, const tracer::render_options& options) {
    image_estimate out;
    rgb sum(0), sum2(0);
    const double n_total = double(options.width) * double(options.height) * double(options.spp);
    for (int y = 0; y < options.height; ++y) {
        for (int x = 0; x < options.width; ++x) {
            const std::uint64_t index = std::uint64_t(y) * std::uint64_t(options.width) + std::uint64_t(x);
            shade::rng random(options.seed, index);
            rgb p_sum(0), p_sum2(0);
            for (int k = 0; k < options.spp; ++k) {
                const rgb c = tracer::sample_pixel(s, options, x, y, random);
                p_sum += c;
                p_sum2 += c * c;
            }
            sum += p_sum;
            sum2 += p_sum2;
            pixel_estimate e;
            const real n = real(options.spp);
            e.mean = p_sum / n;
            const rgb variance = glm::max(p_sum2 / n - e.mean * e.mean, rgb(0)) * (n / (n - 1));
            e.standard_error = glm::sqrt(variance / n);
            out.pixels.push_back(e);
        }
    }
    out.mean = sum / real(n_total);
    const rgb variance = glm::max(sum2 / real(n_total) - out.mean * out.mean, rgb(0));
    out.standard_error = glm::sqrt(variance / real(n_total));
    return out;
}

tracer::render_options path_options(int width, int height, int spp) {
    tracer::render_options o;
    o.width = width;
    o.height = height;
    o.spp = spp;
    o.threads = 1;
    o.method = tracer::integrator::path;
    return o;
}

// The image mean within 3 standard errors of `expected` in every channel, and no pixel
// beyond 5 of its own (a pixel whose samples are all equal must equal `expected` up to
// rounding).
void check_constant_image(const image_estimate& e, real expected) {
    for (int k = 0; k < 3; ++k) {
        CAPTURE(k);
        CHECK(std::abs(e.mean[k] - expected) <= 3 * e.standard_error[k]);
        int outliers = 0;
        for (const auto& p : e.pixels)
            if (std::abs(p.mean[k] - expected) > 5 * p.standard_error[k] + 1e-9 * expected) ++outliers;
        CHECK(outliers == 0);
    }
}

} // namespace

TEST_CASE("path: the Lambert furnace (k_d = 1 in radiance 1) is 1 in every pixel") {
    const auto s = tracer::make_furnace(real(8) / real(6), false);
    const auto e = estimate(s, path_options(8, 6, 64));
    check_constant_image(e, 1);
    // Some pixels see the sphere (their samples vary) and some the environment only.
    int varying = 0;
    for (const auto& p : e.pixels) varying += p.standard_error.x > 0;
    CHECK(varying > 10);
    CHECK(varying < 48);
}

TEST_CASE("path: the enclosure (albedo 0.8, emission 1) is 1 / (1 - 0.8) = 5 in every pixel") {
    // Every bounce adds 0.8^k of the emission: 1 + 0.8 + 0.8^2 + ... = 5. Paths are ended
    // by Russian roulette only, so this checks every bounce and the roulette's 1 / q.
    const auto s = tracer::make_enclosure(real(8) / real(6));
    const auto e = estimate(s, path_options(8, 6, 64));
    check_constant_image(e, 5);
}

TEST_CASE("path: the checks above catch a biased integrator") {
    // Stopping after 4 bounces loses 0.8^5 x 5 = 1.6 of the enclosure's 5.
    const auto s = tracer::make_enclosure(real(8) / real(6));
    auto options = path_options(8, 6, 64);
    options.path.max_bounces = 4;
    const auto e = estimate(s, options);
    CHECK(std::abs(e.mean.x - 5) > 3 * e.standard_error.x);
}
