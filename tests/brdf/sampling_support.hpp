#pragma once
// Sampling checks of the BRDF tests: a binned chi^2 test of sample() against pdf(), and the
// per-sample consistency of f, pdf and weight.
//
// Bins: directions are binned in a frame around an axis (the lobe's expected centre, e.g.
// the mirror direction of v), by u = sqrt(theta'/pi) (theta' the angle to the axis; the
// square root crowds bins near the axis, where sharp lobes live) and by the azimuth
// phi' around the axis. The expected count of a bin is N times the integral of pdf over it
// (midpoint rule on sub-cells, refined where it has not converged,
// dw = sin(theta') 2 pi u du dphi'); the samples sample()
// declines (nullopt) form one more category, expected N (1 - integral of pdf). Categories
// expected below 5 are pooled and the p-value computed by the property kit
// (shade::check::pearson_chi2 and chi2_p_value, shade/check/chi2.hpp). Beside the shared
// checks of brdf/sampling.hpp, this file adds the refined quadrature that the microfacet
// lobes at grazing views need, and a statistic that callers can compare with a threshold.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/brdf/brdf.hpp>
#include <shade/check/chi2.hpp>
#include <shade/core/frame.hpp>
#include <shade/core/random.hpp>
#include <shade/core/surface_point.hpp>

#include "brdf/sampling.hpp"

