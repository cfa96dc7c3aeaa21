// The committed rough-dielectric albedo tables (shade/bsdf/detail/dielectric_albedo_data.hpp
// and beckmann_dielectric_albedo_data.hpp, and their continuations above eta_hat 3,
// *_beyond_data.hpp, written by examples/dielectric_albedo_tables.cpp) against a coarse regeneration with
// shade::rough_dielectric's own sampler, so they cannot drift from the model; their E_avg
// against the rows they average; the grid and interpolation of
// shade/bsdf/dielectric_albedo_table.hpp.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <iterator>
#include <vector>

#include <doctest/doctest.h>

#include <shade/brdf/microfacet/beckmann.hpp>
#include <shade/brdf/microfacet/ggx.hpp>
#include <shade/bsdf/detail/beckmann_dielectric_albedo_beyond_data.hpp>
#include <shade/bsdf/detail/beckmann_dielectric_albedo_data.hpp>
#include <shade/bsdf/detail/dielectric_albedo_beyond_data.hpp>
#include <shade/bsdf/detail/dielectric_albedo_data.hpp>
#include <shade/bsdf/dielectric_albedo_table.hpp>
#include <shade/bsdf/rough_dielectric.hpp>

#include "bsdf/dielectric_albedo.hpp"

namespace {

namespace d = shade::detail;
constexpr d::dielectric_albedo_grid grid{}; // the GGX table's
constexpr const d::dielectric_albedo_grid& beckmann_grid = d::dielectric_beckmann_albedo_grid;

// The generated header states the largest node standard error; it is below this.
constexpr double committed_standard_error = 3e-4;

double eta_of_side(std::size_t side, double eta_hat) { return side == 0 ? eta_hat : 1 / eta_hat; }

// Regenerates, on the table's grid g, every 4th view node, every 5th alpha node and eta nodes 0, 5 and 11 (and
// the last of each axis) of both sides of `committed` with the model family make(alpha,
// eta_s), 32^2 samples each, and counts nodes whose difference exceeds 5 standard
// deviations of the difference (fresh SE + committed SE bound), below, or above by more
// than `raised` as well (a table stored as an upper envelope: its nodes raised by at most
// that, as its header states).
template <class Make>
int count_drifted(const float* committed, const d::dielectric_albedo_grid& g, const Make& make, double raised = 0) {
    int drifted = 0, compared = 0;
    for (std::size_t side = 0; side < 2; ++side)
        for (const std::size_t k : {std::size_t(0), std::size_t(5), g.eta_nodes - 1})
            for (std::size_t j = 0; j < g.alpha_nodes; j = j + 5 < g.alpha_nodes || j == g.alpha_nodes - 1 ? j + 5 : g.alpha_nodes - 1) {
                const double alpha = d::albedo_grid_alpha(j, g.alpha_nodes);
                const double eta_hat = d::dielectric_albedo_eta(g, k);
                const auto model = make(alpha, eta_of_side(side, eta_hat));
                for (std::size_t i = 0; i < g.mu_nodes; i += 4) {
                    const double mu = std::max(
                        d::dielectric_albedo_view_mu(double(i) / double(g.mu_nodes - 1), alpha, eta_hat, side),
                        d::albedo_grid_mu_min);
                    const auto fresh = bsdf_test::single_scattering_albedo(model, std::min(mu, 1.0), 32, 7 + i + 17 * j);
                    const double tolerance = 5 * (fresh.standard_error.x + committed_standard_error);
                    ++compared;
                    // Single scattering never creates energy: R + T <= 1 within the estimate's noise.
                    CHECK(fresh.albedo.x <= 1 + 4 * fresh.standard_error.x + 1e-12);
                    const double difference = double(committed[g.row(side, k, j) + i]) - fresh.albedo.x;
                    if (difference < -tolerance || difference > raised + tolerance) ++drifted;
                }
            }
    // alpha nodes 0, 5, 10, ... and the last: ceil((n - 1) / 5) + 1 of them.
    CHECK(compared == 2 * 3 * int((g.alpha_nodes + 3) / 5 + 1) * int((g.mu_nodes + 3) / 4));
    return drifted;
}

const auto make_ggx = [](double alpha, double eta_s) {
    return shade::rough_dielectric<shade::ggx<double>>(shade::ggx<double>(alpha), eta_s);
};
const auto make_beckmann = [](double alpha, double eta_s) {
    return shade::rough_dielectric<shade::beckmann<double>>(shade::beckmann<double>(alpha), eta_s);
};

} // namespace

