#pragma once
// The grid and the interpolation of the anisotropic correction to the rough-dielectric
// albedo tables (shade/bsdf/dielectric_albedo_table.hpp) that the energy compensation of
// shade::compensated_rough_dielectric reads for anisotropic GGX. The numbers are generated
// into shade/bsdf/detail/dielectric_anisotropic_albedo_data.hpp by
//
//   examples/dielectric_albedo_tables --anisotropic --out include/shade/bsdf/detail/dielectric_anisotropic_albedo_data.hpp
//
// An anisotropic interface (roughness alpha_x along t, alpha_y along b) has a total albedo
// R + T (importance mode) that depends on the azimuth of the view as well as on its cosine:
// the masking of the view and of the reflected and refracted directions follows the
// roughness projected on their azimuths (Heitz 2014, "Understanding the Masking-Shadowing
// Function in Microfacet-Based BRDFs", JCGT 3(2), eq. 80). As for conductors
// (shade/brdf/microfacet/anisotropic_albedo_table.hpp), the difference from the isotropic
// table read at the geometric-mean roughness is tabulated,
//
//     Delta_s(w) = E_s(w) - E_s,iso(mu, sqrt(alpha_x alpha_y)),
//
// for each side s of the view (entering, eta_s > 1; exiting, eta_s < 1). It is not the
// conductor's Delta, nor a multiple of it: refraction changes which directions are masked
// (near eta = 1 the transmitted light leaves almost along the view, at the view's projected
// roughness; from the denser side total internal reflection adds reflected light), and the
// two differ in size and sign at the same view. Delta depends on six numbers, each mapped
// to [0, 1] with uniform nodes:
//
//     x = sqrt(mu)                         dense toward grazing
//     u = (ln(1 + (q^2 - 1) sin^2 phi) / ln(q^2) + 2 phi / pi) / 2
//                                          the mean of two coordinates of w's azimuth phi
//                                          (from the smoother axis; q = max / min
//                                          roughness): the projected roughness on a log
//                                          scale (the conductor tables' coordinate), which
//                                          turns within a few degrees of the smoother axis
//                                          at strong anisotropy, and phi itself, which
//                                          resolves the peak of E that light trapped by
//                                          total internal reflection puts between the axes
//     y = sqrt(sqrt(alpha_x alpha_y))      as the isotropic tables
//     r = ln(q) / ln(ratio_max)            the anisotropy, 0 for isotropic
//     e = log(eta_hat - 1) on [log 0.05, log 2], eta_hat = max(eta, 1 / eta) in [1.05, 3],
//                                          as the isotropic tables
//     the side
//
// Delta is Catmull-Rom cubic (Catmull, Rom 1974) along x, y, r and e, with a neighbour
// beyond either end of an axis extrapolated linearly, and linear along u. For the average,
// each row (the x nodes of one (side, e, r, y, u) node) is stored with its exact cosine
// average; Delta_avg of an interface blends those with the weights of its nodes and
// integrates over the azimuth by quadrature, so it is the average of the Delta the
// interface reads and the compensation stays normalised. Nodes with r = 0 (isotropic) or
// y = 0 (a smooth interface) hold 0. Anisotropy beyond ratio_max reads r = 1, mean
// roughness above 1 reads y = 1 and eta_hat outside [1.05, 3] the nearest end: there the
// correction is approximate. Stored as float; the accuracy is stated in the generated
// header. Layout: index ((((side * e_nodes + m) * r_nodes + k) * y_nodes + j) * u_nodes + i_u)
// * x_nodes + i_x.

#include <cmath>
#include <concepts>
#include <cstddef>

#include <glm/common.hpp>

#include <shade/brdf/microfacet/albedo_table.hpp>
#include <shade/bsdf/dielectric_albedo_table.hpp>
#include <shade/core/quadrature.hpp>

