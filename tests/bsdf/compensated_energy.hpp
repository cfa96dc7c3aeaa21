#pragma once
// The energy that leaves shade::compensated_rough_dielectric for one view (importance mode,
// R + T, with its single- and multiple-scattering parts), the check of issue #31's band on
// it, and random views between the nodes of the albedo tables (for the quick suite,
// tests/bsdf/test_compensated_rough_dielectric.cpp, and the sweep, tests/sweep).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include <shade/bsdf/compensated_rough_dielectric.hpp>
#include <shade/core/math.hpp>
#include <shade/core/random.hpp>

#include "bsdf/dielectric_albedo.hpp"

namespace bsdf_test {

/// The energy that leaves the compensated interface for a view at cosine mu in medium
/// `inside` (importance mode, R + T), with its parts: the single-scattering R + T by
/// rough_dielectric's sampler with the lobe choice integrated out, and the integral of
/// f_ms = f - f_ss (importance mode) |n·l| over each hemisphere.
struct energy {
    double single = 0;   ///< E_ss(mu_v)
    double reflected = 0; ///< integral of f_ms |cos| over v's side
    double transmitted = 0; ///< integral of f_ms |cos| over the far side
    double error = 0;    ///< standard error of the single-scattering estimate
    [[nodiscard]] double total() const { return single + reflected + transmitted; }
};

/// The energy of `model` for the view at cosine mu (inside: in the denser medium, eta > 1).
template <class Distribution>
energy energy_of(const shade::compensated_rough_dielectric<double, Distribution>& model, double mu, bool inside) {
    using T = double;
    shade::surface_point<T> at;
    at.shading = shade::frame<T>::from_normal_tangent({0, 0, 1}, {1, 0, 0});
    energy e;
    // The single-scattering part, seen from the medium of v: mirroring the frame turns an
    // inside view into an outside view of the inverted interface.
    const shade::rough_dielectric<Distribution> mirrored{model.distribution(), inside ? 1 / model.eta() : model.eta()};
    // 160^2 samples, or 480^2 where those leave a standard error above 1e-4 (narrow lobes
    // near grazing, where many drawn directions are lost below the horizon).
    auto ss = single_scattering_albedo(mirrored, mu, 160, 3);
    if (ss.standard_error.x > 1e-4) ss = single_scattering_albedo(mirrored, mu, 480, 3);
    e.single = ss.albedo.x;
    e.error = ss.standard_error.x;
    const shade::vec3<T> v(std::sqrt((1 - mu) * (1 + mu)), 0, inside ? -mu : mu);
    // f_ms depends on l only through |n·l| (the tables are isotropic), so each hemisphere's
    // integral is 2 pi integral_0^1 f_ms(mu_l) mu_l dmu_l: a midpoint rule on 4000 cells
    // (f_ms is piecewise smooth in mu_l; its error is far below 1e-5).
    constexpr int cells = 4000;
    for (const bool far : {false, true}) {
        double sum = 0;
        for (int i = 0; i < cells; ++i) {
            const double mu_l = (i + 0.5) / cells;
            const shade::vec3<T> l(std::sqrt((1 - mu_l) * (1 + mu_l)), 0, inside != far ? -mu_l : mu_l);
            const double f_ms = double(shade::bsdf_f(model, l, v, at, shade::transport_mode::importance).x) -
                                double(shade::bsdf_f(model.single_scattering(), l, v, at, shade::transport_mode::importance).x);
            sum += f_ms * mu_l;
        }
        (far ? e.transmitted : e.reflected) = 2 * shade::pi<double> * sum / cells;
    }
    return e;
}

/// The range of R + T over the views checked, and the largest standard error.
struct energy_range {
    double lowest = 2, highest = 0, largest_error = 0;
    int views = 0;
};

/// Checks one view of `model` (eta and alpha only for the log): R + T in [0.99, upper]
/// within 4 standard errors (issue #31's band for upper = 1.001), and the share of the
/// lost energy that crosses over.
template <class Model>
void expect_view_conserved(const Model& model, const std::string& name, double upper, double eta, double alpha,
                           bool inside, double mu, energy_range& range) {
    CAPTURE(name);
    CAPTURE(eta);
    CAPTURE(alpha);
    CAPTURE(inside);
    CAPTURE(mu);
    const energy e = energy_of(model, mu, inside);
    const double total = e.total();
    CAPTURE(total);
    CAPTURE(e.single);
    CAPTURE(e.reflected);
    CAPTURE(e.transmitted);
    CAPTURE(e.error);
    // The estimates' standard error is below 2e-4; 4 of them allowed.
    CHECK(e.error < 2e-4);
    CHECK(total <= upper + 4 * e.error);
    CHECK(total >= 0.99 - 4 * e.error);
    // The lobe splits as designed: tau of the lost energy crosses over.
    const double lost = 1 - model.single_scattering_albedo(inside, mu);
    CHECK(std::abs(e.transmitted - model.transmitted_share(inside) * lost) <= 1e-3 + 4 * e.error);
    range.lowest = std::min(range.lowest, total);
    range.highest = std::max(range.highest, total);
    range.largest_error = std::max(range.largest_error, e.error);
    ++range.views;
}

/// A view of a random interface: eta = n_inside / n_outside, the roughness (GGX alpha or
/// Beckmann m), the side and the view cosine.
struct random_view {
    double eta = 1.5, alpha = 0.5, mu = 0.5;
    bool inside = false;
};

/// `count` views drawn from `seed`, uniform in log(eta - 1) over eta in [1.05, 3], in
/// sqrt(alpha) over alpha in [0.02, 1] and in mu over [0.05, 1], either side with
/// probability 1/2: almost all between the nodes of the albedo tables in every variable
/// (shade/bsdf/dielectric_albedo_table.hpp), where interpolation errs most.
inline std::vector<random_view> random_views(std::uint64_t seed, int count) {
    shade::rng random(seed);
    std::vector<random_view> views;
    for (int k = 0; k < count; ++k) {
        random_view w;
        w.inside = random.uniform<double>() < 0.5;
        w.eta = 1 + std::exp(std::log(0.05) + random.uniform<double>() * (std::log(2.0) - std::log(0.05)));
        const double y = std::sqrt(0.02) + random.uniform<double>() * (1 - std::sqrt(0.02));
        w.alpha = y * y;
        w.mu = 0.05 + 0.95 * random.uniform<double>();
        views.push_back(w);
    }
    return views;
}

/// expect_view_conserved at every view of `views` for the interface make(alpha, eta).
template <class Make>
energy_range expect_energy_conserved_at(const Make& make, const std::string& name, double upper,
                                        const std::vector<random_view>& views) {
    energy_range range;
    for (const random_view& w : views)
        expect_view_conserved(make(w.alpha, w.eta), name, upper, w.eta, w.alpha, w.inside, w.mu, range);
    MESSAGE(name << ": compensated R + T over " << range.views << " random views: from " << range.lowest << " to "
                 << range.highest << " (largest standard error " << range.largest_error << ")");
    return range;
}

/// Issue #31's lattice of views for the compensated rough dielectric: every eta x alpha x mu
/// of the lists, from the given sides (the defaults span alpha <= 1, mu >= 0.05, eta in
/// [1.05, 3], both sides).
struct view_set {
    std::vector<double> etas{1.05, 1.2, 1.5, 2.4, 3.0};
    std::vector<double> alphas{0.02, 0.1, 0.3, 0.6, 1.0};
    std::vector<double> mus{0.05, 0.2, 0.5, 0.9};
    std::vector<bool> sides{false, true}; ///< inside?
};

/// expect_view_conserved at every view of `set` for the interface make(alpha, eta): R + T in
/// [0.99, upper] (upper = 1.001 in issue #31).
template <class Make>
void expect_energy_conserved(const Make& make, const std::string& name, double upper, const view_set& set = {}) {
    energy_range range;
    for (const double eta : set.etas)
        for (const double alpha : set.alphas) {
            const auto model = make(alpha, eta);
            for (const bool inside : set.sides)
                for (const double mu : set.mus) expect_view_conserved(model, name, upper, eta, alpha, inside, mu, range);
        }
    MESSAGE(name << ": compensated R + T over " << range.views << " views: from " << range.lowest << " to "
                 << range.highest << " (largest standard error " << range.largest_error << ")");
}

} // namespace bsdf_test
