// shade::dielectric_reflection_albedo (shade/bsdf/dielectric_reflection_albedo.hpp) and its
// committed table (shade/bsdf/detail/dielectric_reflection_albedo_data.hpp, written by
// examples/dielectric_albedo_tables --reflection): the table against a coarse regeneration
// with shade::rough_dielectric's own sampler (so it cannot drift from the model), a wrong
// table caught; the function against fresh estimates at points between the nodes, its
// smooth limit (the exact Fresnel reflectance), total internal reflection, the
// index-matched limit, its anisotropic form, and its validation.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <doctest/doctest.h>

#include <shade/brdf/fresnel.hpp>
#include <shade/brdf/microfacet/beckmann.hpp>
#include <shade/brdf/microfacet/ggx.hpp>
#include <shade/bsdf/dielectric_reflection_albedo.hpp>
#include <shade/bsdf/rough_dielectric.hpp>
#include <shade/core/error.hpp>
#include <shade/core/random.hpp>

#include "bsdf/dielectric_albedo.hpp"

namespace {

namespace d = shade::detail;
constexpr const d::dielectric_albedo_grid& grid = d::dielectric_reflection_albedo_grid;
const float* const table = d::ggx_rough_dielectric_reflection_albedo;

// The generated header states the largest node standard error; it is below this.
constexpr double committed_standard_error = 2e-4;
// The generated header states the largest difference between the table and a fresh
// estimate at the cell centres with mu >= 0.05, for each side; they are below these.
constexpr double stated_accuracy_side[2] = {2e-3, 1.8e-2}; // entering, exiting
constexpr double stated_accuracy = stated_accuracy_side[1];

double eta_of_side(std::size_t side, double eta_hat) { return side == 0 ? eta_hat : 1 / eta_hat; }

// The local view at cosine mu on side `side` (0 outside, +z; 1 inside, -z), azimuth phi.
shade::vec3<double> view(double mu, std::size_t side, double phi = 0) {
    const double s = std::sqrt((1 - mu) * (1 + mu));
    return {s * std::cos(phi), s * std::sin(phi), side == 0 ? mu : -mu};
}

// R_ss of a GGX interface of index eta (n_inside / n_outside) for the local view v, fresh.
shade::check::albedo_sample<double> fresh_reflection(double alpha_x, double alpha_y, double eta,
                                                     const shade::vec3<double>& v, std::size_t strata, std::uint64_t seed) {
    const shade::rough_dielectric<shade::ggx<double>> model(shade::ggx<double>(alpha_x, alpha_y), eta);
    return bsdf_test::single_scattering_reflection(model, v, strata, seed);
}

// Regenerates every 4th view node, alpha nodes 0, 5, 10, 15 and eta nodes 0, 7, 13, 19 of
// both sides with the model family make(alpha, eta) (eta = n_inside / n_outside, the view
// outside for the entering side, inside for the exiting one), 48^2 samples each, and counts
// the nodes whose R - F differs from the committed one by more than 5 standard deviations
// of the difference (fresh SE + committed SE bound).
template <class Make>
int count_drifted(const Make& make) {
    int drifted = 0, compared = 0;
    for (std::size_t side = 0; side < 2; ++side)
        for (const std::size_t k : {std::size_t(0), std::size_t(7), std::size_t(13), grid.eta_nodes - 1})
            for (std::size_t j = 0; j < grid.alpha_nodes; j += 5) {
                const double alpha = d::albedo_grid_alpha(j, grid.alpha_nodes);
                const double eta_hat = d::dielectric_albedo_eta(grid, k);
                const auto model = make(alpha, eta_hat); // eta = eta_hat: v outside enters, v inside exits
                const double eta_s = eta_of_side(side, eta_hat);
                for (std::size_t i = 0; i < grid.mu_nodes; i += 4) {
                    const double mu = std::min(
                        std::max(d::dielectric_albedo_view_mu(double(i) / double(grid.mu_nodes - 1), alpha, eta_hat, side,
                                                              grid.near_critical),
                                 d::albedo_grid_mu_min),
                        1.0);
                    const auto fresh = bsdf_test::single_scattering_reflection(model, view(mu, side), 48, 11 + i + 37 * j);
                    const double tolerance = 5 * (fresh.standard_error.x + committed_standard_error);
                    ++compared;
                    const double committed = double(table[grid.row(side, k, j) + i]) + shade::F_dielectric(mu, eta_s);
                    if (std::abs(committed - fresh.albedo.x) > tolerance) ++drifted;
                }
            }
    CHECK(compared == 2 * 4 * 4 * int((grid.mu_nodes + 3) / 4));
    return drifted;
}

} // namespace