namespace shade::detail {

/// Nodes along x = sqrt(mu) of the dielectric anisotropic correction tables.
inline constexpr std::size_t dielectric_anisotropic_mu_nodes = 16;
/// Nodes along u, the azimuth coordinate.
inline constexpr std::size_t dielectric_anisotropic_azimuth_nodes = 9;
/// Nodes along y = sqrt(sqrt(alpha_x alpha_y)).
inline constexpr std::size_t dielectric_anisotropic_roughness_nodes = 10;
/// Nodes along r = ln(alpha_y / alpha_x) / ln(ratio_max).
inline constexpr std::size_t dielectric_anisotropic_ratio_nodes = 6;
/// Nodes along e = log(eta_hat - 1).
inline constexpr std::size_t dielectric_anisotropic_eta_nodes = 5;
/// The largest anisotropy max(alpha_x, alpha_y) / min(alpha_x, alpha_y) the tables cover.
inline constexpr double dielectric_anisotropic_ratio_max = 20;
/// Values per row (one (side, e, r, y, u) node).
inline constexpr std::size_t dielectric_anisotropic_row = dielectric_anisotropic_mu_nodes;
/// Rows per table: 2 sides x eta x ratio x roughness x azimuth nodes.
inline constexpr std::size_t dielectric_anisotropic_rows =
    2 * dielectric_anisotropic_eta_nodes * dielectric_anisotropic_ratio_nodes * dielectric_anisotropic_roughness_nodes *
    dielectric_anisotropic_azimuth_nodes;
/// Values per table.
inline constexpr std::size_t dielectric_anisotropic_size = dielectric_anisotropic_rows * dielectric_anisotropic_row;

/// The row index of node (side, m along e, k along r, j along y, i_u along u).
[[nodiscard]] constexpr std::size_t dielectric_anisotropic_row_index(std::size_t side, std::size_t m, std::size_t k,
                                                                     std::size_t j, std::size_t i_u) noexcept {
    return (((side * dielectric_anisotropic_eta_nodes + m) * dielectric_anisotropic_ratio_nodes + k) *
                dielectric_anisotropic_roughness_nodes +
            j) *
               dielectric_anisotropic_azimuth_nodes +
           i_u;
}

/// The four nodes and weights with which a Catmull-Rom spline (Catmull, Rom 1974, "A Class
/// of Local Interpolating Splines"; tangents (p_i+1 - p_i-1) / 2) reads the fraction t of
/// cell i of an n-node axis (n >= 3): nodes i - 1 .. i + 2, a neighbour beyond an end
/// replaced by its linear extrapolation (2 p_0 - p_1, 2 p_n-1 - p_n-2), so the tangent at an
/// end node is the secant of its cell and no value from beyond the axis is needed. Exact for
/// quadratics inside; the weights sum to 1.
template <std::floating_point T>
struct spline_taps {
    std::size_t node[4]{};
    T weight[4]{};