TEST_CASE("dielectric albedo tables: the committed GGX table agrees with a coarse regeneration by the model's sampler") {
    CHECK(count_drifted(d::ggx_rough_dielectric_albedo, grid, make_ggx) == 0);
}

TEST_CASE("dielectric albedo tables: the continuations above eta_hat 3 agree with a coarse regeneration") {
    // Point values (no envelope), GGX and Beckmann, on their grids (eta_hat 3 to 1000).
    CHECK(count_drifted(d::ggx_rough_dielectric_albedo_beyond, d::dielectric_albedo_beyond_grid, make_ggx) == 0);
    CHECK(count_drifted(d::beckmann_rough_dielectric_albedo_beyond, d::dielectric_beckmann_albedo_beyond_grid,
                        make_beckmann) == 0);
    CHECK(std::size(d::ggx_rough_dielectric_albedo_beyond) == d::dielectric_albedo_beyond_grid.size());
    CHECK(std::size(d::beckmann_rough_dielectric_albedo_beyond) == d::dielectric_beckmann_albedo_beyond_grid.size());
    // Where the continuations meet the main tables (eta_hat 3), the two estimates of the
    // same nodes agree within their noise.
    for (std::size_t side = 0; side < 2; ++side)
        for (std::size_t j = 0; j < grid.alpha_nodes; ++j)
            for (std::size_t i = 0; i < grid.mu_nodes; ++i)
                CHECK(std::abs(double(d::ggx_rough_dielectric_albedo_beyond[d::dielectric_albedo_beyond_grid.row(side, 0, j) + i]) -
                               double(d::ggx_rough_dielectric_albedo[grid.row(side, grid.eta_nodes - 1, j) + i])) <=
                      5 * 2 * committed_standard_error);
}

TEST_CASE("dielectric albedo tables: the committed Beckmann table agrees with a coarse regeneration by the model's sampler") {
    // An upper envelope: nodes raised by at most 7.5e-3 (its header).
    CHECK(count_drifted(d::beckmann_rough_dielectric_albedo, beckmann_grid, make_beckmann, 7.5e-3) == 0);
}

TEST_CASE("dielectric albedo tables: the regeneration check catches a table that does not belong to its model") {
    // Each table checked against the other distribution's interfaces of the same roughness:
    // the two lose different energy to masking at most rough nodes.
    CHECK(count_drifted(d::ggx_rough_dielectric_albedo, grid, make_beckmann) > 20);
    CHECK(count_drifted(d::beckmann_rough_dielectric_albedo, beckmann_grid, make_ggx) > 20);
}

TEST_CASE("dielectric albedo tables: single scattering never creates energy, and a nearly smooth interface loses none") {
    // R + T <= 1 at every node (the nodes are estimates, so within 4 committed standard
    // errors), and >= 0.
    const auto check_range = [](const float* table, std::size_t size) {
        for (std::size_t x = 0; x < size; ++x) {
            CHECK(table[x] >= 0.0f);
            CHECK(table[x] <= 1.0f + float(4 * committed_standard_error));
        }
    };
    check_range(d::ggx_rough_dielectric_albedo, grid.size());
    check_range(d::beckmann_rough_dielectric_albedo, beckmann_grid.size());
    CHECK(std::size(d::beckmann_rough_dielectric_albedo) == beckmann_grid.size());
    CHECK(std::size(d::ggx_rough_dielectric_albedo) == grid.size());
    // alpha = 1e-4 (row 0): a smooth interface reflects F and transmits 1 - F (energy mode:
    // no 1/eta^2), R + T = 1 exactly; the masking of slopes ~1e-4 loses nothing measurable
    // for views more than ~1e-2 rad from grazing (Smith's Lambda of cot(theta) / alpha > 100
    // is below 1e-4 for GGX).
    int checked = 0;
    for (std::size_t side = 0; side < 2; ++side)
        for (std::size_t k = 0; k < grid.eta_nodes; ++k)
            for (std::size_t i = 0; i < grid.mu_nodes; ++i) {
                const double mu = d::dielectric_albedo_view_mu(double(i) / double(grid.mu_nodes - 1), 1e-4,
                                                               d::dielectric_albedo_eta(k, grid.eta_nodes), side);
                if (mu < 1e-2) continue;
                ++checked;
                CAPTURE(side);
                CAPTURE(k);
                CAPTURE(mu);
                CHECK(double(d::ggx_rough_dielectric_albedo[grid.row(side, k, 0) + i]) ==
                      doctest::Approx(1.0).epsilon(1e-3));
            }
    CHECK(checked > 100);
}

