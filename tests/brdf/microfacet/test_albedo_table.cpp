// The committed albedo tables (shade/brdf/microfacet/detail/albedo_data.hpp, written by
// examples/albedo_tables.cpp) against a coarse regeneration with the models' own samplers,
// so they cannot drift from the models; their E_avg against the rows they average; and
// the grid and interpolation of shade/brdf/microfacet/albedo_table.hpp.

#include <cmath>
#include <cstddef>
#include <string>

#include <doctest/doctest.h>

#include <shade/brdf/cook_torrance.hpp>
#include <shade/brdf/microfacet/albedo_table.hpp>
#include <shade/brdf/microfacet/detail/albedo_data.hpp>
#include <shade/check/energy.hpp>

namespace {

namespace d = shade::detail;
constexpr std::size_t n = d::albedo_grid_nodes;

// The generated header states each table's largest node standard error; all are below this.
constexpr double committed_standard_error = 3e-4;

// E at node (i, j) estimated afresh as the generator does (the lobe's own sampler), with
// strata^2 samples.
template <class Model>
shade::check::albedo_sample<double> node_albedo(const Model& model, std::size_t i, std::size_t j, std::size_t strata) {
    const double alpha = d::albedo_grid_alpha(j, n);
    const double mu = std::min(std::max(d::albedo_grid_mu(double(i) / double(n - 1), alpha), d::albedo_grid_mu_min), 1.0);
    const shade::vec3<double> v(std::sqrt((1 - mu) * (1 + mu)), 0, mu);
    shade::surface_point<double> at;
    at.shading = shade::frame<double>::from_normal_tangent({0, 0, 1}, {1, 0, 0});
    return shade::check::sampled_albedo(model, v, at, strata, 1 + j * n + i);
}

struct table_ref {
    std::string name;
    const float* e;
    const float* average;
};

// Regenerates every 18th node of each axis (and the last) of `committed` with the model
// family make(alpha) and counts nodes whose difference exceeds 5 standard deviations of
// the difference (fresh SE + committed SE bound).
template <class Make>
int count_drifted(const float* committed, const Make& make) {
    int drifted = 0;
    for (std::size_t j = 0; j < n; j = j + 18 < n || j == n - 1 ? j + 18 : n - 1) {
        const auto model = make(d::albedo_grid_alpha(j, n));
        for (std::size_t i = 0; i < n; i = i + 18 < n || i == n - 1 ? i + 18 : n - 1) {
            const auto fresh = node_albedo(model, i, j, 40);
            const double tolerance = 5 * (fresh.standard_error.x + committed_standard_error);
            if (std::abs(double(committed[j * n + i]) - fresh.albedo.x) > tolerance) ++drifted;
        }
    }
    return drifted;
}

using ggx_lobe = shade::cook_torrance<shade::ggx<double>, shade::schlick<double>, shade::smith_height_correlated<double>>;
using beckmann_lobe =
    shade::cook_torrance<shade::beckmann<double>, shade::schlick<double>, shade::smith_height_correlated<double>>;
using dielectric_lobe =
    shade::cook_torrance<shade::ggx<double>, shade::dielectric_fresnel<double>, shade::smith_height_correlated<double>>;

const auto make_ggx = [](double a) { return ggx_lobe(shade::ggx<double>(a), shade::schlick<double>(shade::rgb<double>(1))); };
const auto make_beckmann = [](double a) {
    return beckmann_lobe(shade::beckmann<double>(a), shade::schlick<double>(shade::rgb<double>(1)));
};
const auto make_dielectric = [](double a) {
    return dielectric_lobe(shade::ggx<double>(a), shade::dielectric_fresnel<double>(1.5));
};

} // namespace

TEST_CASE("albedo tables: the committed tables agree with a coarse regeneration by the models' own samplers") {
    CHECK(count_drifted(d::ggx_albedo, make_ggx) == 0);
    CHECK(count_drifted(d::beckmann_albedo, make_beckmann) == 0);
    CHECK(count_drifted(d::ggx_dielectric_albedo, make_dielectric) == 0);
}

