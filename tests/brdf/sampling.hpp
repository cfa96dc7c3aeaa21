#pragma once
// Shared checks of the BRDF tests for sample() and pdf() (shade::sampled_brdf):
//   * agreement: every sample's f, pdf and weight equal f(l), pdf(l) and f |n·l| / pdf;
//   * the integral of pdf over the sphere, by a midpoint rule at two resolutions (their
//     difference is the stated error of the coarser one), compared with 1 and with the
//     fraction of sample() calls that return a direction;
//   * a binned chi-square test of where sample() puts its directions against pdf
//     integrated over the bins, with "no direction" as one more outcome, so a sampler
//     whose pdf is off by a constant factor fails it too.
// Bins and quadrature cells are laid out around an axis (the mirror direction of v, where
// every shipped lobe peaks) with polar angle theta = pi t^3, t uniform in [0, 1], so that
// lobes as narrow as a Phong exponent of 10^4 (width ~0.01 rad) are resolved while the
// whole sphere is still covered.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numbers>
#include <vector>

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/brdf/brdf.hpp>
#include <shade/check/chi2.hpp>
#include <shade/core/frame.hpp>
#include <shade/core/random.hpp>
#include <shade/core/surface_point.hpp>

#include "brdf/support.hpp"

namespace brdf_test {

inline constexpr double pi_d = std::numbers::pi;

/// The polar grid around an axis: t = cbrt(theta / pi) and phi split into n_t x n_phi cells.
template <class T>
struct axis_grid {
    shade::frame<T> around; ///< frame whose n is the axis
    int n_t = 0;
    int n_phi = 0;

