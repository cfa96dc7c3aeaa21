#pragma once
// The grid and the interpolation of the anisotropic correction to the microfacet albedo
// tables (shade/brdf/microfacet/albedo_table.hpp) that the multiple-scattering compensation
// for anisotropic distributions (shade::kulla_conty_anisotropic,
// shade/brdf/anisotropic_multiple_scattering.hpp) reads. The numbers are generated into
// shade/brdf/microfacet/detail/anisotropic_albedo_data.hpp by examples/albedo_tables.cpp
// (--anisotropic).
//
// An anisotropic lobe (roughness alpha_x along t, alpha_y along b) has a directional albedo
// with F = 1, E(w), that depends on the azimuth of w as well as on mu = n·w: the masking of w
// follows the roughness projected on w's azimuth (Heitz 2014, "Understanding the
// Masking-Shadowing Function in Microfacet-Based BRDFs", JCGT 3(2), eq. 80), the shadowing of
// the reflected directions the roughness of every azimuth they reach. No isotropic
// roughness reproduces it at every azimuth, so the difference is tabulated:
//
//     Delta(w) = E(w) - E_iso(mu, sqrt(alpha_x alpha_y)),
//
// E_iso being the isotropic table read at the geometric-mean roughness, with its
// cosine-weighted hemispherical average
//
//     Delta_avg = (1 / pi) integral over the hemisphere of Delta(w) (n·w) dw.
//
// Delta depends on four numbers. The lobe is mirror-symmetric about t and about b, and
// exchanging alpha_x and alpha_y exchanges the azimuths phi and pi/2 - phi, so the table
// holds alpha_x <= alpha_y only and a lookup with alpha_x > alpha_y reads it with the
// axes exchanged. With q = alpha_y / alpha_x >= 1 and phi the azimuth from the smoother
// axis, the four coordinates, each in [0, 1] with uniform nodes, are
//
//     x = sqrt(mu)                            nodes dense toward grazing, where E changes
//                                             fastest
//     u = ln(1 + (q^2 - 1) sin^2 phi) / ln(q^2)
//                                             the projected roughness alpha_phi of w's
//                                             azimuth (Heitz 2014, eq. 80: alpha_phi^2 =
//                                             alpha_x^2 (1 + (q^2 - 1) sin^2 phi)) on a log
//                                             scale from alpha_x (u = 0) to alpha_y (u = 1):
//                                             a strong anisotropy turns most of its
//                                             projected roughness within a few degrees of
//                                             the smoother axis, and u spreads those degrees
//     y = sqrt(sqrt(alpha_x alpha_y))         as the isotropic tables
//     r = ln(q) / ln(ratio_max)               the anisotropy, 0 for isotropic
//
// Delta is Catmull-Rom cubic (Catmull, Rom 1974) in x, y and r and linear in u: along x it
// follows the dip of E near mu ~ alpha, along r it bends (at normal incidence it is even in
// ln q), and linear interpolation there would be off by 1e-3 to 3e-3. Slices with
// r = 0 (isotropic: Delta = 0 by definition) or y = 0 (a mirror loses nothing) hold 0. For
// the average, each row (one u node of one slice) is stored with its exact cosine average
// over x; Delta_avg of a lobe blends those with the weights of its slices (exact, x being
// the same for every slice) and integrates the result over the azimuth by quadrature, so
// it is the average of the Delta the lobe reads, to the quadrature's accuracy, and the
// compensation stays normalised. Geometric-mean roughness above 1 reads y = 1; there the
// correction is approximate. Stored as float.
//
// Anisotropy beyond ratio_max, up to a 1-D rough surface (alpha_min -> 0, OpenPBR's
// specular_roughness_anisotropy 1), has a grid of its own, the strong-anisotropy grid: there
// the geometric mean tends to 0 whatever alpha_max, so neither it nor ln q can index the
// lobe. Its difference is taken from the isotropic table at a base roughness that stays
// finite,
//
//     Delta_strong(w) = E(w) - E_iso(mu, alpha_base),
//
// alpha_base the root mean square sqrt((alpha_x^2 + alpha_y^2) / 2) up to 0.7, bent smoothly
// below 1 above it (anisotropic_albedo_base_alpha; the isotropic table stops at alpha 1, and
// reading it at a clamped roughness would put a kink into Delta), with the coordinates
//
//     x = sqrt(mu)                                as above
//     u                                           w's azimuth phi in [0, pi/2] from the
//                                                 smoother axis, 2 phi / pi = g(u) =
//                                                 u (1 + u) / 2: denser near the smoother
//                                                 axis, where the projected roughness turns
//                                                 fastest
//     y = sqrt(alpha_max / sqrt 2)                alpha_max up to sqrt 2, the largest alpha
//                                                 of OpenPBR's roughness_to_alpha
//     z = sqrt(ratio_max alpha_min / alpha_max)   1 at ratio_max, 0 for a 1-D rough surface
//
// Catmull-Rom in x, y and z (along y and z a neighbour beyond an end extrapolated linearly:
// spline_taps of shade/brdf/microfacet/albedo_table.hpp),
// linear in u; Delta_strong_avg from the rows' cosine averages integrated over the azimuth exactly (linear in u, dphi = (pi / 4) (1 + 2 u)
// du). Each node holds its estimate plus strong_anisotropy_lift times 1 - E (E read slightly
// high: the compensation then errs below 1 rather than above). At q = ratio_max the two grids
// describe the same E to their accuracy and the lift. alpha_max above sqrt 2 reads y = 1.