TEST_CASE("albedo tables: the regeneration check catches a table that does not belong to its model") {
    // The Beckmann table checked against GGX lobes, and the F = 1 GGX table against the
    // dielectric lobes: most nodes differ by far more than the tolerance.
    CHECK(count_drifted(d::beckmann_albedo, make_ggx) > 20);
    CHECK(count_drifted(d::ggx_albedo, make_dielectric) > 40);
}

TEST_CASE("albedo tables: each E_avg is the cosine-weighted average of its interpolated row") {
    for (const table_ref& t : {table_ref{"ggx", d::ggx_albedo, d::ggx_albedo_average},
                               table_ref{"beckmann", d::beckmann_albedo, d::beckmann_albedo_average},
                               table_ref{"dielectric", d::ggx_dielectric_albedo, d::ggx_dielectric_albedo_average}}) {
        CAPTURE(t.name);
        for (std::size_t j = 0; j < n; ++j) {
            CAPTURE(j);
            // Stored as float: within half a float ulp of a number <= 1 (6e-8), plus margin.
            CHECK(std::abs(double(t.average[j]) - d::albedo_row_average(t.e + j * n, n, d::albedo_grid_alpha(j, n))) < 1e-7);
            for (std::size_t i = 0; i < n; ++i) {
                CHECK(t.e[j * n + i] >= 0.0f);
                CHECK(t.e[j * n + i] <= 1.0f);
            }
        }
    }
}

TEST_CASE("albedo tables: the quadrature of a row average is exact for a constant row and for E = mu") {
    // E = 1: 2 integral mu dmu = 1. E(mu) = c(mu) is not polynomial in mu, so a row of
    // node values c_i reproduces it only to interpolation error; a constant is exact.
    std::vector<float> ones(n, 1.0f);
    for (const double alpha : {1e-4, 0.01, 0.3, 1.0}) CHECK(d::albedo_row_average(ones.data(), n, alpha) == doctest::Approx(1.0).epsilon(1e-12));
    // At alpha = 1, c = (mu + sqrt(mu)) / 2; nodes E_i = mu_i interpolated linearly in c
    // give ~2/3 = 2 integral mu^2 dmu, to the interpolation error (cells ~1/127 wide).
    std::vector<float> mu_row(n);
    for (std::size_t i = 0; i < n; ++i) mu_row[i] = float(d::albedo_grid_mu(double(i) / double(n - 1), 1.0));
    CHECK(d::albedo_row_average(mu_row.data(), n, 1.0) == doctest::Approx(2.0 / 3.0).epsilon(1e-4));
}

TEST_CASE_TEMPLATE("albedo tables: lookups return the node values at the nodes and interpolate between them", T, float,
                   double) {
    for (const std::size_t j : {std::size_t(3), std::size_t(40), std::size_t(126)}) {
        for (const std::size_t i : {std::size_t(1), std::size_t(64), std::size_t(126)}) {
            const double alpha = d::albedo_grid_alpha(j, n);
            const double mu = d::albedo_grid_mu(double(i) / double(n - 1), alpha);
            CHECK(double(d::albedo_lookup(d::ggx_albedo, n, T(mu), T(alpha))) ==
                  doctest::Approx(double(d::ggx_albedo[j * n + i])).epsilon(1e-4));
            // Halfway in c and in sqrt(alpha): the mean of the four corners.
            const double y = (double(j) + 0.5) / double(n - 1);
            const double mu_mid = d::albedo_grid_mu((double(i) + 0.5) / double(n - 1), y * y);
            const double corners = 0.25 * (double(d::ggx_albedo[j * n + i]) + d::ggx_albedo[j * n + i + 1] +
                                           d::ggx_albedo[(j + 1) * n + i] + d::ggx_albedo[(j + 1) * n + i + 1]);
            CHECK(double(d::albedo_lookup(d::ggx_albedo, n, T(mu_mid), T(y * y))) == doctest::Approx(corners).epsilon(1e-4));
        }
    }
    // Outside the grid: alpha > 1 reads the alpha = 1 row, mu is clamped.
    CHECK(d::albedo_lookup(d::ggx_albedo, n, T(0.5), T(3)) == d::albedo_lookup(d::ggx_albedo, n, T(0.5), T(1)));
    CHECK(d::albedo_lookup(d::ggx_albedo, n, T(2), T(0.3)) == d::albedo_lookup(d::ggx_albedo, n, T(1), T(0.3)));
}
