// shade::dielectric_reflection_albedo (shade/bsdf/dielectric_reflection_albedo.hpp) and its
// committed table (shade/bsdf/detail/dielectric_reflection_albedo_data.hpp, written by
// examples/dielectric_albedo_tables --reflection): the table against a coarse regeneration
// with shade::rough_dielectric's own sampler (so it cannot drift from the model), a wrong
// table caught; the function against fresh estimates at points between the nodes, its
// smooth limit (the exact Fresnel reflectance), total internal reflection, the
// index-matched limit, its anisotropic form, and its validation.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

#include <doctest/doctest.h>

#include <shade/brdf/fresnel.hpp>
#include <shade/brdf/microfacet/beckmann.hpp>
#include <shade/brdf/microfacet/ggx.hpp>
#include <shade/bsdf/detail/dielectric_anisotropic_reflection_albedo_data.hpp>
#include <shade/bsdf/dielectric_anisotropic_reflection_albedo.hpp>
#include <shade/bsdf/dielectric_anisotropic_reflection_table.hpp>
#include <shade/bsdf/dielectric_reflection_albedo.hpp>
#include <shade/bsdf/rough_dielectric.hpp>
#include <shade/core/error.hpp>
#include <shade/core/random.hpp>

#include "bsdf/dielectric_albedo.hpp"

namespace {

namespace d = shade::detail;
template <class T>
using vec3 = shade::vec3<T>;
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

// The function's read at an isotropic point (view cosine mu on the given side, roughness
// alpha, eta_hat) in T, and a fresh estimate of the model there (64^2 samples).
struct read_and_fresh {
    double read = 0;
    double fresh = 0;
    double standard_error = 0;
    [[nodiscard]] double error() const { return std::abs(read - fresh); }
};

template <class T>
read_and_fresh read_against_fresh(double mu, double alpha, double eta_hat, std::size_t side, std::uint64_t seed) {
    const auto estimate = fresh_reflection(alpha, alpha, eta_hat, view(mu, side), 64, seed);
    const T read = shade::dielectric_reflection_albedo(T(mu), T(alpha), T(eta_of_side(side, eta_hat)));
    return {double(read), estimate.albedo.x, estimate.standard_error.x};
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
        const auto at = read_against_fresh<T>(mu, alpha, eta_hat, side, 500 + std::uint64_t(p));
        CAPTURE(mu);
        CAPTURE(alpha);
        CAPTURE(eta_of_side(side, eta_hat));
        CHECK(at.error() <= stated_accuracy_side[side] + 4 * at.standard_error);
        worst = std::max(worst, at.error());
    }
    MESSAGE("reflection albedo against fresh estimates at 24 random points: worst " << worst);
}

