#pragma once
// The grid and the interpolation of the anisotropic correction to the rough-dielectric
// albedo tables (shade/bsdf/dielectric_albedo_table.hpp) that the energy compensation of
// shade::compensated_rough_dielectric reads for anisotropic GGX. The numbers are generated
// into shade/bsdf/detail/dielectric_anisotropic_albedo_data.hpp by
//
//   examples/dielectric_albedo_tables --anisotropic --envelope 40 --envelope-margin 0.001 --envelope-below-z 0.5
//       --envelope-rough-above 1.1 --lift 0.0025,0.0045 --out include/shade/bsdf/detail/dielectric_anisotropic_albedo_data.hpp
//
// An anisotropic interface (roughness alpha_x along t, alpha_y along b) has a total albedo
// R + T (importance mode) that depends on the azimuth of the view as well as on its cosine:
// the masking of the view and of the reflected and refracted directions follows the
// roughness projected on their azimuths (Heitz 2014, "Understanding the Masking-Shadowing
// Function in Microfacet-Based BRDFs", JCGT 3(2), eq. 80). The difference from the isotropic
// table read at a base roughness is tabulated,
//
//     Delta_s(w) = E_s(w) - E_s,iso(mu, alpha_base),
//
// for each side s of the view (entering, eta_s > 1; exiting, eta_s < 1). alpha_base is the
// root mean square alpha_rms = sqrt((alpha_x^2 + alpha_y^2) / 2) up to 0.7, bent smoothly
// toward 1 above (dielectric_anisotropic_base_alpha): alpha_rms stays finite as the smaller
// roughness goes to 0 (a 1-D rough surface, OpenPBR's anisotropy 1), where the geometric
// mean would read a nearly smooth interface, and the bend keeps alpha_base below the
// isotropic table's clamp at alpha 1, which would put a kink into Delta. Delta depends on six
// numbers, each mapped to [0, 1] with uniform nodes:
//
//     x = sqrt(mu)                         dense toward grazing
//     u                                    w's azimuth phi in [0, pi/2] from the smoother
//                                          axis, 2 phi / pi = g(u), g(u) = u (1 + u) / 2:
//                                          denser near the smoother axis, where the
//                                          projected roughness turns fastest
//     y = sqrt(alpha_max / sqrt 2)         alpha_max = max(alpha_x, alpha_y) up to sqrt 2, the
//                                          largest alpha of OpenPBR's roughness_to_alpha
//     z = sqrt(alpha_min / alpha_max)      0 a 1-D rough surface (OpenPBR's anisotropy 1), 1
//                                          isotropic; dense toward 0
//     e = log(eta_hat - 1) on [log 0.05, log 2], eta_hat = max(eta, 1 / eta) in [1.05, 3],
//                                          as the isotropic tables
//     the side
//
// Delta is Catmull-Rom cubic (Catmull, Rom 1974) along x, y, z and e, with a neighbour
// beyond either end of an axis extrapolated linearly, and linear along u. Nodes with y = 0
// (a smooth interface) are 0 by construction and not stored; nodes with z = 1 (isotropic)
// hold E_iso(mu, alpha) - E_iso(mu, alpha_base) where alpha_max <= 1 (0 up to 0.7) and the
// isotropic table's shortfall above (that table stops at alpha = 1), so that an anisotropic
// interface rougher than 1 is compensated. For the
// average, each stored row (the x nodes of one (side, e, z, y, u) node) has its exact cosine
// average; Delta_avg of an interface blends those with the weights of its nodes and
// integrates over the azimuth exactly (linear in u), so it is the average of the Delta the
// interface reads and the compensation stays normalised. alpha_max above sqrt 2 reads y = 1
// and eta_hat outside [1.05, 3] the nearest end: there the correction is approximate. Stored
// as float, each node a little above its estimate of Delta (the lift: 0.0025 entering,
// 0.0045 exiting) and, where z < 0.5 (the exiting side's total-reflection kinks) or
// alpha_rms > 1.1, raised further as an upper envelope of E (the generated header states by
// how much): the compensated albedo 1 + E_true - E_read then errs below 1 rather than above.
// Layout: index
// ((((side * e_nodes + m) * z_nodes + k) * (y_nodes - 1) + j - 1) * u_nodes + i_u) * x_nodes
// + i_x for y node j >= 1.