#include <cmath>
#include <concepts>
#include <cstddef>

#include <glm/common.hpp>

#include <shade/brdf/microfacet/albedo_table.hpp>

namespace shade::detail {

/// Nodes along x = sqrt(mu) of the anisotropic correction tables.
inline constexpr std::size_t anisotropic_albedo_mu_nodes = 24;
/// Nodes along u, the azimuth coordinate.
inline constexpr std::size_t anisotropic_albedo_azimuth_nodes = 9;
/// Nodes along y = sqrt(sqrt(alpha_x alpha_y)).
inline constexpr std::size_t anisotropic_albedo_roughness_nodes = 16;
/// Nodes along r = ln(alpha_y / alpha_x) / ln(ratio_max).
inline constexpr std::size_t anisotropic_albedo_ratio_nodes = 10;
/// The largest anisotropy alpha_y / alpha_x the tables cover.
inline constexpr double anisotropic_albedo_ratio_max = 20;
/// Values per (r, y) node: one slice over (s, x).
inline constexpr std::size_t anisotropic_albedo_slice = anisotropic_albedo_mu_nodes * anisotropic_albedo_azimuth_nodes;
/// Values per table: slices stored by r, then y; within a slice, rows by s, columns by x.
inline constexpr std::size_t anisotropic_albedo_size =
    anisotropic_albedo_ratio_nodes * anisotropic_albedo_roughness_nodes * anisotropic_albedo_slice;
/// Row averages per table: one per (r, y, u) node.
inline constexpr std::size_t anisotropic_albedo_rows =
    anisotropic_albedo_ratio_nodes * anisotropic_albedo_roughness_nodes * anisotropic_albedo_azimuth_nodes;

/// Where a lobe with roughnesses (alpha_x, alpha_y) reads the correction tables: its
/// geometric-mean roughness, whether its axes are exchanged (alpha_x > alpha_y), its
/// anisotropy q = max / min roughness, and its cells along y and r. Computed once per lobe.
template <std::floating_point T>
struct anisotropic_albedo_cell {
    T alpha = 0;          ///< sqrt(alpha_x alpha_y), where the isotropic table is read
    bool swapped = false; ///< alpha_x > alpha_y: the axes are exchanged
    T q2_minus_1 = 0;     ///< q^2 - 1 (> 0)
    T inv_log_q2 = 0;     ///< 1 / ln(q^2)
    std::size_t j = 0;    ///< cell along y
    T ty = 0;             ///< fraction along y
    std::size_t k = 0;    ///< cell along r
    T tr = 0;             ///< fraction along r
};

/// The cell of roughnesses alpha_x != alpha_y, both > 0 and finite.
template <std::floating_point T>
[[nodiscard]] inline anisotropic_albedo_cell<T> anisotropic_albedo_locate(T alpha_x, T alpha_y) noexcept {
    anisotropic_albedo_cell<T> out;
    out.alpha = std::sqrt(alpha_x * alpha_y);
    out.swapped = alpha_x > alpha_y;
    const T q = out.swapped ? alpha_x / alpha_y : alpha_y / alpha_x;
    out.q2_minus_1 = (q - T(1)) * (q + T(1));
    out.inv_log_q2 = T(1) / (T(2) * std::log(q));
    const auto y = albedo_grid_locate(std::sqrt(out.alpha), anisotropic_albedo_roughness_nodes);
    const auto r = albedo_grid_locate(T(std::log(q) / std::log(anisotropic_albedo_ratio_max)), anisotropic_albedo_ratio_nodes);
    out.j = y.i;
    out.ty = y.t;
    out.k = r.i;
    out.tr = r.t;
    return out;
}

/// The azimuth coordinate u of shade/brdf/microfacet/anisotropic_albedo_table.hpp for
/// s = sin^2 of the azimuth from the smoother axis, in [0, 1]:
/// ln(1 + (q^2 - 1) s) / ln(q^2).
template <std::floating_point T>
[[nodiscard]] inline T anisotropic_albedo_u(const anisotropic_albedo_cell<T>& cell, T s) noexcept {
    return std::log1p(cell.q2_minus_1 * s) * cell.inv_log_q2;
}

/// Node index i + a - 1 of an n-node axis, clamped to [0, n - 1] (the edge node repeated).
[[nodiscard]] constexpr std::size_t anisotropic_albedo_node(std::size_t i, int a, std::size_t n) noexcept {
    const std::ptrdiff_t m = std::ptrdiff_t(i) + a - 1;
    return m < 0 ? 0 : (std::size_t(m) > n - 1 ? n - 1 : std::size_t(m));
}

/// One slice's value between two stored rows of nx values (row0 and the row after it, at
/// azimuth nodes i and i + 1): each row Catmull-Rom in x (weights wx on the nodes `column`),
/// then linear at the fraction t between the rows.
template <std::floating_point T>
[[nodiscard]] inline T anisotropic_albedo_row_pair(const float* row0, std::size_t nx, const std::size_t (&column)[4],
                                                   const catmull_rom_weights<T>& wx, T t) noexcept {
    const float* row1 = row0 + nx;
    T d0 = 0, d1 = 0;
    for (int c = 0; c < 4; ++c) {
        d0 += wx.w[c] * T(row0[column[c]]);
        d1 += wx.w[c] * T(row1[column[c]]);
    }
    return d0 + t * (d1 - d0);
}

/// Delta(w) of shade/brdf/microfacet/anisotropic_albedo_table.hpp for the unit local
/// direction w (w.z = mu in [0, 1]) of a lobe located by `cell`: Catmull-Rom in x and linear
/// in u within a slice, Catmull-Rom across the 4 x 4 slices around (y, r), in the table `delta`
/// (anisotropic_albedo_size values). Returns the albedo difference, dimensionless.
template <std::floating_point T>
[[nodiscard]] inline T anisotropic_albedo_delta(const float* delta, const anisotropic_albedo_cell<T>& cell,
                                                T w_x, T w_y, T mu) noexcept {
    constexpr std::size_t nx = anisotropic_albedo_mu_nodes;
    constexpr std::size_t ny = anisotropic_albedo_roughness_nodes;
    constexpr std::size_t nr = anisotropic_albedo_ratio_nodes;
    const T sin2 = w_x * w_x + w_y * w_y;
    // s from the smoother axis; at the pole (sin2 = 0) any value: Delta does not depend on
    // it there.
    const T across = cell.swapped ? w_x * w_x : w_y * w_y;
    const T s = sin2 > T(0) ? glm::min(across / sin2, T(1)) : T(0);
    const auto x = albedo_grid_locate(std::sqrt(glm::clamp(mu, T(0), T(1))), nx);
    const auto u = albedo_grid_locate(anisotropic_albedo_u(cell, s), anisotropic_albedo_azimuth_nodes);
    const catmull_rom_weights<T> wx(x.t), wy(cell.ty), wr(cell.tr);
    std::size_t column[4];
    for (int c = 0; c < 4; ++c) column[c] = anisotropic_albedo_node(x.i, c, nx);
    T sum = 0;
    for (int a = 0; a < 4; ++a) {
        const std::size_t k = anisotropic_albedo_node(cell.k, a, nr);
        T along_y = 0;
        for (int b = 0; b < 4; ++b) {
            const std::size_t j = anisotropic_albedo_node(cell.j, b, ny);
            const float* row0 = delta + (k * ny + j) * anisotropic_albedo_slice + u.i * nx;
            along_y += wy.w[b] * anisotropic_albedo_row_pair(row0, nx, column, wx, u.t);
        }
        sum += wr.w[a] * along_y;
    }
    return sum;
}

/// The cosine average 2 integral_0^1 Delta mu dmu = 4 integral_0^1 Delta(x) x^3 dx of one
/// row of x nodes, Catmull-Rom in x as anisotropic_albedo_delta reads it: 5-point
/// Gauss-Legendre per cell (Abramowitz, Stegun 1964, "Handbook of Mathematical Functions",
/// 25.4.29), exact there (a polynomial of degree 6). For the generator and the tests.
[[nodiscard]] inline double anisotropic_albedo_row_average(const float* row) noexcept {
    constexpr std::size_t nx = anisotropic_albedo_mu_nodes;
    constexpr double node[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831,
                                0.9061798459386640};
    constexpr double weight[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                                  0.4786286704993665, 0.2369268850561891};
    double sum = 0;
    for (std::size_t c = 0; c + 1 < nx; ++c) {
        for (int q = 0; q < 5; ++q) {
            const double t = 0.5 * (1.0 + node[q]);
            const double x = (double(c) + t) / double(nx - 1);
            const catmull_rom_weights<double> w(t);
            double d = 0;
            for (int a = 0; a < 4; ++a) d += w.w[a] * double(row[anisotropic_albedo_node(c, a, nx)]);
            sum += weight[q] * (0.5 / double(nx - 1)) * 4.0 * d * x * x * x;
        }
    }
    return sum;
}

/// Delta_avg, the cosine-weighted hemispherical average of anisotropic_albedo_delta for the
/// lobe located by `cell`, from the table `row_averages` (anisotropic_albedo_row_average of
/// every row of `delta`, ratio x roughness x azimuth nodes): the rows' averages R(u_i)
/// combined with the weights anisotropic_albedo_delta gives their slices (R is exact, the
/// x axis being the same for every slice), then (2 / pi) integral_0^(pi/2) R(u(phi)) dphi
/// with R linear in u between nodes, by 5-point Gauss-Legendre in phi on each u cell.
/// Returns the average albedo difference, dimensionless.
template <std::floating_point T>
[[nodiscard]] inline T anisotropic_albedo_delta_average(const float* row_averages,
                                                        const anisotropic_albedo_cell<T>& cell) noexcept {
    constexpr std::size_t ny = anisotropic_albedo_roughness_nodes;
    constexpr std::size_t nr = anisotropic_albedo_ratio_nodes;
    constexpr std::size_t nu = anisotropic_albedo_azimuth_nodes;
    constexpr double node[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831,
                                0.9061798459386640};
    constexpr double weight[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                                  0.4786286704993665, 0.2369268850561891};
    const catmull_rom_weights<T> wy(cell.ty), wr(cell.tr);
    double r[nu] = {};
    for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b) {
            const std::size_t k = anisotropic_albedo_node(cell.k, a, nr), j = anisotropic_albedo_node(cell.j, b, ny);
            const float* row = row_averages + (k * ny + j) * nu;
            for (std::size_t i = 0; i < nu; ++i) r[i] += double(wr.w[a]) * double(wy.w[b]) * double(row[i]);
        }
    // The azimuth of u: s = (exp(u ln q^2) - 1) / (q^2 - 1), phi = asin(sqrt(s)).
    const double log_q2 = 1.0 / double(cell.inv_log_q2), q2m1 = double(cell.q2_minus_1);
    const auto phi_of = [&](double u) { return std::asin(std::sqrt(glm::min(std::expm1(u * log_q2) / q2m1, 1.0))); };
    double sum = 0;
    double phi0 = 0;
    for (std::size_t i = 0; i + 1 < nu; ++i) {
        const double u0 = double(i) / double(nu - 1);
        const double phi1 = i + 2 == nu ? 1.5707963267948966 : phi_of(double(i + 1) / double(nu - 1));
        const double half = 0.5 * (phi1 - phi0);
        for (int q = 0; q < 5; ++q) {
            const double phi = phi0 + half * (1.0 + node[q]);
            const double sn = std::sin(phi);
            const double u = std::log1p(q2m1 * sn * sn) / log_q2;
            const double t = (u - u0) * double(nu - 1);
            sum += weight[q] * half * (r[i] + t * (r[i + 1] - r[i]));
        }
        phi0 = phi1;
    }
    return T(sum / 1.5707963267948966);
}

