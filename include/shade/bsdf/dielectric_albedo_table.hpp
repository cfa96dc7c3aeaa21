#pragma once
// The grid and the interpolation of the tabulated albedos of shade::rough_dielectric that
// its energy compensation (shade/bsdf/compensated_rough_dielectric.hpp) reads. The numbers
// are generated into shade/bsdf/detail/dielectric_albedo_data.hpp by
//
//   examples/dielectric_albedo_tables --out include/shade/bsdf/detail/dielectric_albedo_data.hpp
//
// (GGX), and for Beckmann (its m read as alpha) into beckmann_dielectric_albedo_data.hpp by
//
//   examples/dielectric_albedo_tables --beckmann --strata 256 --envelope 64 --envelope-margin 0.0003 --envelope-view-steps 4 --out include/shade/bsdf/detail/beckmann_dielectric_albedo_data.hpp
//
// and their continuations above eta_hat 3 (dielectric_albedo_beyond_grid) into
// dielectric_albedo_beyond_data.hpp and beckmann_dielectric_albedo_beyond_data.hpp by
//
//   examples/dielectric_albedo_tables --beyond --strata 256 --out include/shade/bsdf/detail/dielectric_albedo_beyond_data.hpp
//   examples/dielectric_albedo_tables --beyond --beckmann --strata 256 --out include/shade/bsdf/detail/beckmann_dielectric_albedo_beyond_data.hpp
//
// The GGX table holds point values (each node an estimate of E there). The Beckmann table
// holds an upper envelope of E: its nodes raised until the interpolated table is at least a
// fresh estimate of E plus 3e-4 at the middle of every cell edge, face and interior, and at
// the quarters of every cell along the view coordinate, with mu >= 0.05
// (what the compensation needs: its R + T is 1 + E - E_table, so a table that errs high
// keeps R + T at or below 1 where interpolation between point values would err low). Its
// header states by how much the nodes were raised.
//
// A table holds, for a view cosine mu = |n·v|, a roughness alpha and the relative index
// eta_s = n_far / n_v of the side v is on, the total albedo of the single-scattering rough
// dielectric in importance mode (the energy that arrives along v and leaves, reflected
// plus transmitted; no 1/eta^2 factor),
//
//     E(mu, alpha, eta_s) = integral over the sphere of f_importance(l, v) |n·l| dl = R + T,
//
// and its cosine-weighted average over mu, E_avg(alpha, eta_s) = 2 integral_0^1 E mu dmu,
// integrated from the interpolated table when it is read (Kulla, Conty 2017, "Revisiting Physically Based Shading at Imageworks", SIGGRAPH course
// "Physically Based Shading in Theory and Practice", the dielectric slides: one table for
// light entering the denser medium, one for light leaving it; unnumbered). A lossless
// interface loses energy only through masking, so E is smooth in all three variables.
//
// Grid: for each side (entering, eta_s > 1; exiting, eta_s < 1), nodes in
//   * a view coordinate (dielectric_albedo_view), uniform (dielectric_albedo_mu_nodes): on
//     the entering side the c of shade/brdf/microfacet/albedo_table.hpp, c = (s + sqrt(mu)) / 2
//     with s = mu / (mu + alpha (1 - mu)); on the exiting side one that puts the critical
//     angle of total internal reflection on 0.5;
//   * y = sqrt(alpha), uniform, alpha at least 1e-4 (dielectric_albedo_alpha_nodes; 21 for
//     the Beckmann table, dielectric_beckmann_albedo_grid);
//   * x = log(eta_hat - 1), eta_hat = max(eta_s, 1 / eta_s) in [1.05, 3], uniform
//     (dielectric_albedo_eta_nodes): E changes fastest near eta_hat = 1 (seen from the
//     denser side, grazing views lose energy fastest as eta_hat falls toward 1), so the
//     nodes crowd there.
// E is interpolated by Catmull-Rom splines along the view coordinate and y and linearly
// along x. Lookups clamp alpha to [1e-4, 1] and eta_hat to [1.05, 3]: outside,
// the nearest end is read; above 3 compensated_rough_dielectric reads a continuation table
// instead (dielectric_albedo_beyond_grid). The accuracy of each table is stated in the generated header.
// Layout: index ((side * eta_nodes + k) * alpha_nodes + j) * mu_nodes + i; side 0 entering.
//
// The same code reads the reflection table of shade/bsdf/dielectric_reflection_albedo.hpp on
// its own grid (dielectric_reflection_albedo_grid): 33 view nodes, eta_hat in [1.001, 3],
// a Catmull-Rom spline along x too, and view coordinates that also resolve the Fresnel
// reflectance and, on the exiting side, the critical angle (dielectric_albedo_view,
// near_critical).