namespace brdf_test {

struct chi2_result {
    double statistic = 0;
    int dof = 0;
    double p_value = 1;
    double pdf_integral = 0; ///< integral of pdf over the sphere, from the bins
    std::size_t declined = 0; ///< samples for which sample() returned nullopt
};

/// chi^2 test of b.sample(v, uc, u, at) against b.pdf(l, v, at), with `count` samples from
/// a seeded generator, bins around `axis` (world space, unit).
template <shade::sampled_brdf B>
chi2_result sampling_chi2(const B& b, const shade::vec3<shade::scalar_of<B>>& v,
                          const shade::surface_point<shade::scalar_of<B>>& at,
                          const shade::vec3<shade::scalar_of<B>>& axis, std::size_t count = 100000,
                          std::uint64_t seed = 1, int n_u = 32, int n_phi = 16, int sub = 4) {
    using T = shade::scalar_of<B>;
    const double pi = 3.14159265358979323846;
    const auto axis_frame = shade::frame<double>::from_normal(glm::normalize(shade::vec3<double>(axis)));
    const auto bin_of = [&](const shade::vec3<T>& l) {
        const shade::vec3<double> w = axis_frame.to_local(shade::vec3<double>(l));
        const double theta = std::atan2(std::sqrt(w.x * w.x + w.y * w.y), w.z);
        double phi = std::atan2(w.y, w.x);
        if (phi < 0) phi += 2 * pi;
        const int i = std::min(n_u - 1, static_cast<int>(std::sqrt(theta / pi) * n_u));
        const int j = std::min(n_phi - 1, static_cast<int>(phi / (2 * pi) * n_phi));
        return i * n_phi + j;
    };
    std::vector<double> observed(static_cast<std::size_t>(n_u * n_phi) + 1, 0.0);
    shade::rng random(seed);
    chi2_result out;
    for (std::size_t s = 0; s < count; ++s) {
        const T uc = random.uniform<T>();
        const shade::vec2<T> u(random.uniform<T>(), random.uniform<T>());
        const auto sample = b.sample(v, uc, u, at);
        if (!sample) {
            ++out.declined;
            observed.back() += 1;
            continue;
        }
        observed[static_cast<std::size_t>(bin_of(sample->l))] += 1;
    }
    std::vector<double> expected(observed.size(), 0.0);
    // The integral of pdf over bin (i, j) with k x k midpoint sub-cells.
    // `cut` is set when some sub-cells have pdf = 0 and others not (the bin crosses the
    // horizon, where pdf jumps).
    const auto bin_integral = [&](int i, int j, int k, bool* cut = nullptr) {
        double integral = 0;
        bool zero = false, positive = false;
        for (int a = 0; a < k; ++a) {
            const double u = (i + (a + 0.5) / k) / n_u;
            const double theta = pi * u * u;
            const double area = std::sin(theta) * 2 * pi * u / (n_u * k) * (2 * pi / (n_phi * k));
            for (int c = 0; c < k; ++c) {
                const double phi = 2 * pi * (j + (c + 0.5) / k) / n_phi;
                const shade::vec3<double> w(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
                const shade::vec3<T> l(glm::normalize(axis_frame.to_world(w)));
                const double p = static_cast<double>(b.pdf(l, v, at));
                (p > 0 ? positive : zero) = true;
                integral += p * area;
            }
        }
        if (cut) *cut = zero && positive;
        return integral;
    };
    // True when the horizon (n.l = 0) passes through bin (i, j): n.l changes sign on a
    // 17 x 17 lattice that includes the bin's edges.
    const shade::vec3<double> n(at.n());
    const auto crosses_horizon = [&](int i, int j) {
        bool above = false, below = false;
        for (int a = 0; a <= 16; ++a) {
            const double u = (i + a / 16.0) / n_u;
            const double theta = pi * u * u;
            for (int c = 0; c <= 16; ++c) {
                const double phi = 2 * pi * (j + c / 16.0) / n_phi;
                const shade::vec3<double> w(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
                (glm::dot(n, axis_frame.to_world(w)) > 0 ? above : below) = true;
            }
        }
        return above && below;
    };
    double total = 0;
    for (int i = 0; i < n_u; ++i) {
        for (int j = 0; j < n_phi; ++j) {
            // Refined (k doubled) until the expected count changes by less than a tenth of
            // its standard deviation, or k = 8 sub; pdf is steep in sharp lobes, where a
            // fixed rule is off by many standard deviations. A bin that crosses the horizon
            // (pdf jumps to 0) gets 16 sub at once: the midpoint rule converges slowly and
            // unevenly across a jump.
            int k = sub;
            bool cut = false;
            double integral = bin_integral(i, j, k, &cut);
            if (cut || crosses_horizon(i, j)) {
                k = 16 * sub;
                integral = bin_integral(i, j, k);
            }
            while (k < 8 * sub) {
                k *= 2;
                const double finer = bin_integral(i, j, k);
                const double change = std::abs(finer - integral) * static_cast<double>(count);
                integral = finer;
                if (change < 0.1 * std::sqrt(integral * static_cast<double>(count)) + 0.01) break;
            }
            expected[static_cast<std::size_t>(i * n_phi + j)] = integral * static_cast<double>(count);
            total += integral;
        }
    }
    out.pdf_integral = total;
    expected.back() = std::max(0.0, 1 - total) * static_cast<double>(count);
    // The property kit's Pearson statistic (categories expected below 5 pooled) and p-value.
    const shade::check::chi2_statistic chi2 = shade::check::pearson_chi2(observed, expected);
    out.statistic = chi2.statistic;
    out.dof = int(chi2.dof);
    out.p_value = chi2.dof > 0 ? shade::check::chi2_p_value(chi2.statistic, double(chi2.dof)) : 1.0;
    return out;
}

/// Per-sample consistency: every sample() result has a unit direction above the surface,
/// f equal to b.f(l, v, at), pdf equal to b.pdf(l, v, at) and > 0, and
/// weight = f (n·l) / pdf, to relative `rel`. Returns the number of samples checked and
/// fails the doctest check on the first mismatch (with its values captured).
template <shade::sampled_brdf B>
std::size_t check_sample_consistency(const B& b, const shade::vec3<shade::scalar_of<B>>& v,
                                     const shade::surface_point<shade::scalar_of<B>>& at,
                                     std::size_t count, shade::scalar_of<B> rel, std::uint64_t seed = 3) {
    using T = shade::scalar_of<B>;
    shade::rng random(seed);
    const auto near = [&](T a, T c) { return std::abs(a - c) <= rel * std::max(std::abs(a), std::abs(c)); };
    std::size_t checked = 0;
    for (std::size_t s = 0; s < count; ++s) {
        const T uc = random.uniform<T>();
        const shade::vec2<T> u(random.uniform<T>(), random.uniform<T>());
        const auto sample = b.sample(v, uc, u, at);
        if (!sample) continue;
        ++checked;
        const shade::rgb<T> f = b.f(sample->l, v, at);
        const T pdf = b.pdf(sample->l, v, at);
        const T n_dot_l = glm::dot(at.n(), sample->l);
        const bool ok = std::abs(glm::length(sample->l) - T(1)) <= T(10) * std::numeric_limits<T>::epsilon() &&
                        n_dot_l > T(0) && sample->pdf > T(0) && near(sample->pdf, pdf) &&
                        near(sample->f.x, f.x) && near(sample->f.y, f.y) && near(sample->f.z, f.z) &&
                        near(sample->weight.x, sample->f.x * n_dot_l / sample->pdf) &&
                        near(sample->weight.y, sample->f.y * n_dot_l / sample->pdf) &&
                        near(sample->weight.z, sample->f.z * n_dot_l / sample->pdf);
        if (!ok) {
            CAPTURE(uc);
            CAPTURE(u.x);
            CAPTURE(u.y);
            CAPTURE(sample->pdf);
            CAPTURE(pdf);
            CAPTURE(sample->f.x);
            CAPTURE(f.x);
            CAPTURE(n_dot_l);
            CHECK(ok);
            return checked;
        }
    }
    return checked;
}

} // namespace brdf_test
