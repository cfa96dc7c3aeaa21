#pragma once
// Shared helpers of the tests of the combinators (shade::mix, shade::layer): the agreement
// of each sample with the model's own f and pdf, and the sampling checks at several views.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>
#include <string>

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/bsdf/bsdf.hpp>
#include <shade/check/doctest.hpp>
#include <shade/check/sampling.hpp>
#include <shade/core/random.hpp>

#include "bsdf/support.hpp"

namespace combine_test {

using shade::rgb;
using shade::vec2;
using shade::vec3;

/// Draws `n` samples per view (theta in degrees, see bsdf_test::view_deg) in both modes
/// and checks each with bsdf_test::check_sample; a sample with a density must also carry
/// the model's own f (in its mode, shade::bsdf_f) and pdf at l, to rel. Returns the number
/// of samples drawn (not nullopt).
template <class B, class T = shade::scalar_of<B>>
std::size_t expect_consistent_samples(const B& model, const shade::surface_point<T>& at,
                                      std::initializer_list<double> views, int n = 400) {
    const T rel = sizeof(T) <= 4 ? T(2e-4) : T(1e-10);
    shade::rng random(7);
    std::size_t drawn = 0;
    for (const double deg : views) {
        const vec3<T> v = bsdf_test::view_deg(at, deg);
        for (const auto mode : {shade::transport_mode::radiance, shade::transport_mode::importance}) {
            for (int i = 0; i < n; ++i) {
                const vec2<T> u(random.uniform<T>(), random.uniform<T>());
                const auto s = shade::sample_bsdf(model, v, random.uniform<T>(), u, at, mode);
                if (!s) continue;
                ++drawn;
                CAPTURE(deg);
                bsdf_test::check_sample(*s, v, at, rel);
                if (shade::is_specular(s->flags)) continue;
                const rgb<T> f = shade::bsdf_f(model, s->l, v, at, mode);
                const T pdf = model.pdf(s->l, v, at);
                CHECK(std::abs(s->pdf - pdf) <= rel * pdf);
                for (int c = 0; c < 3; ++c) CHECK(std::abs(s->f[c] - f[c]) <= rel * f[c]);
            }
        }
    }
    return drawn;
}

/// The chi-square test and the pdf integral (∫ pdf <= 1 + 1e-3) of `model` at each view.
template <class B, class T = shade::scalar_of<B>>
void expect_sampling(const B& model, const std::string& name, const shade::surface_point<T>& at,
                     std::initializer_list<double> views, std::size_t family) {
    for (const double deg : views) {
        CAPTURE(deg);
        shade::check::chi2_options chi2{.samples = 40000, .alpha = 1e-3, .tests = family};
        chi2.model = name;
        const vec3<T> v = bsdf_test::view_deg(at, deg);
        shade::check::doctest_expect(shade::check::chi2_goodness_of_fit(model, v, at, chi2));
        shade::check::doctest_expect(shade::check::pdf_normalization(model, v, at, chi2));
    }
}

/// A mean and its standard error.
struct mean_estimate {
    double mean = 0;
    double error = 0;
};

/// The mean weight (channel c) of n draws of shade::sample_bsdf(model, v, ...) in `mode`,
/// nullopt counting 0: in radiance mode the albedo seen from v, ∫ f(l, v) |n·l| dl; in
/// importance mode the fraction of the energy arriving along v that leaves.
template <class B, class T = shade::scalar_of<B>>
mean_estimate mean_weight(const B& model, const vec3<T>& v, const shade::surface_point<T>& at,
                          shade::transport_mode mode, int c = 0, int n = 40000) {
    shade::rng random(29);
    double sum = 0, sum2 = 0;
    for (int i = 0; i < n; ++i) {
        const vec2<T> u(random.uniform<T>(), random.uniform<T>());
        const auto s = shade::sample_bsdf(model, v, random.uniform<T>(), u, at, mode);
        const double w = s ? double(s->weight[c]) : 0.0;
        sum += w;
        sum2 += w * w;
    }
    const double mean = sum / n;
    return {mean, std::sqrt(std::max(sum2 / n - mean * mean, 0.0) / (n - 1))};
}

/// 2 ∫_0^1 E(mu) mu dmu of a layer's coat_albedo (the interpolated estimate as the layer
/// reads it), by the midpoint rule on 20000 panels.
template <class L>
double interpolated_average_albedo(const L& layer) {
    using T = shade::scalar_of<L>;
    constexpr int panels = 20000;
    double sum = 0;
    for (int i = 0; i < panels; ++i) {
        const double mu = (i + 0.5) / panels;
        sum += double(layer.coat_albedo(T(mu))) * mu;
    }
    return 2 * sum / panels;
}

} // namespace combine_test