#include <cmath>
#include <concepts>
#include <cstddef>

#include <glm/common.hpp>

#include <shade/brdf/fresnel.hpp>
#include <shade/brdf/microfacet/albedo_table.hpp>
#include <shade/core/math.hpp>
#include <shade/core/quadrature.hpp>

namespace shade::detail {

/// Nodes of the dielectric albedo tables along the view coordinate c.
inline constexpr std::size_t dielectric_albedo_mu_nodes = 25;
/// Nodes along sqrt(alpha).
inline constexpr std::size_t dielectric_albedo_alpha_nodes = 16;
/// Nodes along x = log(eta_hat - 1).
inline constexpr std::size_t dielectric_albedo_eta_nodes = 12;
/// The smallest eta_hat = max(eta_s, 1 / eta_s) of the grid.
inline constexpr double dielectric_albedo_eta_min = 1.05;
/// The largest eta_hat of the grid.
inline constexpr double dielectric_albedo_eta_max = 3.0;

/// The coordinate x = log(eta_hat - 1) of eta_hat at its ends.
inline constexpr double dielectric_albedo_x_min = -2.995732273553991; // log(0.05)
inline constexpr double dielectric_albedo_x_max = 0.6931471805599453; // log(2)

/// The sizes and the eta range of a dielectric albedo table (two sides). The defaults are
/// the grid of the total-albedo tables; the reflection table
/// (shade/bsdf/dielectric_reflection_albedo.hpp) reaches closer to eta_hat = 1 and is
/// interpolated by a spline along x as well.
struct dielectric_albedo_grid {
    std::size_t mu_nodes = dielectric_albedo_mu_nodes;
    std::size_t alpha_nodes = dielectric_albedo_alpha_nodes;
    std::size_t eta_nodes = dielectric_albedo_eta_nodes;
    double eta_min = dielectric_albedo_eta_min; ///< the smallest eta_hat, 1 + exp(x_min)
    double eta_max = dielectric_albedo_eta_max; ///< the largest eta_hat, 1 + exp(x_max)
    double x_min = dielectric_albedo_x_min;     ///< log(eta_min - 1)
    double x_max = dielectric_albedo_x_max;     ///< log(eta_max - 1)
    bool eta_spline = false;                    ///< Catmull-Rom along x (else linear)
    bool near_critical = false;                 ///< the exiting side's view coordinate resolves
                                                ///< the critical angle (dielectric_albedo_view)