/// Nodes along x = sqrt(mu) of the strong-anisotropy tables (as the first grid's, so that
/// anisotropic_albedo_row_average serves both).
inline constexpr std::size_t strong_anisotropy_mu_nodes = anisotropic_albedo_mu_nodes;
/// Nodes along u (2 phi / pi = u (1 + u) / 2) of the strong-anisotropy tables.
inline constexpr std::size_t strong_anisotropy_azimuth_nodes = 13;
/// Nodes along y = sqrt(alpha_max / sqrt 2) of the strong-anisotropy tables.
inline constexpr std::size_t strong_anisotropy_roughness_nodes = 16;
/// Nodes along z = sqrt(ratio_max alpha_min / alpha_max) of the strong-anisotropy tables.
inline constexpr std::size_t strong_anisotropy_ratio_nodes = 5;
/// The largest alpha_max the strong-anisotropy y axis reaches (OpenPBR's largest alpha).
inline constexpr double strong_anisotropy_alpha_top = 1.4142135623730951;
/// Values per (z, y) node: one slice over (u, x).
inline constexpr std::size_t strong_anisotropy_slice = strong_anisotropy_mu_nodes * strong_anisotropy_azimuth_nodes;
/// Values per table: slices stored by z, then y; within a slice, rows by u, columns by x.
inline constexpr std::size_t strong_anisotropy_size =
    strong_anisotropy_ratio_nodes * strong_anisotropy_roughness_nodes * strong_anisotropy_slice;