    spline_taps() = default;
    spline_taps(std::size_t i, T t, std::size_t n) noexcept {
        const T w[4] = {T(0.5) * t * ((T(2) - t) * t - T(1)), T(0.5) * (t * t * (T(3) * t - T(5)) + T(2)),
                        T(0.5) * t * ((T(4) - T(3) * t) * t + T(1)), T(0.5) * t * t * (t - T(1))};
        for (int a = 0; a < 4; ++a) weight[a] = w[a];
        node[0] = i > 0 ? i - 1 : 0;
        node[1] = i;
        node[2] = i + 1;
        node[3] = i + 2 < n ? i + 2 : n - 1;
        if (i == 0) { // ghost 2 p_0 - p_1 for node -1
            weight[1] += T(2) * w[0];
            weight[2] -= w[0];
            weight[0] = 0;
        }
        if (i + 2 >= n) { // ghost 2 p_n-1 - p_n-2 for node n
            weight[2] += T(2) * w[3];
            weight[1] -= w[3];
            weight[3] = 0;
        }
    }
};

/// Where an interface with roughnesses alpha_x != alpha_y and relative index eta reads the
/// correction tables. Computed once per interface.
template <std::floating_point T>
struct dielectric_anisotropic_cell {
    bool swapped = false; ///< alpha_x > alpha_y: the axes are exchanged
    T q2_minus_1 = 0;     ///< q^2 - 1 (> 0), q = max / min roughness
    T inv_log_q2 = 0;     ///< 1 / ln(q^2)
    spline_taps<T> y{};   ///< along sqrt(sqrt(alpha_x alpha_y))
    spline_taps<T> r{};   ///< along ln(q) / ln(ratio_max)
    spline_taps<T> e{};   ///< along log(eta_hat - 1)
};

/// The cell of roughnesses alpha_x != alpha_y (both > 0 and finite) and relative index eta
/// (either side's: only eta_hat = max(eta, 1 / eta) is used).
template <std::floating_point T>
[[nodiscard]] inline dielectric_anisotropic_cell<T> dielectric_anisotropic_locate(T alpha_x, T alpha_y, T eta) noexcept {
    dielectric_anisotropic_cell<T> c;
    c.swapped = alpha_x > alpha_y;
    const T q = c.swapped ? alpha_x / alpha_y : alpha_y / alpha_x;
    c.q2_minus_1 = (q - T(1)) * (q + T(1));
    c.inv_log_q2 = T(1) / (T(2) * std::log(q));
    const auto y = albedo_grid_locate(std::sqrt(std::sqrt(alpha_x * alpha_y)), dielectric_anisotropic_roughness_nodes);
    const auto r = albedo_grid_locate(T(std::log(q) / std::log(dielectric_anisotropic_ratio_max)),
                                      dielectric_anisotropic_ratio_nodes);
    const T eta_hat = eta > T(1) ? eta : T(1) / eta;
    const auto e = albedo_grid_locate(dielectric_albedo_eta_coordinate(eta_hat), dielectric_anisotropic_eta_nodes);
    c.y = spline_taps<T>(y.i, y.t, dielectric_anisotropic_roughness_nodes);
    c.r = spline_taps<T>(r.i, r.t, dielectric_anisotropic_ratio_nodes);
    c.e = spline_taps<T>(e.i, e.t, dielectric_anisotropic_eta_nodes);
    return c;
}

/// The azimuth coordinate u of the tables for the azimuth phi in [0, pi/2] from the smoother
/// axis, phi = atan(|across| / |along|) for the components of w across and along it:
/// (ln(1 + (q^2 - 1) sin^2 phi) / ln(q^2) + 2 phi / pi) / 2, increasing from 0 to 1.
template <std::floating_point T>
[[nodiscard]] inline T dielectric_anisotropic_u(const dielectric_anisotropic_cell<T>& cell, T along, T across) noexcept {
    const T a2 = along * along, c2 = across * across;
    const T sin2 = a2 + c2 > T(0) ? glm::min(c2 / (a2 + c2), T(1)) : T(0);
    const T phi = std::atan2(std::abs(across), std::abs(along));
    return T(0.5) * (std::log1p(cell.q2_minus_1 * sin2) * cell.inv_log_q2 + phi * T(0.6366197723675814));
}

/// The azimuth phi in [0, pi/2] of the coordinate u in [0, 1] for anisotropy q (the inverse
/// of dielectric_anisotropic_u, by bisection to double precision; for the generator and the
/// average).
[[nodiscard]] inline double dielectric_anisotropic_phi(double u, double q2_minus_1, double inv_log_q2) noexcept {
    double lo = 0, hi = 1.5707963267948966;
    for (int k = 0; k < 60; ++k) {
        const double mid = 0.5 * (lo + hi), sn = std::sin(mid);
        const double at = 0.5 * (std::log1p(q2_minus_1 * sn * sn) * inv_log_q2 + mid * 0.6366197723675814);
        (at < u ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

/// Delta_s(w) for the unit local direction w (|w.z| = mu; the sign of w.z is not used: the
/// caller names the side) of an interface located by `cell`, side 0 entering (eta_s > 1),
/// 1 exiting, from `delta` (dielectric_anisotropic_size values). Returns the albedo
/// difference, dimensionless.
template <std::floating_point T>
[[nodiscard]] inline T dielectric_anisotropic_delta(const float* delta, const dielectric_anisotropic_cell<T>& cell,
                                                    std::size_t side, T w_x, T w_y, T mu) noexcept {
    constexpr std::size_t nx = dielectric_anisotropic_mu_nodes;
    // At the pole (w_x = w_y = 0) the azimuth reads 0: Delta does not depend on it there.
    const auto x = albedo_grid_locate(std::sqrt(glm::clamp(std::abs(mu), T(0), T(1))), nx);
    const auto u = albedo_grid_locate(cell.swapped ? dielectric_anisotropic_u(cell, w_y, w_x)
                                                   : dielectric_anisotropic_u(cell, w_x, w_y),
                                      dielectric_anisotropic_azimuth_nodes);
    const spline_taps<T> wx(x.i, x.t, nx);
    T sum = 0;
    for (int a = 0; a < 4; ++a) {
        if (cell.e.weight[a] == T(0)) continue;
        for (int b = 0; b < 4; ++b) {
            if (cell.r.weight[b] == T(0)) continue;
            T along_y = 0;
            for (int c = 0; c < 4; ++c) {
                if (cell.y.weight[c] == T(0)) continue;
                const float* row0 =
                    delta + dielectric_anisotropic_row_index(side, cell.e.node[a], cell.r.node[b], cell.y.node[c], u.i) * nx;
                const float* row1 = row0 + nx;
                T d0 = 0, d1 = 0;
                for (int k = 0; k < 4; ++k) {
                    d0 += wx.weight[k] * T(row0[wx.node[k]]);
                    d1 += wx.weight[k] * T(row1[wx.node[k]]);
                }
                along_y += cell.y.weight[c] * (d0 + u.t * (d1 - d0));
            }
            sum += cell.e.weight[a] * cell.r.weight[b] * along_y;
        }
    }
    return sum;
}

/// The cosine average 2 integral_0^1 Delta mu dmu = 4 integral_0^1 Delta(x) x^3 dx of one
/// row of x nodes, read as dielectric_anisotropic_delta reads it (Catmull-Rom in x):
/// 5-point Gauss-Legendre per cell (Abramowitz, Stegun 1964, "Handbook of Mathematical
/// Functions", 25.4.29), exact there (a polynomial of degree 6). For the generator and the
/// tests.
[[nodiscard]] inline double dielectric_anisotropic_row_average(const float* row) noexcept {
    constexpr std::size_t nx = dielectric_anisotropic_mu_nodes;
    constexpr const double* node = gauss_legendre_5_nodes;
    constexpr const double* weight = gauss_legendre_5_weights;
    double sum = 0;
    for (std::size_t c = 0; c + 1 < nx; ++c)
        for (int q = 0; q < 5; ++q) {
            const double t = 0.5 * (1.0 + node[q]);
            const double x = (double(c) + t) / double(nx - 1);
            const spline_taps<double> w(c, t, nx);
            double d = 0;
            for (int a = 0; a < 4; ++a) d += w.weight[a] * double(row[w.node[a]]);
            sum += weight[q] * (0.5 / double(nx - 1)) * 4.0 * d * x * x * x;
        }
    return sum;
}

/// Delta_s,avg, the cosine-weighted hemispherical average (1 / pi) integral Delta_s(w) |n·w|
/// dw of dielectric_anisotropic_delta on side s for the interface located by `cell`, from
/// `row_averages` (dielectric_anisotropic_row_average of every row of the table): the rows'
/// averages R(u_i) blended with the weights the lookup gives their nodes (exact: the x axis
/// is the same for every row), then (2 / pi) integral_0^(pi/2) R(u(phi)) dphi with R linear
/// in u between nodes, by 5-point Gauss-Legendre in phi on each u cell. Dimensionless.
template <std::floating_point T>
[[nodiscard]] inline T dielectric_anisotropic_delta_average(const float* row_averages,
                                                            const dielectric_anisotropic_cell<T>& cell,
                                                            std::size_t side) noexcept {
    constexpr std::size_t nu = dielectric_anisotropic_azimuth_nodes;
    constexpr const double* node = gauss_legendre_5_nodes;
    constexpr const double* weight = gauss_legendre_5_weights;
    double r[nu] = {};
    for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b)
            for (int c = 0; c < 4; ++c) {
                const double w = double(cell.e.weight[a]) * double(cell.r.weight[b]) * double(cell.y.weight[c]);
                if (w == 0) continue;
                const float* row =
                    row_averages + dielectric_anisotropic_row_index(side, cell.e.node[a], cell.r.node[b], cell.y.node[c], 0);
                for (std::size_t i = 0; i < nu; ++i) r[i] += w * double(row[i]);
            }
    const double inv_log_q2 = double(cell.inv_log_q2), q2m1 = double(cell.q2_minus_1);
    double sum = 0;
    double phi0 = 0;
    for (std::size_t i = 0; i + 1 < nu; ++i) {
        const double u0 = double(i) / double(nu - 1);
        const double phi1 =
            i + 2 == nu ? 1.5707963267948966 : dielectric_anisotropic_phi(double(i + 1) / double(nu - 1), q2m1, inv_log_q2);
        const double half = 0.5 * (phi1 - phi0);
        for (int q = 0; q < 5; ++q) {
            const double phi = phi0 + half * (1.0 + node[q]);
            const double sn = std::sin(phi);
            const double u = 0.5 * (std::log1p(q2m1 * sn * sn) * inv_log_q2 + phi * 0.6366197723675814);
            const double t = (u - u0) * double(nu - 1);
            sum += weight[q] * half * (r[i] + t * (r[i + 1] - r[i]));
        }
        phi0 = phi1;
    }
    return T(sum / 1.5707963267948966);
}

} // namespace shade::detail
