// The path integrator of the reference tracer: scenes whose every pixel is known exactly
// (furnace 1, enclosure 5), that the checks catch a biased integrator, MIS against light
// and BRDF sampling alone on the veach scene, and the error falling as 1 / sqrt(spp).

#include <algorithm>
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

namespace {

// Mean squared difference between two radiance images over the pixels where mask[i] is
// true.
double mse(const tracer::radiance_image& a, const tracer::radiance_image& b, const std::vector<bool>& mask) {
    double sum = 0;
    int count = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) {
        if (!mask[i]) continue;
        const rgb d = a.pixels[i] - b.pixels[i];
        sum += double(glm::dot(d, d));
        ++count;
    }
    return sum / std::max(count, 1);
}

} // namespace

TEST_CASE("path: veach plates: MIS is no worse than the better single strategy") {
    // Direct lighting (one bounce) as in Veach's figure 9.2. The errors of a few samples
    // per pixel are heavy-tailed (a rare sample hits a small, bright light), so each
    // strategy's error is the mean squared error against a 2048-spp reference averaged
    // over 8 independent renders (seeds) of 16 spp.
    const int w = 40, h = 24;
    const auto s = tracer::make_veach(real(w) / real(h));
    auto options = path_options(w, h, 2048);
    options.path.max_bounces = 1;
    options.threads = 0;
    const auto reference = tracer::render(s, options);
    std::vector<std::vector<bool>> plate(4, std::vector<bool>(std::size_t(w * h), false));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            if (const auto hit = s.intersect(s.camera->ray_for_raster(real(x) + 0.5, real(y) + 0.5, w, h)))
                if (hit->object < 4) plate[hit->object][std::size_t(y * w + x)] = true;
    options.spp = 16;
    double error[3][4] = {};
    const tracer::strategy strategies[3] = {tracer::strategy::mis, tracer::strategy::light, tracer::strategy::brdf};
    for (int k = 0; k < 3; ++k) {
        options.path.sampling = strategies[k];
        for (std::uint64_t seed = 2; seed < 10; ++seed) {
            options.seed = seed;
            const auto image = tracer::render(s, options);
            for (std::size_t i = 0; i < 4; ++i) error[k][i] += mse(image, reference, plate[i]) / 8;
        }
    }
    for (std::size_t i = 0; i < 4; ++i) {
        CAPTURE(i);
        MESSAGE("plate ", i, " (alpha ", tracer::veach_alphas[i], "): mean squared error MIS ", error[0][i],
                ", light ", error[1][i], ", BRDF ", error[2][i]);
        CHECK(std::count(plate[i].begin(), plate[i].end(), true) > 20);
        CHECK(error[0][i] <= std::min(error[1][i], error[2][i]));
    }
}

TEST_CASE("path: the error falls as 1 / sqrt(spp)") {
    // The enclosure's exact value is 5 in every pixel, so the root-mean-square error of an
    // image is measured without a reference; four times the samples halve it.
    const auto s = tracer::make_enclosure(real(16) / real(12));
    std::vector<double> errors;
    for (const int spp : {4, 16, 64}) {
        auto options = path_options(16, 12, spp);
        options.threads = 0;
        const auto image = tracer::render(s, options);
        double sum = 0;
        for (const rgb& c : image.pixels) sum += double(glm::dot(c - rgb(5), c - rgb(5)));
        errors.push_back(std::sqrt(sum / double(image.pixels.size())));
    }
    MESSAGE("rms error at 4, 16, 64 spp: ", errors[0], ", ", errors[1], ", ", errors[2]);
    CHECK(errors[0] / errors[1] == doctest::Approx(2).epsilon(0.2));
    CHECK(errors[1] / errors[2] == doctest::Approx(2).epsilon(0.2));
}