/// Row averages per table: one per (z, y, u) node.
inline constexpr std::size_t strong_anisotropy_rows =
    strong_anisotropy_ratio_nodes * strong_anisotropy_roughness_nodes * strong_anisotropy_azimuth_nodes;

/// What every strong-anisotropy node holds above its estimate of Delta_strong, as a share of
/// the energy the lobe loses there: the lift is strong_anisotropy_lift (1 - E) for the node's
/// estimate E. E is then read a little high, so that the compensated albedo 1 + E_true - E_read
/// errs below 1 rather than above (the interpolation's own error reaches 1e-3 to 2e-3 between
/// the nodes of rough lobes), and never above 1 where E is near 1 (a lift that carried E + Delta
/// past 1 would be clamped in E(w) but not in E_avg, and the compensation would gain energy).
inline constexpr double strong_anisotropy_lift = 5e-3;

/// Where the strong-anisotropy base roughness starts to bend away from the root mean square.
inline constexpr double anisotropic_albedo_base_knee = 0.7;

/// The roughness the isotropic table is read at under the strong-anisotropy correction: the
/// root mean square r = sqrt((alpha_x^2 + alpha_y^2) / 2) up to the knee a, above it
/// 1 - (1 - a) exp(-(r - a) / (1 - a)), which meets r with its slope at a and stays below 1
/// (the isotropic table's largest alpha) for every r.
template <std::floating_point T>
[[nodiscard]] inline T anisotropic_albedo_base_alpha(T alpha_x, T alpha_y) noexcept {
    const T r = std::sqrt(T(0.5) * (alpha_x * alpha_x + alpha_y * alpha_y));
    const T a = T(anisotropic_albedo_base_knee);
    return r <= a ? r : T(1) - (T(1) - a) * std::exp(-(r - a) / (T(1) - a));
}