#include <cmath>
#include <concepts>
#include <cstddef>

#include <glm/common.hpp>

#include <shade/brdf/microfacet/albedo_table.hpp>
#include <shade/bsdf/dielectric_albedo_table.hpp>
#include <shade/core/quadrature.hpp>

namespace shade::detail {

/// Nodes along x = sqrt(mu) of the dielectric anisotropic correction tables.
inline constexpr std::size_t dielectric_anisotropic_mu_nodes = 17;
/// Nodes along u, the azimuth coordinate.
inline constexpr std::size_t dielectric_anisotropic_azimuth_nodes = 13;
/// Nodes along y = sqrt(alpha_max / sqrt 2) (node 0, a smooth interface, is not stored).
inline constexpr std::size_t dielectric_anisotropic_roughness_nodes = 10;
/// Nodes along z = sqrt(alpha_min / alpha_max).
inline constexpr std::size_t dielectric_anisotropic_ratio_nodes = 6;
/// Nodes along e = log(eta_hat - 1).
inline constexpr std::size_t dielectric_anisotropic_eta_nodes = 7;
/// The largest alpha_max the y axis reaches (OpenPBR's largest alpha).
inline constexpr double dielectric_anisotropic_alpha_top = 1.4142135623730951;
/// Values per row (one stored (side, e, z, y, u) node).
inline constexpr std::size_t dielectric_anisotropic_row = dielectric_anisotropic_mu_nodes;
/// Stored rows: 2 sides x eta x ratio x (roughness - 1) x azimuth nodes.
inline constexpr std::size_t dielectric_anisotropic_rows =
    2 * dielectric_anisotropic_eta_nodes * dielectric_anisotropic_ratio_nodes *
    (dielectric_anisotropic_roughness_nodes - 1) * dielectric_anisotropic_azimuth_nodes;
/// Values per table.
inline constexpr std::size_t dielectric_anisotropic_size = dielectric_anisotropic_rows * dielectric_anisotropic_row;

/// The row index of the stored node (side, m along e, k along z, 1 <= j along y, i_u along u).
[[nodiscard]] constexpr std::size_t dielectric_anisotropic_row_index(std::size_t side, std::size_t m, std::size_t k,
                                                                     std::size_t j, std::size_t i_u) noexcept {
    return (((side * dielectric_anisotropic_eta_nodes + m) * dielectric_anisotropic_ratio_nodes + k) *
                (dielectric_anisotropic_roughness_nodes - 1) +
            (j - 1)) *
               dielectric_anisotropic_azimuth_nodes +
           i_u;
}

/// The root mean square sqrt((alpha_x^2 + alpha_y^2) / 2) of the two roughnesses.
template <std::floating_point T>
[[nodiscard]] inline T dielectric_anisotropic_rms_alpha(T alpha_x, T alpha_y) noexcept {
    return std::sqrt(T(0.5) * (alpha_x * alpha_x + alpha_y * alpha_y));
}

/// Where the base roughness starts to bend away from the root mean square.
inline constexpr double dielectric_anisotropic_base_knee = 0.7;

/// The roughness the isotropic table is read at under the correction: the root mean square r
/// (dielectric_anisotropic_rms_alpha) up to the knee a = dielectric_anisotropic_base_knee,
/// above it 1 - (1 - a) exp(-(r - a) / (1 - a)), which meets r with its slope at a and stays
/// below 1 (the isotropic table's largest alpha) for every r. The isotropic table clamps alpha
/// at 1, so read at r itself Delta would have a kink where r crosses 1, which the spline
/// between the y and z nodes cannot follow.
template <std::floating_point T>
[[nodiscard]] inline T dielectric_anisotropic_base_alpha(T alpha_x, T alpha_y) noexcept {
    const T r = dielectric_anisotropic_rms_alpha(alpha_x, alpha_y), a = T(dielectric_anisotropic_base_knee);
    return r <= a ? r : T(1) - (T(1) - a) * std::exp(-(r - a) / (T(1) - a));
}

/// Where an interface with roughnesses alpha_x != alpha_y and relative index eta reads the
/// correction tables. Computed once per interface.
template <std::floating_point T>
struct dielectric_anisotropic_cell {
    bool swapped = false; ///< alpha_x > alpha_y: the smoother axis is b
    spline_taps<T> y{};   ///< along sqrt(alpha_max / sqrt 2)
    spline_taps<T> z{};   ///< along sqrt(alpha_min / alpha_max)
    spline_taps<T> e{};   ///< along log(eta_hat - 1)
};

/// The cell of roughnesses alpha_x != alpha_y (>= 0, finite, not both 0) and relative index
/// eta (either side's: only eta_hat = max(eta, 1 / eta) is used).
template <std::floating_point T>
[[nodiscard]] inline dielectric_anisotropic_cell<T> dielectric_anisotropic_locate(T alpha_x, T alpha_y, T eta) noexcept {
    dielectric_anisotropic_cell<T> c;
    c.swapped = alpha_x > alpha_y;
    const T hi = glm::max(alpha_x, alpha_y), lo = glm::min(alpha_x, alpha_y);
    const auto y = albedo_grid_locate(std::sqrt(hi / T(dielectric_anisotropic_alpha_top)), dielectric_anisotropic_roughness_nodes);
    const auto z = albedo_grid_locate(std::sqrt(lo / hi), dielectric_anisotropic_ratio_nodes);
    const T eta_hat = eta > T(1) ? eta : T(1) / eta;
    const auto e = albedo_grid_locate(dielectric_albedo_eta_coordinate(eta_hat), dielectric_anisotropic_eta_nodes);
    c.y = spline_taps<T>(y.i, y.t, dielectric_anisotropic_roughness_nodes);
    c.z = spline_taps<T>(z.i, z.t, dielectric_anisotropic_ratio_nodes);
    c.e = spline_taps<T>(e.i, e.t, dielectric_anisotropic_eta_nodes);
    return c;
}

/// The azimuth coordinate u in [0, 1] of the azimuth phi in [0, pi/2] from the smoother
/// axis: g(u) = 2 phi / pi with g(u) = u (1 + u) / 2, so u = (sqrt(1 + 8 g) - 1) / 2,
/// written 4 g / (1 + sqrt(1 + 8 g)) without cancellation.
template <std::floating_point T>
[[nodiscard]] inline T dielectric_anisotropic_u(T phi) noexcept {
    const T g = glm::clamp(phi * T(0.6366197723675814), T(0), T(1));
    return T(4) * g / (T(1) + std::sqrt(T(1) + T(8) * g));
}

/// The azimuth phi in [0, pi/2] of the coordinate u in [0, 1] (the inverse of
/// dielectric_anisotropic_u): pi/2 u (1 + u) / 2.
[[nodiscard]] constexpr double dielectric_anisotropic_phi(double u) noexcept {
    return 1.5707963267948966 * 0.5 * u * (1 + u);
}

/// Delta_s(w) for the unit local direction w (|w.z| = mu; the sign of w.z is not used: the
/// caller names the side) of an interface located by `cell`, side 0 entering (eta_s > 1),
/// 1 exiting, from `delta` (dielectric_anisotropic_size values). Returns the albedo
/// difference, dimensionless.
template <std::floating_point T>
[[nodiscard]] inline T dielectric_anisotropic_delta(const float* delta, const dielectric_anisotropic_cell<T>& cell,
                                                    std::size_t side, T w_x, T w_y, T mu) noexcept {
    constexpr std::size_t nx = dielectric_anisotropic_mu_nodes;
    const T along = cell.swapped ? w_y : w_x, across = cell.swapped ? w_x : w_y;
    // At the pole (w_x = w_y = 0) the azimuth reads 0: Delta does not depend on it there.
    const auto x = albedo_grid_locate(std::sqrt(glm::clamp(std::abs(mu), T(0), T(1))), nx);
    const auto u = albedo_grid_locate(dielectric_anisotropic_u(std::atan2(std::abs(across), std::abs(along))),
                                      dielectric_anisotropic_azimuth_nodes);
    const spline_taps<T> wx(x.i, x.t, nx);
    T sum = 0;
    for (int a = 0; a < 4; ++a) {
        if (cell.e.weight[a] == T(0)) continue;
        for (int b = 0; b < 4; ++b) {
            if (cell.z.weight[b] == T(0)) continue;
            T along_y = 0;
            for (int c = 0; c < 4; ++c) {
                if (cell.y.weight[c] == T(0) || cell.y.node[c] == 0) continue; // y = 0 holds 0
                const float* row0 =
                    delta + dielectric_anisotropic_row_index(side, cell.e.node[a], cell.z.node[b], cell.y.node[c], u.i) * nx;
                const float* row1 = row0 + nx;
                T d0 = 0, d1 = 0;
                for (int k = 0; k < 4; ++k) {
                    d0 += wx.weight[k] * T(row0[wx.node[k]]);
                    d1 += wx.weight[k] * T(row1[wx.node[k]]);
                }
                along_y += cell.y.weight[c] * (d0 + u.t * (d1 - d0));
            }
            sum += cell.e.weight[a] * cell.z.weight[b] * along_y;
        }
    }
    return sum;
}

/// Delta_s on the correction's own (u, x) nodes for the interface located by `cell`, side s:
/// the lookup's blend over eta, ratio and roughness done once, out[i_u * nx + i_x]
/// (dielectric_anisotropic_azimuth_nodes x dielectric_anisotropic_mu_nodes values), so that
/// dielectric_anisotropic_delta at any w equals the Catmull-Rom spline in x of these values,
/// linear in u (for a caller that reads many views of one interface).
template <std::floating_point T>
inline void dielectric_anisotropic_delta_nodes(const float* delta, const dielectric_anisotropic_cell<T>& cell,
                                               std::size_t side, double* out) noexcept {
    constexpr std::size_t nx = dielectric_anisotropic_mu_nodes, nu = dielectric_anisotropic_azimuth_nodes;
    for (std::size_t k = 0; k < nu * nx; ++k) out[k] = 0;
    for (int a = 0; a < 4; ++a) {
        if (cell.e.weight[a] == T(0)) continue;
        for (int b = 0; b < 4; ++b) {
            if (cell.z.weight[b] == T(0)) continue;
            for (int c = 0; c < 4; ++c) {
                if (cell.y.weight[c] == T(0) || cell.y.node[c] == 0) continue; // y = 0 holds 0
                const double w = double(cell.e.weight[a]) * double(cell.z.weight[b]) * double(cell.y.weight[c]);
                const float* rows =
                    delta + dielectric_anisotropic_row_index(side, cell.e.node[a], cell.z.node[b], cell.y.node[c], 0) * nx;
                for (std::size_t k = 0; k < nu * nx; ++k) out[k] += w * double(rows[k]);
            }
        }
    }
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
/// `row_averages` (dielectric_anisotropic_row_average of every stored row): the rows'
/// averages R(u_i) blended with the weights the lookup gives their nodes (exact: the x axis
/// is the same for every row), then (2 / pi) integral_0^(pi/2) R(u(phi)) dphi =
/// integral_0^1 R(u) g'(u) du, g'(u) = (1 + 2 u) / 2, in closed form for R linear in u on
/// each cell. Dimensionless.
template <std::floating_point T>
[[nodiscard]] inline T dielectric_anisotropic_delta_average(const float* row_averages,
                                                            const dielectric_anisotropic_cell<T>& cell,
                                                            std::size_t side) noexcept {
    constexpr std::size_t nu = dielectric_anisotropic_azimuth_nodes;
    double r[nu] = {};
    for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b)
            for (int c = 0; c < 4; ++c) {
                const double w = double(cell.e.weight[a]) * double(cell.z.weight[b]) * double(cell.y.weight[c]);
                if (w == 0 || cell.y.node[c] == 0) continue;
                const float* row =
                    row_averages + dielectric_anisotropic_row_index(side, cell.e.node[a], cell.z.node[b], cell.y.node[c], 0);
                for (std::size_t i = 0; i < nu; ++i) r[i] += w * double(row[i]);
            }
    double sum = 0;
    for (std::size_t i = 0; i + 1 < nu; ++i) {
        const double u0 = double(i) / double(nu - 1), h = 1.0 / double(nu - 1);
        // integral over the cell of (r_i (1 - t) + r_i+1 t) (1 + 2 (u0 + h t)) / 2 h dt
        // = h / 2 (r_i ((1 + 2 u0) / 2 + h / 3) + r_i+1 ((1 + 2 u0) / 2 + 2 h / 3)).
        sum += 0.5 * h * (r[i] * (0.5 * (1 + 2 * u0) + h / 3) + r[i + 1] * (0.5 * (1 + 2 * u0) + 2 * h / 3));
    }
    return T(sum);
}

} // namespace shade::detail