TEST_CASE("dielectric reflection albedo: the committed table agrees with a coarse regeneration by the model's sampler") {
    const auto make_ggx = [](double alpha, double eta) {
        return shade::rough_dielectric<shade::ggx<double>>(shade::ggx<double>(alpha), eta);
    };
    CHECK(count_drifted(make_ggx) == 0);
}

TEST_CASE("dielectric reflection albedo: the regeneration check catches a table that does not belong to its model") {
    // Beckmann interfaces of the same roughness reflect differently at most rough nodes
    // (their visible normals spread differently), so the GGX table must fail against them.
    const auto make_beckmann = [](double alpha, double eta) {
        return shade::rough_dielectric<shade::beckmann<double>>(shade::beckmann<double>(alpha), eta);
    };
    CHECK(count_drifted(make_beckmann) > 20);
}

TEST_CASE_TEMPLATE("dielectric reflection albedo: agrees with fresh estimates between the nodes", T, float, double) {
    // Random (mu >= 0.05, alpha in [0.01, 1], eta_hat in [1.001, 3]) on both sides, each
    // within the table's stated accuracy for its side at the cell centres (which includes
    // its own estimate's noise) plus 4 standard errors of the fresh estimate.
    shade::rng random(0x7ef1ec7);
    double worst = 0;
    for (int p = 0; p < 24; ++p) {
        const std::size_t side = std::size_t(p % 2);
        const double mu = 0.05 + 0.95 * random.uniform<double>();
        const double y = 0.1 + 0.9 * random.uniform<double>(), alpha = y * y;
        const double eta_hat = 1 + std::exp(grid.x_min + random.uniform<double>() * (grid.x_max - grid.x_min));
        const double eta_s = eta_of_side(side, eta_hat);
        const auto fresh = fresh_reflection(alpha, alpha, eta_hat, view(mu, side), 64, 500 + std::uint64_t(p));
        const double r = double(shade::dielectric_reflection_albedo(T(mu), T(alpha), T(eta_s)));
        CAPTURE(mu);
        CAPTURE(alpha);
        CAPTURE(eta_s);
        CHECK(std::abs(r - fresh.albedo.x) <= stated_accuracy_side[side] + 4 * fresh.standard_error.x);
        worst = std::max(worst, std::abs(r - fresh.albedo.x));
    }
    MESSAGE("reflection albedo against fresh estimates at 24 random points: worst " << worst);
}

