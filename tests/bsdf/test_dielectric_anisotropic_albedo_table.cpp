// The committed anisotropic correction of the rough-dielectric albedo tables
// (shade/bsdf/detail/dielectric_anisotropic_albedo_data.hpp, written by
// examples/dielectric_albedo_tables.cpp --anisotropic) against a coarse regeneration with
// shade::rough_dielectric's own sampler, so it cannot drift from the model; its row
// averages against its rows; and the grid and interpolation of
// shade/bsdf/dielectric_anisotropic_albedo_table.hpp.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include <doctest/doctest.h>

#include <shade/brdf/microfacet/beckmann.hpp>
#include <shade/brdf/microfacet/ggx.hpp>
#include <shade/bsdf/detail/dielectric_albedo_data.hpp>
#include <shade/bsdf/detail/dielectric_anisotropic_albedo_data.hpp>
#include <shade/bsdf/dielectric_albedo_table.hpp>
#include <shade/bsdf/dielectric_anisotropic_albedo_table.hpp>
#include <shade/bsdf/rough_dielectric.hpp>

#include "bsdf/dielectric_albedo.hpp"

namespace {

namespace d = shade::detail;
constexpr std::size_t nx = d::dielectric_anisotropic_mu_nodes, nu = d::dielectric_anisotropic_azimuth_nodes;
constexpr std::size_t ny = d::dielectric_anisotropic_roughness_nodes, nz = d::dielectric_anisotropic_ratio_nodes;
constexpr std::size_t ne = d::dielectric_anisotropic_eta_nodes;
const float* const delta = d::ggx_dielectric_anisotropic_delta;

// The generated header states the largest node standard error; it is below this.
constexpr double committed_standard_error = 7e-4;
// The generated header states the largest raise of a node by the upper envelope; it is below this.
constexpr double committed_raise = 0.14;
// The generator's --lift per side (entering, exiting): every estimated node (not the isotropic
// rows up to alpha 1) is stored this much above its estimate, before the envelope's raises.
constexpr double committed_lift[2] = {0.0025, 0.0045};

double eta_of_side(std::size_t side, double eta_hat) { return side == 0 ? eta_hat : 1 / eta_hat; }

struct node {
    double alpha_x, alpha_y, eta_s, mu;
    shade::vec3<double> v;
};

// The interface and view of node (side, m, k, j, i_u, i_x) as the generator builds them:
// alpha_max = sqrt 2 y^2 along b, alpha_min = z^2 alpha_max (at least 1e-4) along t, eta_hat
// of the isotropic tables' e axis, mu = x^2 and the azimuth phi = pi/2 u (1 + u) / 2 from t.
node node_at(std::size_t side, std::size_t m, std::size_t k, std::size_t j, std::size_t i_u, std::size_t i_x) {
    const double y = double(j) / double(ny - 1), alpha_max = d::dielectric_anisotropic_alpha_top * y * y;
    const double z = double(k) / double(nz - 1), alpha_min = std::max(z * z * alpha_max, 1e-4);
    const double x = double(i_x) / double(nx - 1), mu = std::min(std::max(x * x, d::albedo_grid_mu_min), 1.0);
    const double u = double(i_u) / double(nu - 1), phi = shade::pi<double> / 2 * u * (1 + u) / 2;
    const double s = std::sqrt((1 - mu) * (1 + mu));
    return {alpha_min, alpha_max, eta_of_side(side, d::dielectric_albedo_eta(m, ne)), mu,
            shade::vec3<double>(s * std::cos(phi), s * std::sin(phi), mu)};
}

// E_iso of the committed isotropic table at alpha and eta_s.
double iso_albedo(double alpha, double eta_s, double mu) {
    const d::dielectric_albedo_grid g{};
    return d::dielectric_albedo_lookup(d::ggx_rough_dielectric_albedo, g, d::dielectric_albedo_locate(g, alpha, eta_s), mu);
}

// E_iso at the base roughness: what Delta is measured from.
double base_albedo(const node& n) {
    return iso_albedo(d::dielectric_anisotropic_base_alpha(n.alpha_x, n.alpha_y), n.eta_s, n.mu);
}

// Regenerates nodes spread over all six axes with the interfaces make(alpha_x, alpha_y,
// eta_s), 40^2 samples each, and counts those whose committed Delta is below the fresh one
// plus the lift, or above it by more than the lift and the envelope's largest raise, by more
// than 5 standard deviations of the difference (fresh SE + committed SE bound).
template <class Make>
int count_drifted(const Make& make) {
    int drifted = 0, checked = 0;
    for (std::size_t side = 0; side < 2; ++side)
        for (std::size_t m = 0; m < ne; m += 3)
            for (std::size_t k = 0; k + 1 < nz; k += 2)
                for (std::size_t j = 3; j < ny; j += 5)
                    for (std::size_t i_u = 1; i_u < nu; i_u += 4)
                        for (std::size_t i_x = 4; i_x < nx; i_x += 5) {
                            const node n = node_at(side, m, k, j, i_u, i_x);
                            const auto model = make(n.alpha_x, n.alpha_y, n.eta_s);
                            const auto fresh = bsdf_test::single_scattering_albedo(model, n.v, 40, std::uint64_t(3 + checked));
                            const double fresh_delta = std::min(fresh.albedo.x, 1.0) - base_albedo(n);
                            const double committed = double(delta[d::dielectric_anisotropic_row_index(side, m, k, j, i_u) * nx + i_x]);
                            const double tolerance = 5 * (fresh.standard_error.x + committed_standard_error);
                            const double lift = committed_lift[side];
                            if (committed < fresh_delta + lift - tolerance || committed > fresh_delta + lift + committed_raise + tolerance)
                                ++drifted;
                            ++checked;
                        }
    CHECK(checked == 2 * 3 * 3 * 2 * 3 * 3);
    return drifted;
}

} // namespace