TEST_CASE_TEMPLATE("dielectric albedo tables: E_avg by quadrature is the average of the interpolated E", T, float,
                   double) {
    // Against a midpoint rule on 20000 cells of the same lookup (error ~1e-8 for an
    // integrand with a few kinks), at nodes and between them, on both sides.
    double worst = 0;
    for (const double eta_s : {1.05, 1.3, 2.0, 3.0, 1 / 1.05, 1 / 1.3, 1 / 2.0, 1 / 3.0})
        for (const double alpha : {1e-3, 0.02, 0.1, 0.37, 1.0}) {
            const auto cell = d::dielectric_albedo_locate(grid, T(alpha), T(eta_s));
            double reference = 0;
            constexpr int cells = 20000;
            for (int i = 0; i < cells; ++i) {
                const double mu = (i + 0.5) / cells;
                reference += 2 * mu * double(d::dielectric_albedo_lookup(d::ggx_rough_dielectric_albedo, grid, cell, T(mu)));
            }
            reference /= cells;
            const double quadrature = double(d::dielectric_albedo_average(d::ggx_rough_dielectric_albedo, grid, cell));
            CAPTURE(eta_s);
            CAPTURE(alpha);
            worst = std::max(worst, std::abs(quadrature - reference));
            CHECK(std::abs(quadrature - reference) < 1e-4);
        }
    MESSAGE("E_avg quadrature against a 20000-cell midpoint rule: worst " << worst);
}

TEST_CASE("dielectric albedo tables: the Catmull-Rom spline is exact for cubics and parabolic in the end cells") {
    // p_k = k^3 at k = 0..3: at t = 1/2 between k = 1 and 2, 1.5^3 = 3.375.
    CHECK(d::catmull_rom(0.0, 1.0, 8.0, 27.0, 0.5) == doctest::Approx(3.375).epsilon(1e-15));
    CHECK(d::catmull_rom(0.0, 1.0, 8.0, 27.0, 0.0) == 1.0);
    CHECK(d::catmull_rom(0.0, 1.0, 8.0, 27.0, 1.0) == doctest::Approx(8.0).epsilon(1e-15));
    // Nodes k^2 on a 3-node axis: the end cells extrapolate a ghost node linearly, and the
    // spline through (-1, 0, 1, 4) at t = 1/2 of the first cell is (1 + 9 * 0 + 9 - 4) / 16.
    const auto square = [](std::size_t k) { return double(k * k); };
    CHECK(d::catmull_rom_axis<double>(square, 0, 0, 2, 0.5) == doctest::Approx(6.0 / 16).epsilon(1e-15));
    // The last cell, nodes (0, 1, 4) and ghost 7: (-0 + 9 + 36 - 7) / 16.
    CHECK(d::catmull_rom_axis<double>(square, 1, 0, 2, 0.5) == doctest::Approx(38.0 / 16).epsilon(1e-15));
    // A piece ending at node 2 of a longer axis does not read node 3 (here a wild value).
    const auto kinked = [](std::size_t k) { return k < 3 ? double(k * k) : 1e6; };
    CHECK(d::catmull_rom_axis<double>(kinked, 1, 0, 2, 0.5) == doctest::Approx(38.0 / 16).epsilon(1e-15));
}