/// The azimuth phi in [0, pi/2] from the smoother axis of the strong-anisotropy grid's
/// node u in [0, 1]: phi = (pi / 2) u (1 + u) / 2.
[[nodiscard]] constexpr double strong_anisotropy_phi(double u) noexcept {
    return 1.5707963267948966 * u * (1 + u) / 2;
}

/// Where a lobe with roughnesses alpha_x, alpha_y (alpha_max > ratio_max alpha_min) reads
/// the strong-anisotropy tables: its base roughness, which axis is the smoother, and its
/// cells along y and z. Computed once per lobe.
template <std::floating_point T>
struct strong_anisotropy_cell {
    T alpha_base = 0;   ///< anisotropic_albedo_base_alpha, where the isotropic table is read
    bool y_smoother = false; ///< alpha_y < alpha_x: the azimuth is measured from b
    std::size_t j = 0;  ///< cell along y
    T ty = 0;           ///< fraction along y
    std::size_t k = 0;  ///< cell along z
    T tz = 0;           ///< fraction along z
};

/// The strong-anisotropy cell of roughnesses alpha_x, alpha_y >= 0, not both 0, finite.
template <std::floating_point T>
[[nodiscard]] inline strong_anisotropy_cell<T> strong_anisotropy_locate(T alpha_x, T alpha_y) noexcept {
    strong_anisotropy_cell<T> out;
    out.alpha_base = anisotropic_albedo_base_alpha(alpha_x, alpha_y);
    out.y_smoother = alpha_y < alpha_x;
    const T alpha_max = glm::max(alpha_x, alpha_y), alpha_min = glm::min(alpha_x, alpha_y);
    const T y = std::sqrt(glm::min(alpha_max / T(strong_anisotropy_alpha_top), T(1)));
    const T z = std::sqrt(glm::min(T(anisotropic_albedo_ratio_max) * alpha_min / alpha_max, T(1)));
    const auto cy = albedo_grid_locate(y, strong_anisotropy_roughness_nodes);
    const auto cz = albedo_grid_locate(z, strong_anisotropy_ratio_nodes);
    out.j = cy.i;
    out.ty = cy.t;
    out.k = cz.i;
    out.tz = cz.t;
    return out;
}

