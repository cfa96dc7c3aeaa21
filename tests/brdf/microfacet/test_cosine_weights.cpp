// The GGX lobe's weights of the c nodes (shade/brdf/microfacet/cosine_weights.hpp) and its
// committed table (detail/cosine_weight_data.hpp, written by examples/albedo_tables
// --cosine-weights): the table against a coarse regeneration with the same quadrature (so it
// cannot drift from the definition), a wrong table caught; the weights' sum against the
// independent albedo table of the lobe with F = 1 (Monte Carlo with the lobe's own sampler);
// the smooth limit; and fresnel_albedo_row against the quadrature between the nodes.

#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include <doctest/doctest.h>

#include <shade/brdf/fresnel.hpp>
#include <shade/brdf/microfacet/albedo_table.hpp>
#include <shade/brdf/microfacet/cosine_weights.hpp>
#include <shade/brdf/microfacet/detail/albedo_data.hpp>

namespace {

namespace d = shade::detail;
constexpr std::size_t n = d::cosine_weight_nodes;
constexpr std::size_t m = d::cosine_weight_alpha_nodes;

// The committed weights of view node i, alpha row j.
const float* committed(std::size_t i, std::size_t j) { return d::cosine_weight_table + (j * n + i) * n; }

// The nodes (i, j) whose regenerated weights differ from `table`'s by more than tol in some
// k, regenerating every 9th view node and alpha rows 1, 8, 20, 31 with 96^2 cells (the
// committed table used 384^2; the midpoint rule's two resolutions differ by the cells the
// horizon and the node boundaries cut: 1.4e-3 at most per weight at these nodes, at the
// narrowest row and lowest view).
std::size_t regenerated_mismatches(const float* table, double tol) {
    std::size_t bad = 0;
    std::vector<double> w(n);
    for (const std::size_t j : {std::size_t(1), std::size_t(8), std::size_t(20), m - 1}) {
        for (std::size_t i = 4; i < n; i += 9) {
            d::ggx_cosine_weights(d::cosine_weight_node(i), d::cosine_weight_alpha(j), 96, w.data());
            for (std::size_t k = 0; k < n; ++k) {
                if (std::abs(w[k] - double(table[(j * n + i) * n + k])) > tol) {
                    ++bad;
                    break;
                }
            }
        }
    }
    return bad;
}

} // namespace

TEST_CASE("cosine weights: the committed table is the quadrature, and a wrong one is caught") {
    CHECK(regenerated_mismatches(d::cosine_weight_table, 2.5e-3) == 0);
    // A table with one view's weights shifted by one node (the measure moved by a cell).
    std::vector<float> wrong(d::cosine_weight_table, d::cosine_weight_table + m * n * n);
    const std::size_t j = 8, i = 31;
    for (std::size_t k = n - 1; k > 0; --k) wrong[(j * n + i) * n + k] = wrong[(j * n + i) * n + k - 1];
    wrong[(j * n + i) * n] = 0;
    CHECK(regenerated_mismatches(wrong.data(), 2.5e-3) == 1);
}

TEST_CASE("cosine weights: their sum is the albedo of the lobe with F = 1, from the independent table") {
    // sum_k w_k = E_1(mu, alpha), the albedo of the single-scattering GGX lobe with F = 1
    // (height-correlated), which detail/albedo_data.hpp estimates by Monte Carlo with the
    // lobe's own sampler (stated accuracy 1.2e-3 between its nodes). Views mu >= 0.1.
    double worst = 0;
    for (std::size_t j = 1; j < m; j += 3) {
        for (std::size_t i = 0; i < n; ++i) {
            const double mu = d::cosine_weight_node(i);
            if (mu < 0.1) continue;
            double sum = 0;
            for (std::size_t k = 0; k < n; ++k) sum += double(committed(i, j)[k]);
            const double alpha = d::cosine_weight_alpha(j);
            const double e1 = double(d::albedo_lookup(d::ggx_albedo, d::albedo_grid_nodes, float(mu), float(alpha)));
            INFO("mu ", mu, " alpha ", alpha, ": sum ", sum, ", E_1 ", e1);
            CHECK(std::abs(sum - e1) <= 2e-3);
            worst = std::max(worst, std::abs(sum - e1));
        }
    }
    MESSAGE("cosine weights: |sum - E_1| <= ", worst);
}

TEST_CASE("cosine weights: the smooth lobe's row is F itself at the nodes and linear between them") {
    // alpha = 0: the lobe is a mirror, its albedo with F is F(mu); the table's first row
    // holds the hat weights of c = mu (view node i puts 1 on node i, up to the rounding of
    // the node's x = c^(2/3) (n - 1); node 0 is clamped to mu = 1e-4).
    for (std::size_t i = 1; i < n; ++i) {
        for (std::size_t k = 0; k < n; ++k) CHECK(std::abs(double(committed(i, 0)[k]) - (k == i ? 1.0 : 0.0)) <= 1e-6);
    }
    const auto F = [](float c) { return shade::rgb<float>(shade::F_dielectric(c, 1.5f)); };
    const d::fresnel_albedo_row<float> row(0.0f, F);
    for (std::size_t i = 1; i < n; ++i) {
        const float mu = float(d::cosine_weight_node(i));
        CHECK(row.at(mu).x == doctest::Approx(double(F(mu).x)).epsilon(1e-5));
    }
}

TEST_CASE("cosine weights: the cell holding a cosine") {
    // Nodes c_k = (k / (n - 1))^(3/2): half-way between two nodes in x = c^(2/3) lies in the
    // cell of the lower one; 1 lies in the last cell; below 0 and NaN read as 0.
    for (std::size_t k = 0; k + 1 < n; ++k) {
        const double x = (double(k) + 0.5) / double(n - 1);
        CHECK(d::cosine_weight_cell(x * std::sqrt(x)) == k);
    }
    CHECK(d::cosine_weight_cell(1.0) == n - 2);
    CHECK(d::cosine_weight_cell(2.0) == n - 2);
    CHECK(d::cosine_weight_cell(-0.5) == 0);
    CHECK(d::cosine_weight_cell(std::numeric_limits<double>::quiet_NaN()) == 0);
}

TEST_CASE_TEMPLATE("fresnel_albedo_row: the albedo with a dielectric Fresnel between the nodes", T, float, double) {
    // The row at views and roughnesses between the nodes against the quadrature at that
    // very view and roughness (F at each cell's own cosine): within the table's stated
    // accuracy for the dielectric (the generator's [-1.5e-3, +6e-4], bilinear interpolation
    // plus F's linear interpolation between the c nodes), with room for float rounding.
    double worst = 0;
    for (const double alpha : {0.003, 0.05, 0.2, 0.55, 0.9}) {
        const auto F = [](T c) { return shade::rgb<T>(shade::F_dielectric(c, T(1.5))); };
        const d::fresnel_albedo_row<T> row(T(alpha), F);
        for (const double mu : {0.1, 0.23, 0.5, 0.77, 1.0}) {
            double fresh = 0;
            d::visit_ggx_cosine_measure(mu, alpha, 128, [&](double c, double w) { fresh += w * shade::F_dielectric(c, 1.5); });
            const double got = double(row.at(T(mu)).x);
            INFO("alpha ", alpha, " mu ", mu, ": row ", got, ", quadrature ", fresh);
            CHECK(got - fresh >= -2e-3);
            CHECK(got - fresh <= 1e-3);
            worst = std::max(worst, std::abs(got - fresh));
        }
    }
    MESSAGE("fresnel_albedo_row vs quadrature: <= ", worst);
}