    /// The unit direction at grid coordinates (t, phi).
    [[nodiscard]] vec3<T> direction(double t, double phi) const {
        const double theta = pi_d * t * t * t;
        const shade::vec3<double> local(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                                        std::cos(theta));
        return glm::normalize(around.to_world(vec3<T>(local)));
    }
    /// d(solid angle) / (dt dphi) at t: sin(theta) dtheta/dt = sin(pi t^3) 3 pi t^2.
    [[nodiscard]] static double jacobian(double t) { return std::sin(pi_d * t * t * t) * 3 * pi_d * t * t; }
    /// The cell (i, j) containing w, or -1 for a zero vector.
    [[nodiscard]] int cell(const vec3<T>& w) const {
        const shade::vec3<double> local(around.to_local(w));
        const double len = glm::length(local);
        if (!(len > 0)) return -1;
        const double theta = std::acos(std::clamp(local.z / len, -1.0, 1.0));
        double phi = std::atan2(local.y, local.x);
        if (phi < 0) phi += 2 * pi_d;
        const int i = std::min(n_t - 1, int(std::cbrt(theta / pi_d) * n_t));
        const int j = std::min(n_phi - 1, int(phi / (2 * pi_d) * n_phi));
        return i * n_phi + j;
    }
};

/// The grid of bins for view v: around the mirror direction of v about n.
template <class T>
axis_grid<T> grid_for(const vec3<T>& v, const shade::surface_point<T>& at, int n_t, int n_phi) {
    const vec3<T> r = glm::normalize(T(2) * glm::dot(at.n(), v) * at.n() - v);
    return {shade::frame<T>::from_normal(r), n_t, n_phi};
}

/// The integral of pdf(., v) over each cell of `g` by the midpoint rule with `sub` x `sub`
/// points per cell, in double.
template <shade::sampled_brdf B>
std::vector<double> cell_integrals(const B& model, const vec3<shade::scalar_of<B>>& v,
                                   const shade::surface_point<shade::scalar_of<B>>& at,
                                   const axis_grid<shade::scalar_of<B>>& g, int sub) {
    std::vector<double> out(std::size_t(g.n_t) * std::size_t(g.n_phi), 0.0);
    const double dt = 1.0 / (g.n_t * sub);
    const double dphi = 2 * pi_d / (g.n_phi * sub);
    for (int i = 0; i < g.n_t * sub; ++i) {
        const double t = (i + 0.5) * dt;
        const double jac = axis_grid<shade::scalar_of<B>>::jacobian(t) * dt * dphi;
        for (int j = 0; j < g.n_phi * sub; ++j) {
            const double phi = (j + 0.5) * dphi;
            const double p = double(model.pdf(g.direction(t, phi), v, at));
            out[std::size_t(i / sub) * std::size_t(g.n_phi) + std::size_t(j / sub)] += p * jac;
        }
    }
    return out;
}

/// What the sampling checks found for one model and view.
struct sampling_report {
    double integral = 0;        ///< integral of pdf over the sphere (fine midpoint rule)
    double integral_error = 0;  ///< |fine - coarse|: the stated error of the quadrature
    double drawn_fraction = 0;  ///< fraction of sample() calls that returned a direction
    double drawn_sigma = 0;     ///< its binomial standard deviation
    double chi2 = 0;            ///< chi-square statistic over the bins and "no direction"
    int dof = 0;                ///< its degrees of freedom
    double p_value = 1;         ///< upper-tail probability of chi2 (shade::check::chi2_p_value)
    int disagreements = 0;      ///< samples whose f, pdf or weight disagree with f(), pdf()
    int below = 0;              ///< samples with n·l <= 0 or a non-unit l
};

/// Significance level of every chi-square test in the BRDF tests: 0.01 split over up to
/// 10^3 tests (Bonferroni), so that a correct sampler fails none of them with probability
/// above 0.99 even if every test were run with fresh random numbers.
inline constexpr double chi2_significance = 1e-5;

/// Relative agreement demanded of a sample's f and pdf with f() and pdf() at its l: both
/// evaluate the same expressions, up to the rounding of a few operations.
template <class T>
constexpr T agreement = sizeof(T) <= 4 ? T(1e-5) : T(1e-12);

/// Runs every check for `model` seen from v at `at` with `count` samples (uc, u drawn
/// from a fixed seed) and bins of n_t x n_phi cells (sub x sub quadrature points each).
template <shade::sampled_brdf B>
sampling_report check_sampling(const B& model, const vec3<shade::scalar_of<B>>& v,
                               const shade::surface_point<shade::scalar_of<B>>& at,
                               std::size_t count = 100000, int n_t = 32, int n_phi = 32,
                               int sub = 16, std::uint64_t seed = 1) {
    using T = shade::scalar_of<B>;
    sampling_report r;
    const axis_grid<T> g = grid_for(v, at, n_t, n_phi);
    const std::vector<double> fine = cell_integrals(model, v, at, g, sub);
    const std::vector<double> coarse = cell_integrals(model, v, at, g, sub / 2);
    double coarse_total = 0;
    for (std::size_t i = 0; i < fine.size(); ++i) {
        r.integral += fine[i];
        coarse_total += coarse[i];
    }
    r.integral_error = std::abs(r.integral - coarse_total);

    std::vector<double> observed(fine.size(), 0.0);
    shade::rng random(seed);
    std::size_t drawn = 0;
    for (std::size_t k = 0; k < count; ++k) {
        const T uc = random.uniform<T>();
        const shade::vec2<T> u(random.uniform<T>(), random.uniform<T>());
        const auto s = model.sample(v, uc, u, at);
        if (!s) continue;
        ++drawn;
        const T n_dot_l = glm::dot(at.n(), s->l);
        // Unit up to rounding: a direction reflected about a drawn h, l = 2 (v·h) h - v, has
        // |l|^2 - 1 = 4 (v·h)^2 (|h|^2 - 1), so the few ulps by which h misses unit length
        // are multiplied by up to 4.
        if (!(n_dot_l > T(0)) || !(std::abs(glm::length(s->l) - T(1)) <= T(16) * std::numeric_limits<T>::epsilon()))
            ++r.below;
        const rgb<T> f = model.f(s->l, v, at);
        const T pdf = model.pdf(s->l, v, at);
        if (!close(s->f, f, agreement<T>) || !close(s->pdf, pdf, agreement<T>) ||
            !close(s->weight, f * (n_dot_l / pdf), agreement<T>) || !(s->pdf > T(0)))
            ++r.disagreements;
        const int c = g.cell(s->l);
        if (c >= 0) observed[std::size_t(c)] += 1;
    }
    r.drawn_fraction = double(drawn) / double(count);
    r.drawn_sigma = std::sqrt(std::max(r.drawn_fraction * (1 - r.drawn_fraction), 1.0 / double(count)) /
                              double(count));

    // Chi-square over the cells and the outcome "no direction", by the property kit's
    // Pearson statistic (cells expecting fewer than 5 samples pooled) and p-value.
    const double n = double(count);
    std::vector<double> expected(fine.size() + 1);
    for (std::size_t i = 0; i < fine.size(); ++i) expected[i] = n * fine[i];
    expected.back() = std::max(0.0, n * (1 - r.integral));
    observed.push_back(double(count - drawn));
    const shade::check::chi2_statistic chi2 = shade::check::pearson_chi2(observed, expected);
    r.chi2 = chi2.statistic;
    r.dof = int(chi2.dof);
    r.p_value = chi2.dof > 0 ? shade::check::chi2_p_value(chi2.statistic, double(chi2.dof)) : 1.0;
    return r;
}

/// The CHECKs every correct sampler passes: its samples agree with f and pdf and lie above
/// the surface; the pdf integrates to at most 1 (within the stated quadrature error plus
/// `rounding`, the relative rounding error of pdf itself) and to the fraction of draws that
/// return a direction (within 5 sigma plus both errors); the chi-square test does not
/// reject at chi2_significance. `rounding` is 1e-6 unless a test says why its pdf rounds
/// more (a power cos^s in float multiplies the ~6e-8 rounding of cos by s).
inline void check_report(const sampling_report& r, double rounding = 1e-6) {
    CAPTURE(r.integral);
    CAPTURE(r.integral_error);
    CAPTURE(r.drawn_fraction);
    CAPTURE(r.chi2);
    CAPTURE(r.dof);
    CAPTURE(r.p_value);
    CHECK(r.disagreements == 0);
    CHECK(r.below == 0);
    CHECK(r.integral <= 1 + r.integral_error + rounding);
    CHECK(std::abs(r.integral - r.drawn_fraction) <= 5 * r.drawn_sigma + r.integral_error + rounding);
    CHECK(r.dof >= 10);
    CHECK(r.p_value > chi2_significance);
}

/// The `rounding` for check_report of a lobe cos^s: the pdf has s times the relative
/// rounding error of cos, which is formed with a few roundings (dot products and products):
/// taken as 4 units of eps/2, i.e. 2.4e-3 in float at s = 1e4 (1e-6 where that is smaller,
/// and so always in double).
template <class T>
double pdf_rounding(T exponent) {
    return std::max(1e-6, 4 * double(std::numeric_limits<T>::epsilon() / 2) * double(exponent));
}

/// The views the sampling tests use at `at`: polar angles 0, 45, 80 and 89.9 degrees (the
/// last near grazing) at azimuth 0.3.
template <class T>
std::vector<vec3<T>> sampling_views(const shade::surface_point<T>& at) {
    std::vector<vec3<T>> out;
    for (const double deg : {0.0, 45.0, 80.0, 89.9})
        out.push_back(direction(at, T(deg * pi_d / 180), T(0.3)));
    return out;
}

/// check_report for `model` at `at` from every sampling_views direction.
template <shade::sampled_brdf B>
void check_sampled_model(const B& model, const shade::surface_point<shade::scalar_of<B>>& at,
                         double rounding = 1e-6, std::size_t count = 100000) {
    using T = shade::scalar_of<B>;
    const std::vector<double> degrees = {0.0, 45.0, 80.0, 89.9};
    const auto views = sampling_views(at);
    for (std::size_t i = 0; i < views.size(); ++i) {
        CAPTURE(degrees[i]);
        check_report(check_sampling(model, views[i], at, count), rounding);
        // v below the surface: no direction.
        CHECK_FALSE(model.sample(-views[i], T(0.5), shade::vec2<T>(T(0.3), T(0.6)), at).has_value());
    }
}

} // namespace brdf_test