TEST_CASE_TEMPLATE("dielectric reflection albedo: beyond eta_hat 3, the table's end plus the change of F", T, float, double) {
    // Above the grid (eta_hat > 3: dense dielectrics, OpenPBR's specular_weight > 1) the read
    // is R_ss at eta_hat = 3 plus the lobe's measure of v·h summed against F(eta_s) -
    // F(eta_3) (detail::reflection_albedo_change). Against fresh estimates of the model's own
    // sampler: entering, within the table's stated accuracy plus the node sum's 1.5e-3
    // (measured read - fresh at 384^2: -5e-4 to +2.7e-3 for eta 3.2-100, alpha 1e-4-1, mu
    // 0.05-1); exiting, within the table's stated exiting accuracy for mu <= 0.8 (measured
    // -5.5e-3 to +5.8e-3 at mu <= 0.7) and 5e-2 above (measured -3.8e-2 to +4.5e-2 at mu 1,
    // -1.4e-2 at eta 3.2: the node sum's linear
    // pieces in v·h cross the total-reflection edge, which moves to v·h -> 1 as eta_hat
    // grows). The read before this continuation (the difference R_ss - F at eta_hat 3 plus
    // the exact F of the true eta_s) erred by up to 0.38 entering (alpha 0.5, mu 0.1, eta 10).
    shade::rng random(0x3b7e0d);
    double worst[2] = {0, 0};
    for (int p = 0; p < 24; ++p) {
        const std::size_t side = std::size_t(p % 2);
        const double mu = side == 1 && p % 4 == 1 ? 0.8 + 0.2 * random.uniform<double>()
                                                  : 0.05 + 0.75 * random.uniform<double>();
        const double y = random.uniform<double>(), alpha = std::max(y * y, 1e-4); // the model's smallest
        const double eta_hat = 3 * std::exp(3 * random.uniform<double>());       // 3 to 60
        const auto at = read_against_fresh<T>(mu, alpha, eta_hat, side, 900 + std::uint64_t(p));
        CAPTURE(mu);
        CAPTURE(alpha);
        CAPTURE(eta_of_side(side, eta_hat));
        const double bound = side == 0 ? stated_accuracy_side[0] + 1.5e-3 : mu <= 0.8 ? stated_accuracy_side[1] : 5e-2;
        CHECK(at.error() <= bound + 4 * at.standard_error);
        if (mu <= 0.8) worst[side] = std::max(worst[side], at.error());
    }
    // Continuous at eta_hat = 3 on both sides, and an interface that reflects all but
    // 4e-4 at normal incidence (eta 1e4) reads the lobe's albedo with F = 1 within 1e-3.
    for (const double mu : {0.1, 0.5, 1.0}) {
        for (const double alpha : {0.0, 0.2, 1.0}) {
            for (const std::size_t side : {std::size_t(0), std::size_t(1)}) {
                const T at_end = shade::dielectric_reflection_albedo(T(mu), T(alpha), T(eta_of_side(side, 3)));
                const T above = shade::dielectric_reflection_albedo(T(mu), T(alpha), T(eta_of_side(side, 3.0001)));
                CHECK(std::abs(double(above - at_end)) <= 1e-4);
            }
            const double a = std::max(alpha, 1e-4); // the model's smallest; the table's row 0
            const auto fresh = fresh_reflection(a, a, 1e4, view(mu, 0), 48, 77);
            CHECK(std::abs(double(shade::dielectric_reflection_albedo(T(mu), T(alpha), T(1e4))) - fresh.albedo.x) <=
                  1e-3 + stated_accuracy_side[0] + 4 * fresh.standard_error.x);
        }
    }
    MESSAGE("reflection albedo beyond eta_hat 3 against fresh estimates (mu <= 0.8): worst entering " << worst[0]
                                                                                                     << ", exiting "
                                                                                                     << worst[1]);
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

namespace {

// The anisotropic correction (shade/bsdf/detail/dielectric_anisotropic_reflection_albedo_data.hpp,
// grid shade/bsdf/dielectric_anisotropic_reflection_table.hpp).
const float* const anisotropic_delta = d::ggx_dielectric_anisotropic_reflection_delta;
constexpr std::size_t ax_nodes = d::reflection_anisotropic_mu_nodes, au_nodes = d::reflection_anisotropic_azimuth_nodes;
constexpr std::size_t ay_nodes = d::reflection_anisotropic_roughness_nodes, as_nodes = d::reflection_anisotropic_ratio_nodes;
constexpr std::size_t ae_nodes = d::reflection_anisotropic_eta_nodes;
// The generated header states the largest node standard error; it is below this.
constexpr double anisotropic_standard_error = 7e-4;
// The generated header states the largest raise of a node by the upper envelope; it is below this.
constexpr double anisotropic_raise = 0.15;
// The generated header states the range of (table - fresh estimate) at its random points
// (mu >= 0.1, y 0.1 to 1: entering alpha_max 0.014 to sqrt 2, exiting alpha_rms 0.01 to 1;
// alpha_min / alpha_max 0 to 1, eta_hat 1.05 to 3), per side; these enclose them.
constexpr double anisotropic_low[2] = {-5e-4, -0.0034}, anisotropic_high[2] = {0.0205, 0.1005};

// The interface and view of a node of the correction (as the generator builds them: alpha_max
// of the node's y and z, the smoother alpha z^2 alpha_max along t, at least 1e-4; the view at the node's x and u), and
// R_ss,iso, the value Delta_R is measured from (entering: at the roughness projected on the
// node's azimuth; exiting: at the root-mean-square roughness).
struct anisotropic_node {
    double alpha_x, alpha_y, eta_s, mu, phi, base;
};
anisotropic_node node_at(std::size_t side, std::size_t m, std::size_t k, std::size_t j, std::size_t i_u, std::size_t i_x) {
    const double y = double(j) / double(ay_nodes - 1), z = double(k) / double(as_nodes - 1);
    const double alpha_max = d::reflection_anisotropic_alpha_max(side, y, z), alpha_min = std::max(z * z * alpha_max, 1e-4);
    const double eta_hat = d::dielectric_albedo_eta(m, ae_nodes), eta_s = eta_of_side(side, eta_hat);
    const double mu_c = std::sqrt(1 - 1 / (eta_hat * eta_hat));
    const double mu =
        std::min(std::max(d::reflection_anisotropic_mu(side, double(i_x) / double(ax_nodes - 1), mu_c), d::albedo_grid_mu_min), 1.0);
    const double sin_theta = std::sqrt((1 - mu) * (1 + mu));
    const double phi_k = side == 1 ? d::reflection_anisotropic_kink(sin_theta, 1 / eta_hat) : 0.0;
    const double phi = d::reflection_anisotropic_phi(side, double(i_u) / double(au_nodes - 1), phi_k, alpha_min / alpha_max);
    const double projected = std::sqrt(alpha_min * alpha_min * std::cos(phi) * std::cos(phi) +
                                       alpha_max * alpha_max * std::sin(phi) * std::sin(phi));
    const double rms = std::sqrt(0.5 * (alpha_min * alpha_min + alpha_max * alpha_max));
    const double base = shade::dielectric_reflection_albedo(shade::unchecked, mu, side == 0 ? projected : rms, eta_s);
    return {alpha_min, alpha_max, eta_s, mu, phi, base};
}

// Regenerates correction nodes spread over all six axes with the interfaces make(alpha_x,
// alpha_y, eta) (eta = eta_hat: the view outside enters, inside exits), 40^2 samples each,
// and counts those whose committed Delta_R is below the fresh one, or above it by more than
// the envelope's largest raise, by more than 5 standard deviations of the difference (fresh
// SE + committed SE bound).
template <class Make>
int count_anisotropic_drifted(const Make& make) {
    int drifted = 0, checked = 0;
    for (std::size_t side = 0; side < 2; ++side)
        for (std::size_t m = 0; m < ae_nodes; m += 3)
            for (std::size_t k = 0; k + 1 < as_nodes; k += 2)
                for (std::size_t j = 3; j < ay_nodes; j += 5)
                    for (std::size_t i_u = 1; i_u < au_nodes; i_u += 4)
                        for (std::size_t i_x = 4; i_x < ax_nodes; i_x += 5) {
                            const anisotropic_node n = node_at(side, m, k, j, i_u, i_x);
                            const auto model = make(n.alpha_x, n.alpha_y, side == 0 ? n.eta_s : 1 / n.eta_s);
                            const auto fresh = bsdf_test::single_scattering_reflection(model, view(n.mu, side, n.phi), 40,
                                                                                       std::uint64_t(7 + checked));
                            const double fresh_delta = std::min(fresh.albedo.x, 1.0) - n.base;
                            const double committed =
                                double(anisotropic_delta[d::reflection_anisotropic_row_index(side, m, k, j, i_u) * ax_nodes + i_x]);
                            const double tolerance = 5 * (fresh.standard_error.x + anisotropic_standard_error);
                            if (committed < fresh_delta - tolerance || committed > fresh_delta + anisotropic_raise + tolerance)
                                ++drifted;
                            ++checked;
                        }
    CHECK(checked == 2 * 3 * 3 * 2 * 4 * 3); // sides, e, z, y, u (1, 5, 9, 13), x
    return drifted;
}

} // namespace

TEST_CASE("dielectric reflection albedo: the committed anisotropic correction agrees with a coarse regeneration") {
    CHECK(count_anisotropic_drifted([](double a_x, double a_y, double eta) {
              return shade::rough_dielectric<shade::ggx<double>>(shade::ggx<double>(a_x, a_y), eta);
          }) == 0);
}

TEST_CASE("dielectric reflection albedo: the anisotropic regeneration check catches the wrong interface") {
    // The same nodes regenerated with the roughnesses exchanged (the rougher axis along t):
    // the azimuth of every view then counts from the rougher axis, and many Delta_R change.
    CHECK(count_anisotropic_drifted([](double a_x, double a_y, double eta) {
              return shade::rough_dielectric<shade::ggx<double>>(shade::ggx<double>(a_y, a_x), eta);
          }) > 30);
}

TEST_CASE("dielectric reflection albedo: the anisotropic form against direct estimates at 2:1, 10:1 and anisotropy 1") {
    // R_ss(w) of anisotropic interfaces (eta 1.5 and 1.6 / 1.5 seen from outside, eta_s =
    // eta, and from inside, eta_s = 1 / eta) over mean roughness 0.1, 0.3, 0.44 (the rougher
    // alpha within the grid's sqrt 2 at 10:1), mu 0.2, 0.5, 0.9 and azimuths 0, 30, 60, 90
    // and 135 degrees, with the smoother axis along t and along b, at anisotropy max / min 2
    // and 10 and at OpenPBR's anisotropy 1 (alpha_min 1e-4, alpha_max sqrt 2 times the mean
    // roughness), against fresh 32^2 estimates: each difference within the range the generated
    // header states for its side (table - fresh at 4000 random points of the domain)
    // widened by 4 standard errors of the fresh estimate.
    constexpr std::size_t strata = 32;
    double low[2] = {0, 0}, high[2] = {0, 0};
    for (const double eta : {1.5, 1.6 / 1.5})
        for (const double ratio : {2.0, 10.0, 0.0})
            for (const bool swap : {false, true})
                for (const double alpha : {0.1, 0.3, 0.44})
                    for (const double mu : {0.2, 0.5, 0.9})
                        for (const double degrees : {0.0, 30.0, 60.0, 90.0, 135.0})
                            for (const std::size_t side : {std::size_t(0), std::size_t(1)}) {
                                const double phi = degrees * shade::pi<double> / 180;
                                // ratio 0: anisotropy 1, the rougher alpha sqrt 2 alpha (roughness_to_alpha)
                                const double smooth = ratio > 0 ? alpha / std::sqrt(ratio) : 1e-4;
                                const double rough = ratio > 0 ? alpha * std::sqrt(ratio) : std::sqrt(2.0) * alpha;
                                const double alpha_x = swap ? rough : smooth, alpha_y = swap ? smooth : rough;
                                const auto v = view(mu, side, phi);
                                const auto fresh = fresh_reflection(alpha_x, alpha_y, eta, v, strata, 900);
                                const double r = shade::dielectric_reflection_albedo(v, alpha_x, alpha_y, eta_of_side(side, eta));
                                CAPTURE(eta);
                                CAPTURE(ratio);
                                CAPTURE(swap);
                                CAPTURE(alpha);
                                CAPTURE(mu);
                                CAPTURE(degrees);
                                CAPTURE(side);
                                CAPTURE(fresh.albedo.x);
                                CHECK(r - fresh.albedo.x >= anisotropic_low[side] - 4 * fresh.standard_error.x);
                                CHECK(r - fresh.albedo.x <= anisotropic_high[side] + 4 * fresh.standard_error.x);
                                low[side] = std::min(low[side], r - fresh.albedo.x);
                                high[side] = std::max(high[side], r - fresh.albedo.x);
                            }
    MESSAGE("anisotropic reflection albedo - fresh: " << low[0] << " to " << high[0] << " (v outside), " << low[1]
                                                      << " to " << high[1] << " (inside)");
}

namespace {

// detail::anisotropic_reflection_albedo_grid (what a material reads) against fresh 64^2
// estimates of the model on the rarer side's views, interfaces (eta, alpha_x, alpha_y) over
// the given lists, at view cosines mus and azimuths degrees: read - fresh asserted within
// [low_bound, high_bound] widened by 4 standard errors; returns the range found and the
// largest |error| of the correction table alone (detail::anisotropic_reflection_albedo) at
// the same views. With without_margin the grids are read by at_without_margin.
struct grid_against_fresh {
    double low = 1, high = -1, table_worst = 0;
};
struct alphas {
    double x, y;
};
template <class T>
grid_against_fresh check_grid_against_fresh(std::initializer_list<double> etas, std::initializer_list<alphas> interfaces,
                                            std::initializer_list<double> mus, std::initializer_list<double> azimuths,
                                            std::uint64_t seed, double low_bound, double high_bound,
                                            bool without_margin = false) {
    constexpr std::size_t strata = 64;
    grid_against_fresh out;
    for (const double eta : etas)
        for (const alphas& a : interfaces) {
            const d::anisotropic_reflection_albedo_grid<T> per_interface(T(a.x), T(a.y), T(eta));
            const d::anisotropic_reflection_albedo<T> plain(T(a.x), T(a.y), T(eta));
            for (const double mu : mus)
                for (const double degrees : azimuths) {
                    const auto v = view(mu, 0, degrees * shade::pi<double> / 180);
                    const auto fresh = fresh_reflection(a.x, a.y, eta, v, strata, seed);
                    const vec3<T> w(v);
                    const double error =
                        double(without_margin ? per_interface.at_without_margin(w) : per_interface.at(w)) -
                        fresh.albedo.x;
                    CAPTURE(eta);
                    CAPTURE(a.x);
                    CAPTURE(a.y);
                    CAPTURE(mu);
                    CAPTURE(degrees);
                    CAPTURE(fresh.albedo.x);
                    CHECK(error >= low_bound - 4 * fresh.standard_error.x);
                    CHECK(error <= high_bound + 4 * fresh.standard_error.x);
                    out.low = std::min(out.low, error);
                    out.high = std::max(out.high, error);
                    out.table_worst = std::max(out.table_worst, std::abs(double(plain.at(w)) - fresh.albedo.x));
                }
        }
    return out;
}

} // namespace

TEST_CASE_TEMPLATE("dielectric reflection albedo: beyond eta_hat 3 an anisotropic interface's grid reads at or above direct estimates",
                   T, float, double) {
    // detail::anisotropic_reflection_albedo_grid (what a material reads) above the correction
    // table's eta 3 on the rarer side: eta 3.5, 6 and 20, at 5:1, 1.25:1 and 24:1 and with a
    // rougher alpha above 1, both axes rougher in turn, mu 0.1-0.95 and six azimuths, against
    // fresh 64^2 estimates of the model: read - fresh at least -4 standard errors (it reads at
    // or above, so a material's white furnace does not exceed 1) and at most 1e-2 (its
    // margin 2e-3 plus the quadrature's error, measured within +5e-3; the 24:1 interface at
    // alpha 1.2 is on the grid of strong anisotropy, the next test's: up to +8e-3). The table alone, its
    // correction read at 3, errs by several per cent here (asserted: its largest |error| is
    // above 2e-2, so these points test the grid and not the table). At eta 2.4 and 1.05
    // the grid is the table, value for value (below 1 it integrates: the test below).
    const grid_against_fresh found = check_grid_against_fresh<T>(
        {3.5, 6.0, 20.0}, {{0.3, 0.06}, {0.06, 0.3}, {0.15, 0.12}, {1.2, 0.05}, {0.4, 0.9}}, {0.1, 0.3, 0.6, 0.95},
        {0.0, 25.0, 50.0, 75.0, 90.0, 140.0}, 901, 0.0, 1e-2);
    MESSAGE("anisotropic grid beyond eta 3 - fresh: " << found.low << " to " << found.high
                                                      << "; the table alone: |error| up to " << found.table_worst);
    CHECK(found.table_worst > 2e-2);
    for (const double eta : {2.4, 1.05}) {
        const d::anisotropic_reflection_albedo_grid<T> extended(T(0.3), T(0.06), T(eta));
        CHECK(!extended.integrated_below_one());
        const d::anisotropic_reflection_albedo<T> plain(T(0.3), T(0.06), T(eta));
        for (const double mu : {0.1, 0.5, 1.0})
            for (const double degrees : {0.0, 40.0, 90.0}) {
                const vec3<T> w(view(mu, 0, degrees * shade::pi<double> / 180));
                CHECK(extended.at(w) == plain.at(w));
            }
    }
}

TEST_CASE_TEMPLATE("dielectric reflection albedo: at strong anisotropy above 1 an interface's grid reads at or above direct estimates, along its smoother axis too",
                   T, float, double) {
    // From the rarer side at alpha_max / alpha_min >= 20 (and alpha_max >= 0.25) the
    // correction table is interpolated across a feature a few degrees wide around the
    // smoother axis at grazing views and reads up to 0.08 high there (asserted: the table
    // alone errs by more than 0.03 at these points), and the correction beyond 3 on its 13
    // azimuths read up to 0.05 low. detail::anisotropic_reflection_albedo_grid integrates
    // R_ss per interface there: eta 1.05, 1.5 and 6, 100:1 at alpha_max 1.41 (roughness 1,
    // anisotropy 0.99), both axes smoother in turn, 100:1 at 0.69 and 0.35, 50:1 at 1.41;
    // mu 0.1-0.6 and azimuths crowded toward both axes, against fresh 64^2 estimates: read -
    // fresh at least -4 standard errors and at most 1e-2 (its margin 3e-3 plus the rows'
    // interpolation and the quadrature: measured within +9e-3 on probes of 300 views).
    const grid_against_fresh found = check_grid_against_fresh<T>(
        {1.05, 1.5, 6.0}, {{1.414, 0.01414}, {0.01414, 1.414}, {0.693, 0.00693}, {0.3535, 0.003535}, {1.414, 0.0283}},
        {0.1, 0.15, 0.2, 0.3, 0.6}, {0.0, 1.0, 3.0, 30.0, 70.0, 85.0, 87.0, 88.5, 89.5, 90.0}, 907, 0.0, 1e-2);
    MESSAGE("anisotropic grid at strong anisotropy above 1 - fresh: " << found.low << " to " << found.high
                                                                      << "; the table alone: |error| up to "
                                                                      << found.table_worst);
    CHECK(found.table_worst > 3e-2);
    // Below the anisotropy (19:1) or the roughness (alpha_max 0.2) at which it integrates,
    // the grid is the table, value for value.
    for (const std::array<double, 2> a : {std::array<double, 2>{0.95, 0.05}, std::array<double, 2>{0.2, 0.002}}) {
        const d::anisotropic_reflection_albedo_grid<T> grid_or_table{T(a[0]), T(a[1]), T(1.5)};
        const d::anisotropic_reflection_albedo<T> plain{T(a[0]), T(a[1]), T(1.5)};
        CHECK(!grid_or_table.integrated());
        for (const double mu : {0.1, 0.5, 1.0})
            for (const double degrees : {0.0, 40.0, 90.0}) {
                const vec3<T> w(view(mu, 0, degrees * shade::pi<double> / 180));
                CHECK(grid_or_table.at(w) == plain.at(w));
            }
    }
}

TEST_CASE_TEMPLATE("dielectric reflection albedo: near index match from the denser side an anisotropic interface's grid reads at or above direct estimates",
                   T, float, double) {
    // Below an index ratio of 1 but above 1 / 1.05 the correction table is extrapolated (scaled
    // toward 0 at 1), and grazing views below the critical cosine along the smoother axis
    // reflect totally where it reads half that (asserted: the table alone errs by more than
    // 0.1 here). detail::anisotropic_reflection_albedo_grid integrates R_ss per interface
    // there: eta 0.96, 0.975 and 0.99 (critical cosines 0.28, 0.22, 0.14), 2.4:1, 48:1, 10:1
    // and 1.1:1, both axes smoother in turn, mu 0.05-0.95 and six azimuths, against fresh
    // 64^2 estimates of the model: read - fresh at least -1e-3 - 4 standard errors (so a
    // material's white furnace stays at most 1.001; measured +1.4e-3 at the lowest) and at
    // most 0.03: just above the critical cosine along the smoother axis of a surface that is
    // nearly smooth along it, R_ss falls by up to 1 - F within a few hundredths of mu, which
    // the rows (dense toward mu_c from both sides) bridge from above (measured 0.016; 0.158
    // with 12 even rows above mu_c and 24^2 visible normals).
    const grid_against_fresh found =
        check_grid_against_fresh<T>({0.96, 0.975, 0.99}, {{0.38, 0.16}, {0.48, 0.01}, {0.02, 0.2}, {0.5, 0.45}},
                                    {0.05, 0.1, 0.15, 0.2, 0.3, 0.6, 0.95}, {0.0, 30.0, 60.0, 80.0, 90.0, 110.0}, 907,
                                    -1e-3, 0.03);
    MESSAGE("anisotropic grid near index match, denser side - fresh: " << found.low << " to " << found.high
                                                                        << "; the table alone: |error| up to "
                                                                        << found.table_worst);
    CHECK(found.table_worst > 0.1);
    // Copies own their grid: a copy reads as the original after the original is gone.
    const vec3<T> w(view(0.1, 0, shade::pi<double> / 2));
    auto original = std::make_unique<d::anisotropic_reflection_albedo_grid<T>>(T(0.38), T(0.16), T(0.96));
    const T expected = original->at(w);
    const d::anisotropic_reflection_albedo_grid<T> copy(*original);
    d::anisotropic_reflection_albedo_grid<T> assigned;
    assigned = *original;
    const d::anisotropic_reflection_albedo_grid<T> moved(std::move(*original));
    original.reset();
    CHECK(copy.at(w) == expected);
    CHECK(assigned.at(w) == expected);
    CHECK(moved.at(w) == expected);
}

TEST_CASE_TEMPLATE("dielectric reflection albedo: below an index ratio of 1 an anisotropic interface's grid reads R_ss from either side within its bounds",
                   T, float, double) {
    // The grid integrates R_ss for the interface at every index ratio below 1 (here 0.4,
    // 0.6 and 0.8: critical cosines 0.92, 0.80, 0.60), where the table reads it from 0.03 low
    // to 0.18 high (asserted: its largest |error| at these views is above 0.03, so the
    // points test the grid). 2.4:1, 10:1 and 1.1:1 at moderate roughness, both axes smoother in turn, mu
    // 0.05-1 and six azimuths, against fresh 64^2 estimates of the model. at() keeps the
    // near-index form's bound from below, -1e-3 - 4 standard errors, and reads at most 0.02
    // high (its margin 5e-3 plus the quadrature and the chords above the critical cosine,
    // where R_ss is convex; measured +1.1e-3 to +9.9e-3). at_without_margin, which the
    // material reads under a thin film (openpbr_surface), within [-0.012, +0.012] (measured
    // -5.3e-3 to +5.9e-3; +-9e-3 over 4,800 random views in a probe): the 40 x 40
    // quadrature's error, which 24^2 visible normals, 12 even rows above the critical cosine
    // and bilinear reads left at +0.02 near the pole and up to +0.2 just above mu_c.
    const grid_against_fresh with_margin =
        check_grid_against_fresh<T>({0.4, 0.6, 0.8}, {{0.38, 0.16}, {0.16, 0.38}, {0.6, 0.06}, {0.5, 0.45}},
                                    {0.05, 0.2, 0.5, 0.75, 0.85, 0.95, 1.0}, {0.0, 30.0, 60.0, 90.0, 110.0, 160.0}, 911,
                                    -1e-3, 0.02, false);
    const grid_against_fresh without =
        check_grid_against_fresh<T>({0.4, 0.6, 0.8}, {{0.38, 0.16}, {0.16, 0.38}, {0.6, 0.06}, {0.5, 0.45}},
                                    {0.05, 0.2, 0.5, 0.75, 0.85, 0.95, 1.0}, {0.0, 30.0, 60.0, 90.0, 110.0, 160.0}, 911,
                                    -0.012, 0.012, true);
    MESSAGE("anisotropic grid integrated below 1 - fresh: at() " << with_margin.low << " to " << with_margin.high
                                                                  << ", at_without_margin() " << without.low << " to "
                                                                  << without.high << "; the table alone: |error| up to "
                                                                  << with_margin.table_worst);
    CHECK(with_margin.table_worst > 0.03);
    // Isotropic, or above 1, there is no grid: at_without_margin is at(), the table.
    for (const std::array<double, 3> interface : {std::array<double, 3>{0.3, 0.3, 0.6}, std::array<double, 3>{0.38, 0.16, 1.5}}) {
        const T ax = T(interface[0]), ay = T(interface[1]), eta = T(interface[2]);
        const d::anisotropic_reflection_albedo_grid<T> grid_or_table{ax, ay, eta};
        const d::anisotropic_reflection_albedo<T> plain{ax, ay, eta};
        CHECK(!grid_or_table.integrated_below_one());
        for (const double mu : {0.1, 0.5, 1.0}) {
            const vec3<T> w(view(mu, 0, 0.7));
            CHECK(grid_or_table.at(w) == plain.at(w));
            CHECK(grid_or_table.at_without_margin(w) == plain.at(w));
        }
    }
}

TEST_CASE_TEMPLATE("dielectric reflection albedo: below an index ratio of 1 a narrow anisotropic interface reads R_ss at or above direct estimates around the critical cosine",
                   T, float, double) {
    // A narrow lobe's R_ss steps from 1 toward F(mu) within about alpha sin(theta_c) of the
    // critical cosine mu_c; the grid's rows (a few thousandths apart there) bridged the step
    // with chords reading R_ss up to 0.085 low below mu_c (an opaque material's white
    // furnace, 1 + true - read, reached 1.042 for alphas 0.0036 and 0.0011 at index 0.5).
    // With alpha_min <= window_alpha_max R_ss is read from an anisotropic_kink_window over
    // the grid's rows within window_rows of mu_c (cells crowding toward mu_c, each lifted over
    // its bilinear read). Against fresh 64^2 estimates of the model at views within 0.004 of
    // mu_c, five azimuths, narrow and one-axis-narrow interfaces (both axes smoother in turn)
    // at three index ratios: at() at least -1e-3 - 4 standard errors below (the furnace at
    // most 1.001) and at most 0.03 above; at_without_margin() (the transmission's read of
    // R_ss under a film) at most 0.012 above. The one interface nearly smooth along one axis
    // (alphas 1e-4 and 0.2263) reads up to 0.045 high on that axis just below mu_c: there
    // R_ss is flat (c = mu cos(theta_m) < mu_c, total reflection) and falls as soon as the
    // view turns off the axis, so the window's first azimuth cell is lifted by what its
    // halfway azimuth rises above the chord (measured +0.036; the grid alone read +0.01 there
    // and 0.01 low just above mu_c).
    using d::anisotropic_reflection_albedo_grid;
    double low = 1, high = -1, without_high = -1;
    for (const double eta : {0.3, 0.5, 0.9})
        for (const alphas a : {alphas{0.0036, 0.0011}, alphas{0.0011, 0.0036}, alphas{0.0141, 1e-4}, alphas{0.05, 0.03},
                               alphas{1e-4, 0.2263}}) {
            const anisotropic_reflection_albedo_grid<T> g(T(a.x), T(a.y), T(eta));
            REQUIRE(g.windowed());
            const double mu_c = std::sqrt(1 - eta * eta);
            for (const double offset : {-0.004, -0.001, -0.0003, 0.0, 0.0003, 0.001, 0.004})
                for (const double degrees : {0.0, 30.0, 60.0, 85.0, 90.0}) {
                    const auto v = view(mu_c + offset, 0, degrees * shade::pi<double> / 180);
                    const auto fresh = fresh_reflection(a.x, a.y, eta, v, 64, 919);
                    const vec3<T> w(v);
                    const double error = double(g.at(w)) - fresh.albedo.x;
                    const double without = double(g.at_without_margin(w)) - fresh.albedo.x;
                    CAPTURE(eta);
                    CAPTURE(a.x);
                    CAPTURE(a.y);
                    CAPTURE(offset);
                    CAPTURE(degrees);
                    CAPTURE(fresh.albedo.x);
                    CHECK(error >= -1e-3 - 4 * fresh.standard_error.x);
                    const double high_bound = std::min(a.x, a.y) / std::max(a.x, a.y) < 1e-3 ? 0.045 : 0.03;
                    CHECK(error <= high_bound + 4 * fresh.standard_error.x);
                    CHECK(without <= 0.012 + 4 * fresh.standard_error.x);
                    low = std::min(low, error);
                    high = std::max(high, error);
                    without_high = std::max(without_high, without);
                }
        }
    MESSAGE("narrow anisotropic interface below 1 around mu_c, read - fresh: at() " << low << " to " << high
                                                                                     << ", at_without_margin() up to "
                                                                                     << without_high);
    // Wider lobes keep the grid alone.
    CHECK(!anisotropic_reflection_albedo_grid<T>(T(0.38), T(0.16), T(0.5)).windowed());
    // Copies own their window: a copy reads as the original after the original is gone, at
    // a view inside the window (mu_c - 0.001 at index 0.5).
    const vec3<T> w(view(std::sqrt(0.75) - 0.001, 0, 1.2));
    auto original = std::make_unique<anisotropic_reflection_albedo_grid<T>>(T(0.0036), T(0.0011), T(0.5));
    REQUIRE(original->windowed());
    const T expected = original->at(w), expected_below = original->at_without_margin(w);
    const anisotropic_reflection_albedo_grid<T> copy(*original);
    anisotropic_reflection_albedo_grid<T> assigned;
    assigned = *original;
    const anisotropic_reflection_albedo_grid<T> moved(std::move(*original));
    original.reset();
    const anisotropic_reflection_albedo_grid<T>& assigned_read = assigned;
    for (const anisotropic_reflection_albedo_grid<T>* g : {&copy, &assigned_read, &moved}) {
        CHECK(g->windowed());
        CHECK(g->at(w) == expected);
        CHECK(g->at_without_margin(w) == expected_below);
    }
}

TEST_CASE_TEMPLATE("dielectric reflection albedo: below an index ratio of 1 a strongly anisotropic interface reads R_ss at or above direct estimates along its total-reflection curve",
                   T, float, double) {
    // On a surface rough along x and nearly smooth along y, every facet sees a view beyond
    // the critical angle once even the facet tilted most toward it (along x) does:
    // mu^2 + (1 - mu^2) cos^2(phi) < mu_c^2, phi the view's azimuth from x. Along that curve
    // R_ss has a kink that runs diagonally across the grid's cells, away from mu_c (which the
    // curve reaches only along y), and their bilinear reads fell up to 0.018 below R_ss,
    // beyond the 1e-2 margin (measured read - true -6e-3 for alphas 0.7094 x 0.00903 at
    // index 0.861, mu 0.387, phi 1.216 from x; the furnace 1.006-1.009). The cells near the
    // curve are lifted (dielectric_side_grid::lift_cells). Against fresh 64^2 estimates at
    // views on and beside the curve for three such interfaces (both axes smoother in turn):
    // at least -1e-3 - 4 standard errors.
    using d::anisotropic_reflection_albedo_grid;
    double low = 1, high = -1;
    for (const std::array<double, 3> interface : {std::array<double, 3>{0.7094, 0.00903, 0.861},
                                                  std::array<double, 3>{0.00903, 0.7094, 0.861},
                                                  std::array<double, 3>{0.3576, 0.0052, 0.545}}) {
        const double ax = interface[0], ay = interface[1], eta = interface[2];
        const anisotropic_reflection_albedo_grid<T> g{T(ax), T(ay), T(eta)};
        const double mu_c = std::sqrt(1 - eta * eta);
        for (const double mu : {0.6 * mu_c, 0.75 * mu_c, 0.9 * mu_c})
            for (const double offset : {-0.03, -0.01, 0.0, 0.01, 0.03}) {
                // The curve's azimuth from the rougher axis at mu, then a step beside it.
                const double cos_rough = std::sqrt((mu_c * mu_c - mu * mu) / (1 - mu * mu));
                const double from_rough = std::acos(cos_rough) + offset;
                const double phi = ax > ay ? from_rough : shade::pi<double> / 2 - from_rough;
                const auto v = view(mu, 0, phi);
                const auto fresh = fresh_reflection(ax, ay, eta, v, 64, 921);
                const double error = double(g.at(vec3<T>(v))) - fresh.albedo.x;
                CAPTURE(ax);
                CAPTURE(ay);
                CAPTURE(eta);
                CAPTURE(mu);
                CAPTURE(phi);
                CAPTURE(fresh.albedo.x);
                CHECK(error >= -1e-3 - 4 * fresh.standard_error.x);
                low = std::min(low, error);
                high = std::max(high, error);
            }
    }
    MESSAGE("strongly anisotropic interface below 1 along its total-reflection curve, read - fresh: " << low << " to "
                                                                                                      << high);
}

TEST_CASE_TEMPLATE("dielectric reflection albedo: the anisotropic grid below 1 reads finite values at its extremes", T, float,
                   double) {
    // At the smallest index ratio (1e-4: the critical cosine sqrt(1 - 1e-8) is 1 in float,
    // and the rows above it would all sit at 1) and for directions with NaN or infinite
    // components (a grid read must not turn NaN into a node index), at() and
    // at_without_margin() read values in [0, 1].
    for (const double eta : {1e-4, 0.5}) {
        const d::anisotropic_reflection_albedo_grid<T> grid_below(T(0.3), T(0.1), T(eta));
        REQUIRE(grid_below.integrated_below_one());
        const T nan = std::numeric_limits<T>::quiet_NaN(), inf = std::numeric_limits<T>::infinity();
        for (const vec3<T>& w : {vec3<T>(0, 0, 1), vec3<T>(T(0.6), T(0.8), 0), vec3<T>(T(0.6), 0, T(0.8)),
                                 vec3<T>(nan, 0, nan), vec3<T>(inf, 1, T(0.5)), vec3<T>(inf, inf, inf),
                                 vec3<T>(0, nan, 1)}) {
            CAPTURE(eta);
            CAPTURE(w.x);
            CAPTURE(w.y);
            CAPTURE(w.z);
            for (const T r : {grid_below.at(w), grid_below.at_without_margin(w)}) {
                CHECK(r >= T(0));
                CHECK(r <= T(1));
            }
        }
    }
}

TEST_CASE("dielectric reflection albedo: the side grid's read from below stays under a concave-then-convex function") {
    // dielectric_side_grid::at_or_below on a function of mu alone (the same at every
    // azimuth) shaped as R_ss of a side with total internal reflection: concave below the
    // critical cosine mu_c (1 - 0.3 (mu / mu_c)^4), convex above it (0.68 exp(-8 (mu -
    // mu_c)) + 0.02, continuous at mu_c). The chords of a concave function lie below it and
    // a convex function lies above the lines through two of its points outside them, so
    // at_or_below never exceeds the function (up to the nodes' float rounding); at(), linear
    // in the rows' coordinate, reads above it on the convex side (asserted: the check can
    // fail).
    const double eta = 0.6, mu_c = std::sqrt(1 - eta * eta);
    const auto f = [mu_c](double mu) {
        return mu <= mu_c ? 1 - 0.3 * std::pow(mu / mu_c, 4) : 0.68 * std::exp(-8 * (mu - mu_c)) + 0.02;
    };
    const d::dielectric_side_grid<double> side(0.3, 0.1, eta, 0.0, 0.0,
                                               [&f](const vec3<double>& v) { return f(v.z); }, true);
    double at_above = 0;
    for (int k = 0; k <= 2000; ++k) {
        const double mu = 0.001 + 0.999 * k / 2000.0;
        const vec3<double> w = view(mu, 0, 0.37 * k);
        CAPTURE(mu);
        CHECK(side.at_or_below(w) <= f(mu) + 1e-6);
        at_above = std::max(at_above, side.at(w) - f(mu));
    }
    CHECK(at_above > 1e-4);
}

TEST_CASE("dielectric reflection albedo: the anisotropic grid's coordinates") {
    // The exiting side's azimuth coordinate puts the kink phi_k (sin(theta) cos(phi_k) =
    // 1 / eta_hat) on u = 1/2 and its view coordinate the critical cosine on x = 1/2, both
    // nodes; each coordinate increases and is inverted by its inverse.
    for (const double eta_hat : {1.05, 1.5, 3.0}) {
        const double mu_c = std::sqrt(1 - 1 / (eta_hat * eta_hat));
        CHECK(d::reflection_anisotropic_x<double>(1, mu_c, mu_c) == doctest::Approx(0.5));
        CHECK((ax_nodes - 1) % 2 == 0);
        CHECK((au_nodes - 1) % 2 == 0);
        for (const double mu : {0.05, 0.3, 0.6, 0.99}) {
            const double sin_theta = std::sqrt((1 - mu) * (1 + mu));
            const double phi_k = d::reflection_anisotropic_kink(sin_theta, 1 / eta_hat);
            if (sin_theta > 1 / eta_hat) {
                CHECK(sin_theta * std::cos(phi_k) == doctest::Approx(1 / eta_hat));
                CHECK(d::reflection_anisotropic_u<double>(1, phi_k, phi_k, 0.5) == doctest::Approx(0.5));
            } else {
                CHECK(phi_k == 0);
            }
            for (const std::size_t side : {std::size_t(0), std::size_t(1)}) {
                for (const double ratio : {0.0, 1e-4, 0.04, 0.5, 0.999999}) {
                    double previous = -1;
                    for (int i = 0; i <= 90; ++i) {
                        const double phi = i * shade::pi<double> / 180;
                        const double u = d::reflection_anisotropic_u<double>(side, phi, phi_k, ratio);
                        CHECK(u >= previous);
                        previous = u;
                        if (side == 0 || phi >= phi_k)
                            CHECK(d::reflection_anisotropic_phi(side, u, phi_k, ratio) == doctest::Approx(phi).epsilon(1e-9));
                    }
                }
                CHECK(d::reflection_anisotropic_x<double>(side, d::reflection_anisotropic_mu(side, 0.37, mu_c), mu_c) ==
                      doctest::Approx(0.37));
                CHECK(d::reflection_anisotropic_x<double>(side, d::reflection_anisotropic_mu(side, 0.81, mu_c), mu_c) ==
                      doctest::Approx(0.81));
            }
        }
    }
}

TEST_CASE("dielectric reflection albedo: the entering side's azimuth coordinate follows the projected roughness") {
    // Side 0's u is defined by u^3 = (alpha_phi - alpha_min) / (alpha_max - alpha_min), alpha_phi
    // = sqrt(alpha_min^2 cos^2 phi + alpha_max^2 sin^2 phi) (Heitz 2014, eq. 80), computed in
    // the header in a form without cancellation; here straight from the definition. Its ends:
    // 0 on the smoother axis and 1 on the rougher one at any ratio, and at ratio 0 u^3 = sin(phi).
    for (const double ratio : {0.0, 1e-4, 0.04, 0.3, 0.9}) {
        CHECK(d::reflection_anisotropic_u<double>(0, 0.0, 0.0, ratio) == 0);
        CHECK(d::reflection_anisotropic_u<double>(0, shade::pi<double> / 2, 0.0, ratio) == doctest::Approx(1.0).epsilon(1e-12));
        for (int i = 1; i < 90; ++i) {
            const double phi = i * shade::pi<double> / 180, c = std::cos(phi), s = std::sin(phi);
            const double projected = std::sqrt(ratio * ratio * c * c + s * s); // alpha_phi / alpha_max
            const double expected = std::cbrt((projected - ratio) / (1 - ratio));
            CHECK(d::reflection_anisotropic_u<double>(0, phi, 0.0, ratio) == doctest::Approx(expected).epsilon(1e-12));
            if (ratio == 0) CHECK(std::pow(d::reflection_anisotropic_u<double>(0, phi, 0.0, ratio), 3) == doctest::Approx(s).epsilon(1e-12));
        }
    }
    // A view at the pole (phi 0, both alphas 0 impossible here) reads u = 0 without NaN at ratio 0.
    CHECK(d::reflection_anisotropic_u<float>(0, 0.0f, 0.0f, 0.0f) == 0.0f);
}

TEST_CASE("dielectric reflection albedo: the anisotropic grid's roughness coordinate") {
    // Entering, y = sqrt(alpha_max / sqrt 2): alpha_max sqrt 2 is y = 1, sqrt 2 / 4 is 1/2.
    // Exiting, y = sqrt(alpha_rms): OpenPBR's roughness_to_alpha gives alpha_t = r^2 sqrt(2 /
    // (1 + b^2)) and alpha_b = b alpha_t (b = 1 - anisotropy), so alpha_rms^2 = (alpha_t^2 +
    // alpha_b^2) / 2 = r^4 and y = r whatever the anisotropy: roughness 1 is the last node.
    CHECK(d::reflection_anisotropic_y(0, 0.3, std::sqrt(2.0)) == doctest::Approx(1.0));
    CHECK(d::reflection_anisotropic_y(0, 0.0, std::sqrt(2.0) / 4) == doctest::Approx(0.5));
    for (const double r : {0.1, 0.5, 0.9, 1.0})
        for (const double anisotropy : {0.0, 0.5, 0.9, 1.0}) {
            const double b = 1 - anisotropy, alpha_t = r * r * std::sqrt(2 / (1 + b * b)), alpha_b = b * alpha_t;
            CHECK(d::reflection_anisotropic_y(1, alpha_b, alpha_t) == doctest::Approx(r).epsilon(1e-12));
            // The generator's inverse: alpha_max of (y, z = sqrt(alpha_min / alpha_max)).
            CHECK(d::reflection_anisotropic_alpha_max(1, r, std::sqrt(b)) == doctest::Approx(alpha_t).epsilon(1e-12));
            CHECK(d::reflection_anisotropic_alpha_max(0, d::reflection_anisotropic_y(0, alpha_b, alpha_t), std::sqrt(b)) ==
                  doctest::Approx(alpha_t).epsilon(1e-12));
        }
    // Rougher than the axis's end reads the end (sqrt 2 entering, alpha_rms 1 exiting).
    CHECK(d::reflection_anisotropic_y(0, 1.0, 3.0) == 1.0);
    CHECK(d::reflection_anisotropic_y(1, 0.5, 1.5) == 1.0);
}

TEST_CASE_TEMPLATE("dielectric reflection albedo: the anisotropic form's limits, pole and grid ends", T, float, double) {
    const vec3<T> w = vec3<T>(view(0.4, 0, 0.7));
    // Equal alphas: the isotropic form exactly.
    CHECK(shade::dielectric_reflection_albedo(w, T(0.3), T(0.3), T(1.5)) ==
          shade::dielectric_reflection_albedo(T(0.4), T(0.3), T(1.5)));
    // Index-matched: nothing reflected, whatever the anisotropy.
    CHECK(shade::dielectric_reflection_albedo(w, T(0.1), T(0.9), T(1)) == T(0));
    // Anisotropy 1 is on the grid (s = alpha_min / alpha_max = 0): alpha_min 0 and
    // OpenPBR's 1e-4 read nearly the same (s 0 and 8e-5).
    for (const double phi : {0.0, 0.5, 1.2})
        for (const T eta_s : {T(1.5), T(1 / 1.5)}) {
            const vec3<T> v = vec3<T>(view(0.6, 0, phi));
            CHECK(std::abs(shade::dielectric_reflection_albedo(v, T(1e-4), T(1.2), eta_s) -
                           shade::dielectric_reflection_albedo(v, T(0), T(1.2), eta_s)) < T(1e-3));
        }
    // The correction depends on the azimuth: along the smoother and the rougher axis differ,
    // and exchanging the alphas exchanges the azimuths.
    const vec3<T> along_t = vec3<T>(view(0.3, 0, 0)), along_b = vec3<T>(view(0.3, 0, 0.5 * shade::pi<double>));
    CHECK(std::abs(shade::dielectric_reflection_albedo(along_t, T(0.05), T(0.5), T(1.5)) -
                   shade::dielectric_reflection_albedo(along_b, T(0.05), T(0.5), T(1.5))) > T(0.01));
    CHECK(shade::dielectric_reflection_albedo(along_t, T(0.05), T(0.5), T(1.5)) ==
          doctest::Approx(double(shade::dielectric_reflection_albedo(along_b, T(0.5), T(0.05), T(1.5)))).epsilon(1e-5));
    // The sign of w.z does not matter (eta_s names the side).
    const vec3<T> below(w.x, w.y, -w.z);
    CHECK(shade::dielectric_reflection_albedo(below, T(0.1), T(0.5), T(1 / 1.5)) ==
          shade::dielectric_reflection_albedo(w, T(0.1), T(0.5), T(1 / 1.5)));
    // At the pole the azimuth is undefined and R_ss of the interface does not depend on it:
    // the readings 1e-5 off the pole (mu = 1 - 5e-11) at any azimuth and the pole's each lie
    // within their side's stated range of the one true value, so they differ by at most its
    // width.
    for (const std::size_t side : {std::size_t(0), std::size_t(1)})
        for (const T eta_hat : {T(1.5), T(2.2)})
            for (const auto& alphas : {std::pair<T, T>(T(0.1), T(0.5)), std::pair<T, T>(T(0.7), T(0.2))}) {
                const T eta_s = side == 0 ? eta_hat : T(1) / eta_hat;
                const T pole = shade::dielectric_reflection_albedo(vec3<T>(0, 0, 1), alphas.first, alphas.second, eta_s);
                for (const double phi : {0.0, 0.7, 1.5708, 2.5}) {
                    const vec3<T> near(T(1e-5 * std::cos(phi)), T(1e-5 * std::sin(phi)), T(1));
                    CHECK(std::abs(shade::dielectric_reflection_albedo(near, alphas.first, alphas.second, eta_s) - pole) <=
                          T(anisotropic_high[side] - anisotropic_low[side]));
                }
            }
    // detail::anisotropic_reflection_albedo (one interface, many views) is what the function
    // reads, the committed table its default.
    for (const T eta_s : {T(1.5), T(1 / 1.5), T(1.02), T(4)})
        for (const auto& alphas : {std::pair<T, T>(T(0.1), T(0.5)), std::pair<T, T>(T(0.7), T(0.2)),
                                   std::pair<T, T>(T(1e-4), T(1.4))}) {
            const d::anisotropic_reflection_albedo<T> interface(alphas.first, alphas.second, eta_s);
            for (const double mu : {0.05, 0.3, 0.8, 1.0})
                for (const double phi : {0.0, 1.0, 2.5}) {
                    const vec3<T> v = vec3<T>(view(mu, 0, phi));
                    const T r = shade::dielectric_reflection_albedo(v, alphas.first, alphas.second, eta_s);
                    CHECK(interface.at(v) == r);
                    CHECK(interface.at(v, anisotropic_delta) == r);
                    CHECK(r >= T(0));
                    CHECK(r <= T(1));
                }
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
    const vec3<T> w(T(0.6), T(0), T(0.8));
    CHECK_THROWS_AS((void)shade::dielectric_reflection_albedo(w, T(0.3), T(-1), T(1.5)), shade::invalid_parameter);
    CHECK_THROWS_WITH((void)shade::dielectric_reflection_albedo(w, T(0.3), T(0.3), T(2e4)), doctest::Contains("eta_s"));
    CHECK_THROWS_WITH((void)shade::dielectric_reflection_albedo(vec3<T>(T(0.6), T(0), T(0.6)), T(0.3), T(0.2), T(1.5)),
                      doctest::Contains("w"));
    CHECK_THROWS_WITH((void)shade::dielectric_reflection_albedo(vec3<T>(nan, T(0), T(1)), T(0.3), T(0.2), T(1.5)),
                      doctest::Contains("w"));
    CHECK_THROWS_WITH((void)shade::dielectric_reflection_albedo(w, nan, T(0.2), T(1.5)), doctest::Contains("alpha_x"));
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