TEST_CASE_TEMPLATE("dielectric reflection albedo: a smooth interface reflects the exact Fresnel reflectance", T, float,
                   double) {
    // As alpha -> 0, f_R tends to a mirror weighted by F(mu, eta_s), so R_ss -> F(mu, eta_s)
    // (Walter et al. 2007, eq. 20 with D -> delta(m - n), G -> 1), total internal reflection
    // included (F = 1 from the denser side beyond the critical angle). The lookup adds the
    // exact F to the table's R_ss - F, whose alpha = 0 row was estimated at alpha = 1e-4.
    // There R_ss - F is the masking loss, 1 - G2 / G1 ~ Lambda(l) ~ (alpha tan(theta))^2 / 4
    // <= 1e-6 for mu >= 0.05, plus what the normals tilted by more than the distance to a
    // steep part of F change: GGX's slopes have a heavy tail, P(tan(theta_m) > t) =
    // alpha^2 / (alpha^2 + t^2) (Walter et al. 2007, the CDF behind eq. 35), and F changes
    // by at most 1, so a view 1e-2 or more from the critical angle (a tilt of >= 1e-2 rad
    // to cross it) differs by <= 1e-8 / 1e-4 = 1e-4; the spline through such nodes keeps
    // that order (its weights add to <= 1.25 in absolute value per axis at mid-cell). So
    // R = F to 1e-4 (and float's rounding) at alpha = 0, mu >= 0.05, |mu - mu_c| >= 1e-2.
    for (const double eta_hat : {1.001, 1.02, 1.1, 1.33, 1.5, 2.0, 2.4, 3.0})
        for (const std::size_t side : {std::size_t(0), std::size_t(1)}) {
            const double eta_s = eta_of_side(side, eta_hat);
            const double mu_c = side == 1 ? std::sqrt(1 - 1 / (eta_hat * eta_hat)) : 0.0;
            for (double mu = 0.05; mu <= 1.0; mu += 0.0125) {
                if (std::abs(mu - mu_c) < 1e-2) continue;
                CAPTURE(eta_s);
                CAPTURE(mu);
                const double F = shade::F_dielectric(mu, eta_s);
                const double tolerance = 1e-4 + 8 * double(std::numeric_limits<T>::epsilon());
                CHECK(std::abs(double(shade::dielectric_reflection_albedo(T(mu), T(0), T(eta_s))) - F) <= tolerance);
            }
        }
}

TEST_CASE_TEMPLATE("dielectric reflection albedo: total internal reflection from the denser side", T, float, double) {
    // eta_s < 1: below the critical angle, mu < mu_c = sqrt(1 - eta_s^2), every microfacet of
    // a smooth interface reflects totally (F = 1), so R_ss = 1 but for masking and for the
    // normals tilted past the critical angle (bounds as in the test above: (alpha
    // tan(theta))^2 / 4 and alpha^2 / tilt^2): at alpha = 0, mu >= 0.05 and mu_c - mu >= 0.05,
    // 1 - R <= 1e-6 + 4e-6, within the 1e-4 of that test; at alpha = 0.01, mu >= 0.1 and
    // mu_c - mu >= 0.1, 1 - R <= 2 (0.01 * 10)^2 / 4 + 1e-4 / 1e-2 = 1.5e-2, plus the table's
    // stated accuracy. Above mu_c it is no longer total.
    for (const double eta_hat : {1.1, 1.33, 1.5, 2.0, 3.0}) {
        const double eta_s = 1 / eta_hat, mu_c = std::sqrt(1 - eta_s * eta_s);
        for (double mu = 0.05; mu <= mu_c - 0.05; mu += 0.01) {
            CAPTURE(eta_hat);
            CAPTURE(mu);
            CHECK(double(shade::dielectric_reflection_albedo(T(mu), T(0), T(eta_s))) >= 1 - 1e-4);
            if (mu >= 0.1 && mu <= mu_c - 0.1)
                CHECK(double(shade::dielectric_reflection_albedo(T(mu), T(0.01), T(eta_s))) >= 1 - 1.5e-2 - stated_accuracy);
        }
        CHECK(double(shade::dielectric_reflection_albedo(T(std::min(mu_c + 0.05, 1.0)), T(0), T(eta_s))) < 0.9);
    }
}

TEST_CASE_TEMPLATE("dielectric reflection albedo: an index-matched interface reflects nothing, and R falls to it", T, float,
                   double) {
    // eta_s = 1: F = 0 at every angle and the table's difference is scaled by eta_hat - 1 = 0.
    for (const double alpha : {0.0, 0.01, 0.3, 1.0})
        for (const double mu : {0.01, 0.2, 0.7, 1.0}) {
            CHECK(shade::dielectric_reflection_albedo(T(mu), T(alpha), T(1)) == T(0));
            // Below the grid's eta_hat = 1.001, R shrinks toward 0 (away from grazing, where F
            // itself is near 1 for any eta != 1) and stays continuous at 1.001.
            const T at_edge = shade::dielectric_reflection_albedo(T(mu), T(alpha), T(1.001));
            const T below = shade::dielectric_reflection_albedo(T(mu), T(alpha), T(1.0005));
            CHECK(below >= T(0));
            if (mu >= 0.2) CHECK(below <= at_edge + T(1e-6));
            const T just_below = shade::dielectric_reflection_albedo(T(mu), T(alpha), T(1.001) - T(1e-6));
            CHECK(std::abs(double(just_below) - double(at_edge)) < 2e-3);
        }
}

