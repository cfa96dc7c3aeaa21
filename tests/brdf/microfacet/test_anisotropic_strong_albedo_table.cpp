// The committed strong-anisotropy correction tables (shade/brdf/microfacet/detail/
// anisotropic_strong_albedo_data.hpp, written by examples/albedo_tables.cpp
// --anisotropic-strong) against a coarse regeneration with the models' own samplers, so they
// cannot drift from the models; their row averages against the rows; and the interpolation
// of the strong-anisotropy grid of shade/brdf/microfacet/anisotropic_albedo_table.hpp.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include <doctest/doctest.h>

#include <shade/brdf/cook_torrance.hpp>
#include <shade/brdf/microfacet/anisotropic_albedo_table.hpp>
#include <shade/brdf/microfacet/detail/albedo_data.hpp>
#include <shade/brdf/microfacet/detail/anisotropic_strong_albedo_data.hpp>
#include <shade/check/energy.hpp>

namespace {

namespace d = shade::detail;
constexpr std::size_t nx = d::strong_anisotropy_mu_nodes, nu = d::strong_anisotropy_azimuth_nodes;
constexpr std::size_t ny = d::strong_anisotropy_roughness_nodes, nz = d::strong_anisotropy_ratio_nodes;

// The generated header states each table's largest node standard error; both are below this.
constexpr double committed_standard_error = 3e-4;

struct node {
    double alpha_x, alpha_y; // the lobe of slice (k, j): the smoother axis along t
    shade::vec3<double> v;   // the view of row i_u, column i_x
    double mu;
    double alpha_base;
};

// The lobe and view of node (k, j, i_u, i_x), as the generator builds them: alpha_max =
// sqrt 2 y_j^2, alpha_min = alpha_max z_k^2 / ratio_max (at z = 0, 1e-7 alpha_max: a 1-D
// rough surface), mu = x^2, and the azimuth phi = (pi / 2) u (1 + u) / 2 from t.
node node_at(std::size_t k, std::size_t j, std::size_t i_u, std::size_t i_x) {
    const double y = double(j) / double(ny - 1), z = double(k) / double(nz - 1);
    const double alpha_max = y * y * d::strong_anisotropy_alpha_top;
    const double alpha_min = alpha_max * std::max(z * z / d::anisotropic_albedo_ratio_max, 1e-7);
    const double x = double(i_x) / double(nx - 1);
    const double mu = std::min(std::max(x * x, d::albedo_grid_mu_min), 1.0);
    const double phi = d::strong_anisotropy_phi(double(i_u) / double(nu - 1));
    const double sin_theta = std::sqrt((1 - mu) * (1 + mu));
    return {alpha_min, alpha_max, shade::vec3<double>(sin_theta * std::cos(phi), sin_theta * std::sin(phi), mu), mu,
            d::anisotropic_albedo_base_alpha(alpha_min, alpha_max)};
}

template <class Distribution>
using lobe = shade::cook_torrance<Distribution, shade::schlick<double>, shade::smith_height_correlated<double>>;

// Regenerates nodes of `delta` spread over all four axes (z = 0, the 1-D rough surface,
// among them) with make(alpha_x, alpha_y) and 48^2 samples each, and counts those whose
// difference from the committed value without its lift exceeds 5 standard deviations of the
// difference (fresh SE + committed SE bound).
template <class Make>
int count_drifted(const float* delta, const float* iso, const Make& make) {
    int drifted = 0, checked = 0;
    shade::surface_point<double> at;
    at.shading = shade::frame<double>::from_normal_tangent({0, 0, 1}, {1, 0, 0});
    for (std::size_t k = 0; k < nz; k += 2)
        for (std::size_t j = 3; j < ny; j += 6)
            for (std::size_t i_u = 0; i_u < nu; i_u += 4)
                for (std::size_t i_x = 1; i_x < nx; i_x += 6) {
                    const node n = node_at(k, j, i_u, i_x);
                    const auto model = make(n.alpha_x, n.alpha_y);
                    const auto fresh = shade::check::sampled_albedo(model, n.v, at, 48, std::uint64_t(5 + checked));
                    const double e_iso = d::albedo_lookup(iso, d::albedo_grid_nodes, n.mu, n.alpha_base);
                    const double fresh_delta = std::min(fresh.albedo.x, 1.0) - e_iso;
                    // The node holds E - E_iso + c (1 - E), c the lift: E = (stored + E_iso - c) / (1 - c).
                    const double c = d::strong_anisotropy_lift;
                    const double stored = double(delta[((k * ny + j) * nu + i_u) * nx + i_x]);
                    const double committed = (stored + e_iso - c) / (1 - c) - e_iso;
                    const double tolerance = 5 * (fresh.standard_error.x + committed_standard_error);
                    if (std::abs(committed - fresh_delta) > tolerance) ++drifted;
                    ++checked;
                }
    CHECK(checked == 3 * 3 * 4 * 4);
    return drifted;
}

} // namespace

