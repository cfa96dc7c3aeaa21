// The committed anisotropic correction tables (shade/brdf/microfacet/detail/
// anisotropic_albedo_data.hpp, written by examples/albedo_tables.cpp --anisotropic) against
// a coarse regeneration with the models' own samplers, so they cannot drift from the models;
// their row averages against the rows; and the interpolation of
// shade/brdf/microfacet/anisotropic_albedo_table.hpp.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include <doctest/doctest.h>

#include <shade/brdf/cook_torrance.hpp>
#include <shade/brdf/microfacet/anisotropic_albedo_table.hpp>
#include <shade/brdf/microfacet/detail/albedo_data.hpp>
#include <shade/brdf/microfacet/detail/anisotropic_albedo_data.hpp>
#include <shade/check/energy.hpp>

namespace {

namespace d = shade::detail;
constexpr std::size_t nx = d::anisotropic_albedo_mu_nodes, nu = d::anisotropic_albedo_azimuth_nodes;
constexpr std::size_t ny = d::anisotropic_albedo_roughness_nodes, nr = d::anisotropic_albedo_ratio_nodes;

// The generated header states each table's largest node standard error; both are below this.
constexpr double committed_standard_error = 6e-4;

struct node {
    double alpha_x, alpha_y; // the lobe of slice (k, j)
    shade::vec3<double> v;   // the view of row i_u, column i_x
    double mu;
};

// The lobe and view of node (k, j, i_u, i_x), as the generator builds them: geometric-mean
// roughness y_j^2, anisotropy q = ratio_max^(k / (nr - 1)), mu = x^2, and the azimuth whose
// u = ln(1 + (q^2 - 1) sin^2 phi) / ln(q^2) is the row's.
node node_at(std::size_t k, std::size_t j, std::size_t i_u, std::size_t i_x) {
    const double y = double(j) / double(ny - 1), alpha = y * y;
    const double q = std::pow(d::anisotropic_albedo_ratio_max, double(k) / double(nr - 1));
    const double x = double(i_x) / double(nx - 1);
    const double mu = std::min(std::max(x * x, d::albedo_grid_mu_min), 1.0);
    const double u = double(i_u) / double(nu - 1);
    const double sin2 = std::min(std::expm1(u * 2 * std::log(q)) / ((q - 1) * (q + 1)), 1.0);
    const double sin_theta = std::sqrt((1 - mu) * (1 + mu));
    return {alpha / std::sqrt(q), alpha * std::sqrt(q),
            shade::vec3<double>(sin_theta * std::sqrt(1 - sin2), sin_theta * std::sqrt(sin2), mu), mu};
}

template <class Distribution>
using lobe = shade::cook_torrance<Distribution, shade::schlick<double>, shade::smith_height_correlated<double>>;

// Regenerates nodes of `delta` spread over all four axes with make(alpha_x, alpha_y) and
// 48^2 samples each, and counts those whose difference exceeds 5 standard deviations of
// the difference (fresh SE + committed SE bound).
template <class Make>
int count_drifted(const float* delta, const float* iso, const Make& make) {
    int drifted = 0, checked = 0;
    shade::surface_point<double> at;
    at.shading = shade::frame<double>::from_normal_tangent({0, 0, 1}, {1, 0, 0});
    for (std::size_t k = 1; k < nr; k += 3)
        for (std::size_t j = 2; j < ny; j += 6)
            for (std::size_t i_u = 0; i_u < nu; i_u += 4)
                for (std::size_t i_x = 1; i_x < nx; i_x += 6) {
                    const node n = node_at(k, j, i_u, i_x);
                    const auto model = make(n.alpha_x, n.alpha_y);
                    const auto fresh = shade::check::sampled_albedo(model, n.v, at, 48, std::uint64_t(3 + checked));
                    const double alpha = double(j * j) / double((ny - 1) * (ny - 1));
                    const double fresh_delta = std::min(fresh.albedo.x, 1.0) -
                                               d::albedo_lookup(iso, d::albedo_grid_nodes, n.mu, alpha);
                    const double committed = double(delta[((k * ny + j) * nu + i_u) * nx + i_x]);
                    const double tolerance = 5 * (fresh.standard_error.x + committed_standard_error);
                    if (std::abs(committed - fresh_delta) > tolerance) ++drifted;
                    ++checked;
                }
    CHECK(checked == 3 * 3 * 3 * 4);
    return drifted;
}

} // namespace