TEST_CASE("dielectric reflection albedo: the anisotropic form against direct estimates at 2:1 and 10:1") {
    // The anisotropic entry reads the isotropic table at sqrt(alpha_x alpha_y) whatever the
    // view's azimuth. Its error against fresh estimates of the anisotropic interface, over
    // azimuths 0, 45 and 90 degrees from the smoother axis t, mu 0.2, 0.5, 0.9, mean
    // roughness 0.1, 0.3, 0.6 and eta 1.5 seen from outside (eta_s = 1.5) and from inside
    // (eta_s = 1 / 1.5), stays below the bounds docs/properties.md states (measured there
    // with 256^2 samples; here 32^2, so 4 fresh standard errors are added).
    constexpr std::size_t strata = 32;
    for (const double ratio : {2.0, 10.0}) {
        double worst[2] = {0, 0};
        const double bounds[2][2] = {{0.045, 0.15}, {0.13, 0.46}};
        for (const double alpha : {0.1, 0.3, 0.6})
            for (const double mu : {0.2, 0.5, 0.9})
                for (const double phi : {0.0, 0.25 * shade::pi<double>, 0.5 * shade::pi<double>})
                    for (const std::size_t side : {std::size_t(0), std::size_t(1)}) {
                        const double alpha_x = alpha / std::sqrt(ratio), alpha_y = alpha * std::sqrt(ratio);
                        const auto fresh = fresh_reflection(alpha_x, alpha_y, 1.5, view(mu, side, phi), strata, 900);
                        const double bound = bounds[ratio == 2.0 ? 0 : 1][side];
                        const double r = shade::dielectric_reflection_albedo(mu, alpha_x, alpha_y, eta_of_side(side, 1.5));
                        CHECK(r == shade::dielectric_reflection_albedo(mu, alpha, eta_of_side(side, 1.5)));
                        CAPTURE(ratio);
                        CAPTURE(alpha);
                        CAPTURE(mu);
                        CAPTURE(phi);
                        CAPTURE(side);
                        CHECK(std::abs(r - fresh.albedo.x) <= bound + 4 * fresh.standard_error.x);
                        worst[side] = std::max(worst[side], std::abs(r - fresh.albedo.x));
                    }
        MESSAGE("anisotropic reflection albedo read at sqrt(alpha_x alpha_y), " << ratio << ":1: worst " << worst[0]
                                                                                << " (v outside), " << worst[1] << " (inside)");
    }
}

TEST_CASE_TEMPLATE("dielectric reflection albedo: bad input is refused with the parameter's name", T, float, double) {
    const T nan = std::numeric_limits<T>::quiet_NaN();
    CHECK_THROWS_AS((void)shade::dielectric_reflection_albedo(T(1.5), T(0.3), T(1.5)), shade::invalid_parameter);
    CHECK_THROWS_AS((void)shade::dielectric_reflection_albedo(nan, T(0.3), T(1.5)), shade::invalid_parameter);
    CHECK_THROWS_AS((void)shade::dielectric_reflection_albedo(T(0.5), T(-0.1), T(1.5)), shade::invalid_parameter);
    CHECK_THROWS_AS((void)shade::dielectric_reflection_albedo(T(0.5), nan, T(1.5)), shade::invalid_parameter);
    CHECK_THROWS_AS((void)shade::dielectric_reflection_albedo(T(0.5), T(0.3), T(0)), shade::invalid_parameter);
    CHECK_THROWS_AS((void)shade::dielectric_reflection_albedo(T(0.5), T(0.3), nan), shade::invalid_parameter);
    CHECK_THROWS_AS((void)shade::dielectric_reflection_albedo(T(0.5), T(0.3), T(-1), T(1.5)), shade::invalid_parameter);
    CHECK_THROWS_WITH((void)shade::dielectric_reflection_albedo(T(0.5), T(0.3), T(0.3), T(2e4)),
                      doctest::Contains("eta_s"));
    CHECK_THROWS_WITH((void)shade::dielectric_reflection_albedo(T(0.5), T(-0.3), T(1.5)), doctest::Contains("alpha"));
    // In range: a value in [0, 1], the unchecked form the same.
    const T r = shade::dielectric_reflection_albedo(T(0.5), T(0.3), T(1.5));
    CHECK(r >= T(0));
    CHECK(r <= T(1));
    CHECK(r == shade::dielectric_reflection_albedo(shade::unchecked, T(0.5), T(0.3), T(1.5)));
}