TEST_CASE("dielectric anisotropic albedo table: the committed GGX correction agrees with a coarse regeneration") {
    CHECK(count_drifted([](double a_x, double a_y, double eta_s) {
              return shade::rough_dielectric<shade::ggx<double>>(shade::ggx<double>(a_x, a_y), eta_s);
          }) == 0);
}

TEST_CASE("dielectric anisotropic albedo table: the regeneration check catches a correction of the wrong interface") {
    // The same nodes regenerated with the roughnesses exchanged (the rougher axis along t):
    // the azimuth of every view then counts from the rougher axis, and many Delta change.
    CHECK(count_drifted([](double a_x, double a_y, double eta_s) {
              return shade::rough_dielectric<shade::ggx<double>>(shade::ggx<double>(a_y, a_x), eta_s);
          }) > 30);
}

TEST_CASE("dielectric anisotropic albedo table: isotropic slices up to alpha 1 hold E_iso(alpha) - E_iso(base) or a raise of "
          "it; row averages are the rows' averages") {
    for (std::size_t side = 0; side < 2; ++side)
        for (std::size_t m = 0; m < ne; ++m)
            for (std::size_t k = 0; k < nz; ++k)
                for (std::size_t j = 1; j < ny; ++j)
                    for (std::size_t i_u = 0; i_u < nu; ++i_u) {
                        const std::size_t row = d::dielectric_anisotropic_row_index(side, m, k, j, i_u);
                        // z = 1 is the isotropic table itself while alpha_max <= 1 (y <= 2^-1/4):
                        // Delta = E_iso(alpha) - E_iso(base alpha) there (0 up to the base's knee,
                        // where the base alpha is alpha), raised only by the envelope; stored with 4
                        // significant digits (relative rounding 5e-4).
                        const double y = double(j) / double(ny - 1);
                        if (k + 1 == nz && d::dielectric_anisotropic_alpha_top * y * y <= 1)
                            for (std::size_t i = 0; i < nx; ++i) {
                                const node n = node_at(side, m, k, j, i_u, i);
                                const double expected = iso_albedo(n.alpha_y, n.eta_s, n.mu) - base_albedo(n);
                                if (n.alpha_y <= d::dielectric_anisotropic_base_knee) CHECK(expected == 0.0);
                                const double stored = double(delta[row * nx + i]), rounding = 5e-4 * std::abs(expected);
                                CHECK(stored >= expected - rounding);
                                CHECK(stored <= expected + rounding + committed_raise);
                            }
                        // The stored average is the float of the exact average of the row.
                        CHECK(double(d::ggx_dielectric_anisotropic_delta_average[row]) ==
                              doctest::Approx(d::dielectric_anisotropic_row_average(delta + row * nx)).epsilon(1e-6));
                    }
    CHECK(d::dielectric_anisotropic_row_index(1, ne - 1, nz - 1, ny - 1, nu - 1) + 1 == d::dielectric_anisotropic_rows);
}