TEST_CASE("anisotropic albedo tables: the committed corrections agree with a coarse regeneration by the models' own samplers") {
    const auto ggx = [](double a_x, double a_y) {
        return lobe<shade::ggx<double>>(shade::ggx<double>(a_x, a_y), shade::schlick<double>(shade::rgb<double>(1)));
    };
    const auto beckmann = [](double m_x, double m_y) {
        return lobe<shade::beckmann<double>>(shade::beckmann<double>(m_x, m_y),
                                             shade::schlick<double>(shade::rgb<double>(1)));
    };
    CHECK(count_drifted(d::ggx_anisotropic_albedo_delta, d::ggx_albedo, ggx) == 0);
    CHECK(count_drifted(d::beckmann_anisotropic_albedo_delta, d::beckmann_albedo, beckmann) == 0);
}

TEST_CASE("anisotropic albedo tables: isotropic and mirror slices hold 0, row averages are the rows' averages") {
    for (const float* delta : {d::ggx_anisotropic_albedo_delta, d::beckmann_anisotropic_albedo_delta}) {
        int nonzero = 0;
        for (std::size_t k = 0; k < nr; ++k)
            for (std::size_t j = 0; j < ny; ++j)
                if (k == 0 || j == 0)
                    for (std::size_t i = 0; i < d::anisotropic_albedo_slice; ++i)
                        nonzero += delta[(k * ny + j) * d::anisotropic_albedo_slice + i] != 0.0f;
        CHECK(nonzero == 0);
    }
    const auto rows_match = [](const float* delta, const float* averages) {
        int off = 0;
        for (std::size_t row = 0; row < d::anisotropic_albedo_rows; ++row) {
            const double expected = d::anisotropic_albedo_row_average(delta + row * nx);
            off += std::abs(double(averages[row]) - expected) > 1e-6 * (1 + std::abs(expected));
        }
        return off;
    };
    CHECK(rows_match(d::ggx_anisotropic_albedo_delta, d::ggx_anisotropic_albedo_delta_average) == 0);
    CHECK(rows_match(d::beckmann_anisotropic_albedo_delta, d::beckmann_anisotropic_albedo_delta_average) == 0);
}

TEST_CASE_TEMPLATE("anisotropic albedo tables: Catmull-Rom weights interpolate and reproduce cubics", T, float, double) {
    // At t = 0 the spline passes through node i; the weights sum to 1 (constants kept); and
    // the spline reproduces any quadratic (its tangent rule is exact for them): p(n) = n^2
    // at nodes -1, 0, 1, 2 gives t^2 at fraction t.
    const d::catmull_rom_weights<T> at_node(T(0));
    CHECK(at_node.w[0] == T(0));
    CHECK(at_node.w[1] == T(1));
    CHECK(at_node.w[2] == T(0));
    CHECK(at_node.w[3] == T(0));
    for (const double t : {0.1, 0.37, 0.5, 0.9}) {
        const d::catmull_rom_weights<T> w{T(t)};
        CHECK(double(w.w[0] + w.w[1] + w.w[2] + w.w[3]) == doctest::Approx(1.0).epsilon(1e-6));
        CHECK(double(w.w[0] * T(1) + w.w[1] * T(0) + w.w[2] * T(1) + w.w[3] * T(4)) == doctest::Approx(t * t).epsilon(1e-6));
    }
}

TEST_CASE_TEMPLATE("anisotropic albedo tables: a lobe on the nodes reads the node values", T, float, double) {
    // GGX at y_6, r_5 (alpha = (6/15)^2, q = 20^(5/9)): the fractions are 0 up to rounding, so
    // Delta at the view of node (i_u, i_x) is the stored value.
    const std::size_t k = 5, j = 6;
    for (const std::size_t i_u : {std::size_t(0), std::size_t(3), std::size_t(8)})
        for (const std::size_t i_x : {std::size_t(4), std::size_t(11), nx - 1}) {
            const node n = node_at(k, j, i_u, i_x);
            const auto cell = d::anisotropic_albedo_locate(T(n.alpha_x), T(n.alpha_y));
            const T got = d::anisotropic_albedo_delta(d::ggx_anisotropic_albedo_delta, cell, T(n.v.x), T(n.v.y), T(n.v.z));
            const double stored = double(d::ggx_anisotropic_albedo_delta[((k * ny + j) * nu + i_u) * nx + i_x]);
            CAPTURE(i_u);
            CAPTURE(i_x);
            CHECK(double(got) == doctest::Approx(stored).epsilon(1e-4).scale(1));
            // The same lobe with its axes exchanged, seen from the exchanged azimuth.
            const auto swapped = d::anisotropic_albedo_locate(T(n.alpha_y), T(n.alpha_x));
            const T got_swapped =
                d::anisotropic_albedo_delta(d::ggx_anisotropic_albedo_delta, swapped, T(n.v.y), T(n.v.x), T(n.v.z));
            CHECK(double(got_swapped) == doctest::Approx(double(got)).epsilon(1e-6).scale(1));
        }
}