    /// Floats in the E table: 2 sides x eta x alpha x mu nodes.
    [[nodiscard]] constexpr std::size_t size() const noexcept { return 2 * eta_nodes * alpha_nodes * mu_nodes; }
    /// The offset of row (side, k, j) (side 0 entering, k the eta node, j the alpha node).
    [[nodiscard]] constexpr std::size_t row(std::size_t side, std::size_t k, std::size_t j) const noexcept {
        return ((side * eta_nodes + k) * alpha_nodes + j) * mu_nodes;
    }
};

/// The grid of the reflection table (shade/bsdf/dielectric_reflection_albedo.hpp): 33 view
/// nodes, the default alpha nodes, and 20 nodes along x = log(eta_hat - 1) from log(1e-3) to
/// log(2) (eta_hat in [1.001, 3]) with a Catmull-Rom spline along x: the reflectance falls
/// toward 0 as eta_hat nears 1, steeply in x, where the total albedo stays near 1. On the
/// exiting side the view coordinate crowds its nodes about the critical angle, where the
/// reflectance steps down from 1 (dielectric_albedo_view, near_critical).
inline constexpr dielectric_albedo_grid dielectric_reflection_albedo_grid{
    33, dielectric_albedo_alpha_nodes, 20, 1.001, 3.0,
    -6.907755278982137, // log(1e-3)
    0.6931471805599453, // log(2)
    true, true};

/// The grid of the Beckmann total-albedo table (beckmann_dielectric_albedo_data.hpp), which
/// compensated_rough_dielectric over Beckmann and the generator's --beckmann read: the
/// default grid with 21 nodes along sqrt(alpha) instead of 16. Seen from the denser side
/// below the critical angle at small eta_hat, E stays 1 (every microfacet reflects totally)
/// up to a roughness and then falls steeply (at eta_hat 1.05, mu 0.2: 0.9997 at m 0.04,
/// 0.9874 at m 0.06, 0.9480 at m 0.08), a bend that the spline through 16 nodes misses by
/// up to 4.4e-3 and the one through 21 by up to 1.2e-3 (docs/properties.md).
inline constexpr dielectric_albedo_grid dielectric_beckmann_albedo_grid{
    dielectric_albedo_mu_nodes, 21, dielectric_albedo_eta_nodes, dielectric_albedo_eta_min,
    dielectric_albedo_eta_max, dielectric_albedo_x_min, dielectric_albedo_x_max, false, false};

/// The grids of the dense-index continuations of the two total-albedo tables
/// (dielectric_albedo_beyond_data.hpp), which compensated_rough_dielectric reads where
/// eta_hat lies above 3, the main tables' end (specular_ior above 3 in OpenPBR): the same
/// view and roughness nodes as the table continued (16 or 21 along sqrt(alpha)), and 12
/// nodes along x = log(eta_hat - 1) from log 2 to log 999 (eta_hat from 3 to 1000) with a
/// Catmull-Rom spline along x. E keeps changing up there (at normal incidence and alpha 1
/// from 0.73 at eta_hat 3 to 0.49 at 10, toward the F = 1 lobe's 0.31), so reading the
/// main table's end instead errs by tenths. Above 1000 the end is read (F0 > 0.996).
inline constexpr dielectric_albedo_grid dielectric_albedo_beyond_grid{
    dielectric_albedo_mu_nodes, dielectric_albedo_alpha_nodes, 12, 3.0, 1000.0,
    0.6931471805599453, // log(2)
    6.906754778648554,  // log(999)
    true, false};

/// The Beckmann table's continuation (see dielectric_albedo_beyond_grid): 21 nodes along
/// sqrt(alpha), as dielectric_beckmann_albedo_grid.
inline constexpr dielectric_albedo_grid dielectric_beckmann_albedo_beyond_grid{
    dielectric_albedo_mu_nodes, 21, 12, 3.0, 1000.0, 0.6931471805599453, 6.906754778648554, true, false};

/// What compensated_rough_dielectric adds to E read from the continuations: they hold point
/// values, whose interpolation errs either way by up to about 2e-3 where mu >= 0.05 (their
/// headers state it), and the compensation's R + T is 1 + E_true - E_read, so reading E this
/// much high keeps R + T at or below 1 + 1e-3 there, at the price of reading up to 2e-3 low
/// where the interpolation is exact.
inline constexpr double dielectric_albedo_beyond_lift = 2e-3;

/// eta_hat at node k of grid g: 1 + exp(x_k), x uniform from g.x_min to g.x_max.
[[nodiscard]] inline double dielectric_albedo_eta(const dielectric_albedo_grid& g, std::size_t k) noexcept {
    return 1.0 + std::exp(g.x_min + double(k) / double(g.eta_nodes - 1) * (g.x_max - g.x_min));
}

/// eta_hat at node k of an n-node axis of the default range: x uniform from log(0.05) to log(2).
[[nodiscard]] inline double dielectric_albedo_eta(std::size_t k, std::size_t n) noexcept {
    dielectric_albedo_grid g{};
    g.eta_nodes = n;
    return dielectric_albedo_eta(g, k);
}

/// The coordinate in [0, 1] of eta_hat (clamped to [g.eta_min, g.eta_max]) on grid g's
/// log(eta_hat - 1) axis.
template <std::floating_point T>
[[nodiscard]] inline T dielectric_albedo_eta_coordinate(const dielectric_albedo_grid& g, T eta_hat) noexcept {
    const double e = glm::clamp(double(eta_hat), g.eta_min, g.eta_max);
    return T((std::log(e - 1.0) - g.x_min) / (g.x_max - g.x_min));
}

/// The coordinate in [0, 1] of eta_hat (clamped to [1.05, 3]) on the default log(eta_hat - 1) axis.
template <std::floating_point T>
[[nodiscard]] inline T dielectric_albedo_eta_coordinate(T eta_hat) noexcept {
    return dielectric_albedo_eta_coordinate(dielectric_albedo_grid{}, eta_hat);
}

/// The view coordinate of (mu, alpha, eta_hat) on a side's table, in [0, 1], increasing in
/// mu. On the entering side it is c = albedo_grid_c(mu, alpha) of the conductor tables. On
/// the exiting side total internal reflection sets in below mu_c = sqrt(1 - 1 / eta_hat^2),
/// where E has a dip whose place moves with eta; the coordinate puts mu_c on 0.5 at every
/// eta, so the dip stays in the same column of every eta block (a table with an odd number
/// of view nodes has a node there):
///
///     below mu_c:  (2 s(mu) / s(mu_c) + sqrt(mu / mu_c) + mu / mu_c) / 8,   s = mu / (mu + alpha (1 - mu))
///     above mu_c:  1/2 + (mu - mu_c) / (2 (1 - mu_c))
///
/// s resolves the masking near grazing at small alpha, sqrt(mu / mu_c) the steep fall of E
/// toward grazing at large alpha, mu / mu_c spreads the rest evenly up to mu_c.
///
/// With near_critical (the reflection table), the coordinate also follows the Fresnel
/// reflectance F(mu) itself, which the reflectance R equals as alpha -> 0: through
/// q(mu) = (1 - F(mu, eta_s)) / (1 - F(1, eta_s)), increasing from 0 (grazing, or the
/// critical angle) to 1 (normal view), F being monotonic in mu. Near eta_hat = 1, F falls
/// from 1 within a small distance of grazing (entering) or of the critical angle
/// (exiting), a scale that neither c nor the pieces above resolve. On the exiting side R
/// steps from 1 (total internal reflection) down to F across the critical angle, over a
/// width of about alpha in mu (the spread of the microfacet normals about n), and just above
/// mu_c, F falls as 1 - O(sqrt(mu - mu_c)) (Born, Wolf 1999, "Principles of Optics", 7th ed.,
/// sec. 1.5.4); with r(d) = d / (d + alpha), d the distance from mu_c:
///
///     entering:    (2 c + q(mu)) / 3
///     below mu_c:  (t_below(mu) + 1/2 - r(mu_c - mu) / (2 r(mu_c))) / 2
///     above mu_c:  1/2 + (sqrt(d / (1 - mu_c)) + r(d) / r(1 - mu_c) + q(mu)) / 6,   d = mu - mu_c
///
/// F(mu, eta_s), eta_s = eta_hat on side 0 and 1 / eta_hat on side 1, comes from the
/// callable fresnel_at(), called only where the coordinate reads it (for a caller that has
/// F at mu already); dielectric_albedo_view computes it.
template <std::floating_point T, class FresnelAt>
[[nodiscard]] inline T dielectric_albedo_view_with(T mu, T alpha, T eta_hat, std::size_t side, bool near_critical,
                                                   FresnelAt&& fresnel_at) noexcept {
    // q(mu): 1 - F normalised to [0, 1] (F(1) = f0 < 1 for the eta_hat of the grids).
    const auto q = [eta_hat, &fresnel_at](T) {
        const T f0 = sqr((eta_hat - T(1)) / (eta_hat + T(1)));
        return glm::clamp((T(1) - T(fresnel_at())) / (T(1) - f0), T(0), T(1));
    };
    if (side == 0) return near_critical ? (T(2) * albedo_grid_c(mu, alpha) + q(mu)) / T(3) : albedo_grid_c(mu, alpha);
    const T mu_c = std::sqrt(glm::max(T(1) - T(1) / (eta_hat * eta_hat), T(0)));
    const auto r = [alpha](T d) { return d / (d + alpha); };
    if (mu >= mu_c) {
        const T d = mu - mu_c, span = T(1) - mu_c;
        if (!near_critical) return T(0.5) + T(0.5) * d / span;
        return T(0.5) + (std::sqrt(d / span) + r(d) / r(span) + q(mu)) / T(6);
    }
    const auto s = [alpha](T m) { return m / (m + alpha * (T(1) - m)); };
    const T x = mu / mu_c;
    const T below = (T(2) * s(mu) / s(mu_c) + std::sqrt(x) + x) / T(8);
    if (!near_critical) return below;
    return T(0.5) * (below + T(0.5) - T(0.5) * r(mu_c - mu) / r(mu_c));
}

/// The view coordinate of dielectric_albedo_view_with, F_dielectric(mu, eta_s) computed
/// where it is read.
template <std::floating_point T>
[[nodiscard]] inline T dielectric_albedo_view(T mu, T alpha, T eta_hat, std::size_t side,
                                              bool near_critical = false) noexcept {
    const T eta_s = side == 0 ? eta_hat : T(1) / eta_hat;
    return dielectric_albedo_view_with(mu, alpha, eta_hat, side, near_critical,
                                       [mu, eta_s] { return F_dielectric(mu, eta_s); });
}

/// The view cosine at coordinate t in [0, 1] (the inverse of dielectric_albedo_view), by
/// bisection to double precision (for the generator and the tests).
[[nodiscard]] inline double dielectric_albedo_view_mu(double t, double alpha, double eta_hat, std::size_t side,
                                                     bool near_critical = false) noexcept {
    return bisect_increasing(
        [=](double mu) { return dielectric_albedo_view(mu, alpha, eta_hat, side, near_critical); }, t);
}

/// Where a lookup reads: the side, and the cells and fractions along alpha and eta.
template <std::floating_point T>
struct dielectric_albedo_cell {
    std::size_t side = 0;       ///< 0 entering (eta_s > 1), 1 exiting (eta_s < 1)
    albedo_grid_cell<T> alpha{}; ///< cell along sqrt(alpha)
    albedo_grid_cell<T> eta{};   ///< cell along x = log(eta_hat - 1)
    T alpha_clamped = 1;         ///< alpha clamped to [1e-4, 1] (for the view coordinate)
    T eta_clamped = 1;           ///< eta_hat clamped to the grid's range (for the view coordinate)
};

/// The cell of (alpha, eta_s): eta_s > 1 reads the entering table, eta_s < 1 (and NaN)
/// the exiting one; alpha clamped to [1e-4, 1] and eta_hat to [g.eta_min, g.eta_max].
template <std::floating_point T>
[[nodiscard]] inline dielectric_albedo_cell<T> dielectric_albedo_locate(const dielectric_albedo_grid& g, T alpha,
                                                                         T eta_s) noexcept {
    dielectric_albedo_cell<T> c;
    c.side = eta_s > T(1) ? 0 : 1;
    const T eta_hat = eta_s > T(1) ? eta_s : T(1) / eta_s;
    c.alpha_clamped = glm::clamp(alpha, T(albedo_grid_alpha_min), T(1));
    c.alpha = albedo_grid_locate(std::sqrt(c.alpha_clamped), g.alpha_nodes);
    c.eta_clamped = glm::clamp(eta_hat, T(g.eta_min), T(g.eta_max));
    c.eta = albedo_grid_locate(dielectric_albedo_eta_coordinate(g, c.eta_clamped), g.eta_nodes);
    return c;
}

/// The Catmull-Rom spline through p0..p3 at t in [0, 1] between p1 and p2 (Catmull, Rom
/// 1974, "A Class of Local Interpolating Splines", in Computer Aided Geometric Design,
/// Academic Press; the uniform cubic Hermite form with tangents (p2 - p0) / 2 and
/// (p3 - p1) / 2): exact for cubics, error O(h^4) for smooth data where linear
/// interpolation has O(h^2).
template <std::floating_point T>
[[nodiscard]] constexpr T catmull_rom(T p0, T p1, T p2, T p3, T t) noexcept {
    return p1 + T(0.5) * t * ((p2 - p0) + t * ((T(2) * p0 - T(5) * p1 + T(4) * p2 - p3) + t * (T(3) * (p1 - p2) + p3 - p0)));
}

/// catmull_rom in cell i (between nodes i and i + 1) of an axis whose nodes lo..hi form one
/// smooth piece: node(i - 1 .. i + 2), with a neighbour outside [lo, hi] extrapolated
/// linearly (2 p_lo - p_lo+1 below, 2 p_hi - p_hi-1 above), so the tangent at an end node
/// of the piece is the secant of its cell (the end cells are not the parabola through their
/// three nodes: for p_k = k^2 the first cell reads 0.375 at its middle, not 0.25) and no
/// value from across the piece's ends is used.
template <std::floating_point T, class Node>
[[nodiscard]] inline T catmull_rom_axis(const Node& node, std::size_t i, std::size_t lo, std::size_t hi, T t) noexcept {
    const T p1 = node(i);
    const T p2 = node(i + 1);
    const T p0 = i > lo ? node(i - 1) : T(2) * p1 - p2;
    const T p3 = i + 1 < hi ? node(i + 2) : T(2) * p2 - p1;
    return catmull_rom(p0, p1, p2, p3, t);
}

/// The table of grid g interpolated at a located cell and view cosine mu (clamped to
/// [0, 1]), not clamped: a Catmull-Rom spline along the view coordinate and along
/// sqrt(alpha), linear along x (a Catmull-Rom spline when g.eta_spline). On the exiting
/// side the view axis is two pieces, below and above the critical angle (the node at 0.5
/// when the view nodes are odd in number), joined with a kink as E is.
template <std::floating_point T>
[[nodiscard]] inline T dielectric_albedo_interpolate(const float* table, const dielectric_albedo_grid& g,
                                                     const dielectric_albedo_cell<T>& cell, T mu) noexcept {
    const T m = glm::clamp(mu, T(0), T(1));
    const auto c_mu =
        albedo_grid_locate(dielectric_albedo_view(m, cell.alpha_clamped, cell.eta_clamped, cell.side, g.near_critical),
                           g.mu_nodes);
    const std::size_t last = g.mu_nodes - 1;
    const std::size_t middle = cell.side == 1 && last % 2 == 0 ? last / 2 : last;
    const std::size_t lo = c_mu.i < middle ? 0 : middle;
    const std::size_t hi = c_mu.i < middle ? middle : last;
    // The value at eta node k, interpolated along the view coordinate and sqrt(alpha).
    const auto block_value = [&](std::size_t k) {
        const auto row_value = [&](std::size_t j) {
            const float* row = table + g.row(cell.side, k, j);
            return catmull_rom_axis<T>([row](std::size_t i) { return T(row[i]); }, c_mu.i, lo, hi, c_mu.t);
        };
        return catmull_rom_axis<T>(row_value, cell.alpha.i, 0, g.alpha_nodes - 1, cell.alpha.t);
    };
    if (g.eta_spline) return catmull_rom_axis<T>(block_value, cell.eta.i, 0, g.eta_nodes - 1, cell.eta.t);
    const T e0 = block_value(cell.eta.i);
    const T e1 = block_value(cell.eta.i + 1);
    return e0 + cell.eta.t * (e1 - e0);
}

/// E(mu, alpha, eta_s) read from a table of grid g at a located cell
/// (dielectric_albedo_interpolate). Returns the albedo R + T, dimensionless, clamped to
/// [0, 1] (the spline may overshoot a node value by a little where E bends sharply).
template <std::floating_point T>
[[nodiscard]] inline T dielectric_albedo_lookup(const float* table, const dielectric_albedo_grid& g,
                                                const dielectric_albedo_cell<T>& cell, T mu) noexcept {
    return glm::clamp(dielectric_albedo_interpolate(table, g, cell, mu), T(0), T(1));
}

/// E_avg(alpha, eta_s) = 2 integral_0^1 E(mu) mu dmu of the interpolated table at a located
/// cell (the E that dielectric_albedo_lookup returns), by 5-point Gauss-Legendre quadrature
/// on 8 equal intervals of mu (Abramowitz, Stegun 1964, "Handbook of Mathematical
/// Functions", 25.4.29): the interpolant is smooth between the few places where it crosses
/// a node or the critical angle, so the quadrature error stays far below the table's own
/// (the tests bound it).
/// Returns the average albedo, dimensionless, in [0, 1].
template <std::floating_point T>
[[nodiscard]] inline T dielectric_albedo_average(const float* table, const dielectric_albedo_grid& g,
                                                 const dielectric_albedo_cell<T>& cell) noexcept {
    const T average = T(gauss_legendre_integral(
        [&](double mu) { return 2 * mu * double(dielectric_albedo_lookup(table, g, cell, T(mu))); }, 0, 1, 8));
    return glm::clamp(average, T(0), T(1));
}

} // namespace shade::detail