TEST_CASE("dielectric anisotropic albedo table: the spline taps reproduce quadratics inside and use the secant at the ends") {
    const auto read = [](const auto& p, std::size_t i, double t, std::size_t n) {
        const shade::detail::spline_taps<double> w(i, t, n);
        double sum = 0, weights = 0;
        for (int a = 0; a < 4; ++a) {
            sum += w.weight[a] * p(w.node[a]);
            weights += w.weight[a];
        }
        CHECK(weights == doctest::Approx(1.0).epsilon(1e-15));
        return sum;
    };
    // The Catmull-Rom tangent (p_i+1 - p_i-1) / 2 is exact for a quadratic, so inside cells
    // reproduce p_k = k^2 at any t: cell 2 of 6 nodes at t = 0.25 gives 2.25^2.
    const auto square = [](std::size_t k) { return double(k * k); };
    CHECK(read(square, 2, 0.25, 6) == doctest::Approx(2.25 * 2.25).epsilon(1e-14));
    CHECK(read(square, 1, 0.7, 6) == doctest::Approx(1.7 * 1.7).epsilon(1e-14));
    // End cells: the ghost 2 p_0 - p_1 makes the tangent at the end node the secant p_1 - p_0.
    // The Hermite cubic at t = 1/2 is (p_0 + p_1) / 2 + (m_0 - m_1) / 8: in cell 0, m_0 = 1,
    // m_1 = (4 - 0) / 2 = 2, so 0.5 - 1/8 = 0.375; in cell 4 of 6 nodes, m_0 = (25 - 9) / 2 = 8,
    // m_1 = 25 - 16 = 9, so 20.5 - 1/8 = 20.375.
    CHECK(read(square, 0, 0.5, 6) == doctest::Approx(0.375).epsilon(1e-14));
    CHECK(read(square, 4, 0.5, 6) == doctest::Approx(20.375).epsilon(1e-14));
    CHECK(read(square, 0, 0.0, 6) == 0.0);
    CHECK(read(square, 4, 1.0, 6) == doctest::Approx(25.0).epsilon(1e-14));
}

TEST_CASE("dielectric anisotropic albedo table: the azimuth coordinate runs from 0 to 1 and phi inverts it") {
    CHECK(d::dielectric_anisotropic_u(0.0) == 0.0);
    CHECK(d::dielectric_anisotropic_u(shade::pi<double> / 2) == doctest::Approx(1.0).epsilon(1e-15));
    // g(u) = u (1 + u) / 2 = 2 phi / pi: u = 1/2 is phi = pi/2 * 3/8 (33.75 degrees).
    CHECK(d::dielectric_anisotropic_u(shade::pi<double> * 3 / 16) == doctest::Approx(0.5).epsilon(1e-15));
    CHECK(d::dielectric_anisotropic_phi(0.5) == doctest::Approx(shade::pi<double> * 3 / 16).epsilon(1e-15));
    for (const double u : {0.0, 0.1, 0.5, 0.93, 1.0})
        CHECK(d::dielectric_anisotropic_u(d::dielectric_anisotropic_phi(u)) == doctest::Approx(u).epsilon(1e-14));
}