/// Delta_strong(w) for the unit local direction w (w.z = mu in [0, 1]) of a lobe located by
/// `cell`: Catmull-Rom in x (the first grid's) and in y and z (spline_taps), linear in
/// u, in the table `delta`
/// (strong_anisotropy_size values). Returns the albedo difference, dimensionless.
template <std::floating_point T>
[[nodiscard]] inline T strong_anisotropy_delta(const float* delta, const strong_anisotropy_cell<T>& cell, T w_x,
                                               T w_y, T mu) noexcept {
    constexpr std::size_t nx = strong_anisotropy_mu_nodes, nu = strong_anisotropy_azimuth_nodes;
    constexpr std::size_t ny = strong_anisotropy_roughness_nodes, nz = strong_anisotropy_ratio_nodes;
    // The azimuth from the smoother axis, then u = (sqrt(1 + 8 p) - 1) / 2 for p = 2 phi / pi.
    const T along = std::abs(cell.y_smoother ? w_y : w_x), across = std::abs(cell.y_smoother ? w_x : w_y);
    const T p = along > T(0) || across > T(0) ? std::atan2(across, along) * T(0.63661977236758134) : T(0);
    const T u_coordinate = T(0.5) * (std::sqrt(T(1) + T(8) * glm::min(p, T(1))) - T(1));
    const auto x = albedo_grid_locate(std::sqrt(glm::clamp(mu, T(0), T(1))), nx);
    const auto u = albedo_grid_locate(u_coordinate, nu);
    const catmull_rom_weights<T> wx(x.t);
    const spline_taps<T> wy(cell.j, cell.ty, ny), wz(cell.k, cell.tz, nz);
    std::size_t column[4];
    for (int c = 0; c < 4; ++c) column[c] = anisotropic_albedo_node(x.i, c, nx);
    T sum = 0;
    for (int a = 0; a < 4; ++a) {
        if (wz.weight[a] == T(0)) continue;
        const std::size_t k = wz.node[a];
        T along_y = 0;
        for (int b = 0; b < 4; ++b) {
            if (wy.weight[b] == T(0)) continue;
            const std::size_t j = wy.node[b];
            const float* row0 = delta + (k * ny + j) * strong_anisotropy_slice + u.i * nx;
            along_y += wy.weight[b] * anisotropic_albedo_row_pair(row0, nx, column, wx, u.t);
        }
        sum += wz.weight[a] * along_y;
    }
    return sum;
}