TEST_CASE("dielectric reflection albedo: the reflection grid's view coordinate and eta axis") {
    // near_critical: the exiting side still puts mu_c on 0.5 and is inverted by view_mu; the
    // entering side mixes q = (1 - F) / (1 - f0) into c, still 0 at grazing and 1 at mu = 1.
    for (const double eta_hat : {1.001, 1.05, 1.5, 3.0})
        for (const double alpha : {1e-4, 0.1, 1.0}) {
            const double mu_c = std::sqrt(1 - 1 / (eta_hat * eta_hat));
            // (to 1e-6: above mu_c the coordinate grows as sqrt(mu - mu_c), so the rounding of
            // mu_c here, ~1e-16, moves it by ~1e-8)
            CHECK(d::dielectric_albedo_view(mu_c, alpha, eta_hat, 1, true) == doctest::Approx(0.5).epsilon(1e-6));
            for (const std::size_t side : {std::size_t(0), std::size_t(1)}) {
                CHECK(d::dielectric_albedo_view(0.0, alpha, eta_hat, side, true) == doctest::Approx(0.0));
                CHECK(d::dielectric_albedo_view(1.0, alpha, eta_hat, side, true) == doctest::Approx(1.0).epsilon(1e-9));
                double previous = -1;
                for (int i = 0; i <= 200; ++i) {
                    const double mu = i / 200.0;
                    const double t = d::dielectric_albedo_view(mu, alpha, eta_hat, side, true);
                    CHECK(t >= previous); // increasing, so view_mu's bisection inverts it
                    previous = t;
                }
                for (const double t : {0.1, 0.37, 0.5, 0.52, 0.9})
                    CHECK(d::dielectric_albedo_view(d::dielectric_albedo_view_mu(t, alpha, eta_hat, side, true), alpha,
                                                    eta_hat, side, true) == doctest::Approx(t).epsilon(1e-9));
            }
        }
    // eta nodes: 1.001 and 3 at the ends, and a lookup returns the node values at the nodes
    // (the Catmull-Rom spline along x passes through them).
    CHECK(d::dielectric_albedo_eta(grid, 0) == doctest::Approx(1.001).epsilon(1e-14));
    CHECK(d::dielectric_albedo_eta(grid, grid.eta_nodes - 1) == doctest::Approx(3.0).epsilon(1e-14));
    for (const std::size_t side : {std::size_t(0), std::size_t(1)})
        for (const std::size_t k : {std::size_t(3), std::size_t(11)})
            for (const std::size_t j : {std::size_t(2), std::size_t(9)})
                for (const std::size_t i : {std::size_t(3), std::size_t(20)}) {
                    const double alpha = d::albedo_grid_alpha(j, grid.alpha_nodes);
                    const double eta_hat = d::dielectric_albedo_eta(grid, k);
                    const double mu =
                        d::dielectric_albedo_view_mu(double(i) / double(grid.mu_nodes - 1), alpha, eta_hat, side, true);
                    const auto cell = d::dielectric_albedo_locate(grid, alpha, eta_of_side(side, eta_hat));
                    CHECK(d::dielectric_albedo_interpolate(table, grid, cell, mu) ==
                          doctest::Approx(double(table[grid.row(side, k, j) + i])).epsilon(1e-6).scale(1e-6));
                }
}