TEST_CASE_TEMPLATE("dielectric anisotropic albedo table: lookups at nodes return the node values", T, float, double) {
    for (const std::size_t side : {std::size_t(0), std::size_t(1)})
        for (const std::size_t m : {std::size_t(1), std::size_t(3)})
            for (const std::size_t k : {std::size_t(1), std::size_t(3)})
                for (const std::size_t j : {std::size_t(2), std::size_t(7)})
                    for (const std::size_t i_u : {std::size_t(0), std::size_t(3), std::size_t(nu - 1)})
                        for (const std::size_t i_x : {std::size_t(3), std::size_t(10)}) {
                            const node n = node_at(side, m, k, j, i_u, i_x);
                            const auto cell = d::dielectric_anisotropic_locate(T(n.alpha_x), T(n.alpha_y), T(n.eta_s));
                            const double committed =
                                double(delta[d::dielectric_anisotropic_row_index(side, m, k, j, i_u) * nx + i_x]);
                            CAPTURE(side);
                            CAPTURE(m);
                            CAPTURE(k);
                            CAPTURE(j);
                            CAPTURE(i_u);
                            CAPTURE(i_x);
                            CHECK(double(d::dielectric_anisotropic_delta(delta, cell, side, T(n.v.x), T(n.v.y), T(n.mu))) ==
                                  doctest::Approx(committed).epsilon(1e-5));
                            // The axes exchanged read the same node.
                            const auto swapped = d::dielectric_anisotropic_locate(T(n.alpha_y), T(n.alpha_x), T(n.eta_s));
                            CHECK(double(d::dielectric_anisotropic_delta(delta, swapped, side, T(n.v.y), T(n.v.x), T(n.mu))) ==
                                  doctest::Approx(committed).epsilon(1e-5));
                        }
}

TEST_CASE_TEMPLATE("dielectric anisotropic albedo table: Delta_avg is the cosine average of the Delta the lookup reads", T,
                   float, double) {
    // (1 / pi) integral Delta (n·w) dw = (2 / pi) integral_0^(pi/2) dphi 4 integral_0^1 Delta x^3 dx
    // (mu = x^2; Delta is even in each axis of the azimuth), by the midpoint rule on 300 x 300
    // cells (its error is below 1e-5 for this piecewise-smooth integrand).
    double worst = 0;
    for (const auto& lobe : {std::pair{0.05, 0.5}, std::pair{0.6, 0.3}, std::pair{0.3, 0.9}, std::pair{1e-4, 1.2}})
        for (const double eta : {1.1, 1.5, 2.7}) {
            const auto cell = d::dielectric_anisotropic_locate(T(lobe.first), T(lobe.second), T(eta));
            for (const std::size_t side : {std::size_t(0), std::size_t(1)}) {
                double sum = 0;
                constexpr int cells = 300;
                for (int i = 0; i < cells; ++i) {
                    const double phi = (i + 0.5) / cells * shade::pi<double> / 2;
                    for (int k = 0; k < cells; ++k) {
                        const double x = (k + 0.5) / cells, mu = x * x, s = std::sqrt((1 - mu) * (1 + mu));
                        sum += double(d::dielectric_anisotropic_delta(delta, cell, side, T(s * std::cos(phi)), T(s * std::sin(phi)),
                                                                      T(mu))) *
                               4 * x * x * x / cells / cells;
                    }
                }
                const double average =
                    double(d::dielectric_anisotropic_delta_average(d::ggx_dielectric_anisotropic_delta_average, cell, side));
                CAPTURE(lobe.first);
                CAPTURE(eta);
                CAPTURE(side);
                worst = std::max(worst, std::abs(average - sum));
                CHECK(average == doctest::Approx(sum).epsilon(2e-5));
            }
        }
    MESSAGE("Delta_avg against a 300 x 300 midpoint rule: worst difference " << worst);
}