/// Delta_strong_avg, the cosine-weighted hemispherical average of strong_anisotropy_delta
/// for the lobe located by `cell`, from the table `row_averages` (anisotropic_albedo_row_average
/// of every row of the delta table, z x y x u nodes): the rows' averages R(u_i) combined with
/// the weights strong_anisotropy_delta gives their slices, then (2 / pi) integral_0^(pi/2)
/// R dphi = integral_0^1 R(u) (1 + 2 u) / 2 du with R linear in u on each cell (2-point
/// Gauss-Legendre, exact for that quadratic). Returns the average albedo difference,
/// dimensionless.
template <std::floating_point T>
[[nodiscard]] inline T strong_anisotropy_delta_average(const float* row_averages,
                                                       const strong_anisotropy_cell<T>& cell) noexcept {
    constexpr std::size_t ny = strong_anisotropy_roughness_nodes, nz = strong_anisotropy_ratio_nodes;
    constexpr std::size_t nu = strong_anisotropy_azimuth_nodes;
    const spline_taps<T> wy(cell.j, cell.ty, ny), wz(cell.k, cell.tz, nz);
    double r[nu] = {};
    for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b) {
            const float* row = row_averages + (wz.node[a] * ny + wy.node[b]) * nu;
            for (std::size_t i = 0; i < nu; ++i) r[i] += double(wz.weight[a]) * double(wy.weight[b]) * double(row[i]);
        }
    constexpr double g = 0.28867513459481287; // 1 / (2 sqrt 3): the 2-point Gauss nodes at 1/2 -+ g
    const double h = 1.0 / double(nu - 1);
    double sum = 0;
    const double fractions[2] = {0.5 - g, 0.5 + g};
    for (std::size_t i = 0; i + 1 < nu; ++i)
        for (const double t : fractions) {
            const double u = (double(i) + t) * h;
            sum += 0.5 * h * (r[i] + t * (r[i + 1] - r[i])) * 0.5 * (1 + 2 * u);
        }
    return T(sum);
}

} // namespace shade::detail