TEST_CASE("strong anisotropy tables: the committed corrections agree with a coarse regeneration by the models' own samplers") {
    // Unchecked distributions: the 1-D rough surface's nodes have alpha_min below the models'
    // smallest accepted roughness, as in the generator.
    const auto ggx = [](double a_x, double a_y) {
        return lobe<shade::ggx<double>>(shade::ggx<double>(shade::unchecked, a_x, a_y),
                                        shade::schlick<double>(shade::rgb<double>(1)));
    };
    const auto beckmann = [](double m_x, double m_y) {
        return lobe<shade::beckmann<double>>(shade::beckmann<double>(shade::unchecked, m_x, m_y),
                                             shade::schlick<double>(shade::rgb<double>(1)));
    };
    CHECK(count_drifted(d::ggx_anisotropic_strong_albedo_delta, d::ggx_albedo, ggx) == 0);
    CHECK(count_drifted(d::beckmann_anisotropic_strong_albedo_delta, d::beckmann_albedo, beckmann) == 0);
    // A table of the other distribution fails: GGX and Beckmann lobes of the same roughnesses
    // shadow differently.
    CHECK(count_drifted(d::beckmann_anisotropic_strong_albedo_delta, d::ggx_albedo, ggx) > 20);
}

TEST_CASE("strong anisotropy tables: mirror slices hold 0, row averages are the rows' averages") {
    for (const float* delta : {d::ggx_anisotropic_strong_albedo_delta, d::beckmann_anisotropic_strong_albedo_delta}) {
        int nonzero = 0;
        for (std::size_t k = 0; k < nz; ++k)
            for (std::size_t i = 0; i < d::strong_anisotropy_slice; ++i)
                nonzero += delta[(k * ny) * d::strong_anisotropy_slice + i] != 0.0f;
        CHECK(nonzero == 0);
    }
    const auto rows_match = [](const float* delta, const float* averages) {
        int off = 0;
        for (std::size_t row = 0; row < d::strong_anisotropy_rows; ++row) {
            const double expected = d::anisotropic_albedo_row_average(delta + row * nx);
            off += std::abs(double(averages[row]) - expected) > 1e-6 * (1 + std::abs(expected));
        }
        return off;
    };
    CHECK(rows_match(d::ggx_anisotropic_strong_albedo_delta, d::ggx_anisotropic_strong_albedo_delta_average) == 0);
    CHECK(rows_match(d::beckmann_anisotropic_strong_albedo_delta, d::beckmann_anisotropic_strong_albedo_delta_average) ==
          0);
}

TEST_CASE_TEMPLATE("spline_taps: the end taps extrapolate linearly and keep linear functions", T, float,
                   double) {
    // Weights sum to 1 and p(n) = 3 n - 2 is reproduced exactly in every cell, the first and
    // last included (Catmull-Rom reproduces quadratics inside; the extrapolated neighbour
    // keeps lines at the ends). At t = 0 the spline passes through the node.
    constexpr std::size_t n = 6;
    for (std::size_t i = 0; i + 1 < n; ++i)
        for (const double t : {0.0, 0.2, 0.5, 0.85}) {
            const d::spline_taps<T> taps(i, T(t), n);
            double sum = 0, line = 0;
            for (int a = 0; a < 4; ++a) {
                sum += double(taps.weight[a]);
                line += double(taps.weight[a]) * (3 * double(taps.node[a]) - 2);
            }
            CAPTURE(i);
            CAPTURE(t);
            CHECK(sum == doctest::Approx(1.0).epsilon(1e-6));
            CHECK(line == doctest::Approx(3 * (double(i) + t) - 2).epsilon(1e-5).scale(1));
        }
}

TEST_CASE_TEMPLATE("strong anisotropy tables: a lobe on the nodes reads the node values, either axis the smoother", T,
                   float, double) {
    // GGX at y_9, z_2 (alpha_max = sqrt 2 (9/15)^2, alpha_min = alpha_max / 80): the fractions
    // are 0 up to rounding, so Delta at the view of node (i_u, i_x) is the stored value; the
    // same lobe with its axes exchanged, seen from the exchanged azimuth, reads the same.
    const std::size_t k = 2, j = 9;
    for (const std::size_t i_u : {std::size_t(0), std::size_t(5), nu - 1})
        for (const std::size_t i_x : {std::size_t(4), std::size_t(13), nx - 1}) {
            const node n = node_at(k, j, i_u, i_x);
            const auto cell = d::strong_anisotropy_locate(T(n.alpha_x), T(n.alpha_y));
            const T got = d::strong_anisotropy_delta(d::ggx_anisotropic_strong_albedo_delta, cell, T(n.v.x), T(n.v.y),
                                                     T(n.v.z));
            const double stored = double(d::ggx_anisotropic_strong_albedo_delta[((k * ny + j) * nu + i_u) * nx + i_x]);
            CAPTURE(i_u);
            CAPTURE(i_x);
            CHECK(double(got) == doctest::Approx(stored).epsilon(2e-4).scale(1));
            const auto swapped = d::strong_anisotropy_locate(T(n.alpha_y), T(n.alpha_x));
            const T got_swapped = d::strong_anisotropy_delta(d::ggx_anisotropic_strong_albedo_delta, swapped, T(n.v.y),
                                                             T(n.v.x), T(n.v.z));
            CHECK(double(got_swapped) == doctest::Approx(double(got)).epsilon(1e-6).scale(1));
        }
}