TEST_CASE("dielectric albedo tables: the exiting side's view coordinate puts the critical angle at 0.5") {
    // Total internal reflection from the denser side starts at sin(theta_c) = 1 / eta_hat,
    // mu_c = sqrt(1 - 1 / eta_hat^2): for eta_hat = 1.5, mu_c = sqrt(5) / 3.
    const double mu_c = std::sqrt(5.0) / 3;
    for (const double alpha : {1e-4, 0.1, 1.0}) {
        CHECK(d::dielectric_albedo_view(mu_c, alpha, 1.5, 1) == doctest::Approx(0.5).epsilon(1e-12));
        CHECK(d::dielectric_albedo_view(mu_c * (1 - 1e-12), alpha, 1.5, 1) == doctest::Approx(0.5).epsilon(1e-9));
        CHECK(d::dielectric_albedo_view_mu(0.5, alpha, 1.5, 1) == doctest::Approx(mu_c).epsilon(1e-12));
        // The entering side uses the conductor tables' coordinate unchanged.
        CHECK(d::dielectric_albedo_view(0.3, alpha, 1.5, 0) == d::albedo_grid_c(0.3, alpha));
        for (const double t : {0.0, 0.1, 0.5, 0.73, 1.0})
            for (const std::size_t side : {std::size_t(0), std::size_t(1)})
                CHECK(std::abs(d::dielectric_albedo_view(d::dielectric_albedo_view_mu(t, alpha, 1.5, side), alpha, 1.5, side) -
                               t) < 1e-9);
    }
    // eta nodes: 1.05 and 3 at the ends, 1 + exp(x) uniform in x between.
    CHECK(d::dielectric_albedo_eta(0, grid.eta_nodes) == doctest::Approx(1.05).epsilon(1e-14));
    CHECK(d::dielectric_albedo_eta(grid.eta_nodes - 1, grid.eta_nodes) == doctest::Approx(3.0).epsilon(1e-14));
}

TEST_CASE_TEMPLATE("dielectric albedo tables: lookups return the node values at the nodes and interpolate between them", T,
                   float, double) {
    const float* table = d::ggx_rough_dielectric_albedo;
    for (const std::size_t side : {std::size_t(0), std::size_t(1)})
        for (const std::size_t k : {std::size_t(2), std::size_t(7)})
            for (const std::size_t j : {std::size_t(3), std::size_t(11)})
                for (const std::size_t i : {std::size_t(1), std::size_t(8), std::size_t(14)}) {
                    CAPTURE(side);
                    CAPTURE(k);
                    CAPTURE(j);
                    CAPTURE(i);
                    const double alpha = d::albedo_grid_alpha(j, grid.alpha_nodes);
                    const double eta_hat = d::dielectric_albedo_eta(k, grid.eta_nodes);
                    const double mu = d::dielectric_albedo_view_mu(double(i) / double(grid.mu_nodes - 1), alpha, eta_hat, side);
                    const auto cell = d::dielectric_albedo_locate(grid, T(alpha), T(eta_of_side(side, eta_hat)));
                    CHECK(cell.side == side);
                    CHECK(double(d::dielectric_albedo_lookup(table, grid, cell, T(mu))) ==
                          doctest::Approx(double(table[grid.row(side, k, j) + i])).epsilon(1e-4));
                    // Halfway along the view coordinate at a node of alpha and eta: the
                    // Catmull-Rom spline at t = 1/2, (-p0 + 9 p1 + 9 p2 - p3) / 16.
                    const double mu_mid =
                        d::dielectric_albedo_view_mu((double(i) + 0.5) / double(grid.mu_nodes - 1), alpha, eta_hat, side);
                    const float* row = table + grid.row(side, k, j);
                    const double mean = (-double(row[i - 1]) + 9.0 * row[i] + 9.0 * row[i + 1] - row[i + 2]) / 16;
                    CHECK(double(d::dielectric_albedo_lookup(table, grid, cell, T(mu_mid))) == doctest::Approx(mean).epsilon(1e-4));
                }
    // Outside the grid: eta_hat > 3 reads the eta_hat = 3 block, alpha > 1 the alpha = 1 row,
    // and eta_s < 1 the exiting side.
    const auto far = d::dielectric_albedo_locate(grid, T(0.3), T(10));
    const auto end = d::dielectric_albedo_locate(grid, T(0.3), T(3));
    CHECK(d::dielectric_albedo_lookup(table, grid, far, T(0.5)) == d::dielectric_albedo_lookup(table, grid, end, T(0.5)));
    const auto rough = d::dielectric_albedo_locate(grid, T(4), T(1.5));
    const auto one = d::dielectric_albedo_locate(grid, T(1), T(1.5));
    CHECK(d::dielectric_albedo_lookup(table, grid, rough, T(0.5)) == d::dielectric_albedo_lookup(table, grid, one, T(0.5)));
    CHECK(d::dielectric_albedo_locate(grid, T(0.3), T(1) / T(1.5)).side == 1);
}
