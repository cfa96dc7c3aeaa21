#pragma once
// The grid and the interpolation of the anisotropic correction Delta_R of
// shade::dielectric_reflection_albedo's anisotropic form
// (shade/bsdf/dielectric_anisotropic_reflection_albedo.hpp). The numbers are generated into
// shade/bsdf/detail/dielectric_anisotropic_reflection_albedo_data.hpp by
//
//   examples/dielectric_albedo_tables --anisotropic --reflection --out include/shade/bsdf/detail/dielectric_anisotropic_reflection_albedo_data.hpp
//
// Delta_R,s(w) = R_ss(w) - R_ss,iso(mu, alpha_phi, eta_s) is the reflected albedo of a GGX
// interface with roughnesses alpha_x (along t), alpha_y (along b) at the view w, minus the
// isotropic reflection table at the roughness projected on w's azimuth. It depends on six
// numbers, each mapped to [0, 1] with uniform nodes:
//
//     x                                 the view's cosine mu: side 0 x = sqrt(mu), dense
//                                       toward grazing; side 1 x = sqrt(mu / mu_c) / 2 below
//                                       the critical cosine mu_c = sqrt(1 - 1 / eta_hat^2)
//                                       and 1/2 + sqrt((mu - mu_c) / (1 - mu_c)) / 2 above, so
//                                       that mu_c is a node
//     u                                 w's azimuth phi in [0, pi/2] from the smoother axis:
//                                       side 0 (entering, eta_s > 1) u^3 = (alpha_phi -
//                                       alpha_min) / (alpha_max - alpha_min), alpha_phi the
//                                       roughness projected on phi (below); side 1 (exiting,
//                                       eta_s < 1) g(t), g(t) = t (1 + t) / 2, above the kink
//                                       phi_k, which is on u = 1/2 (below)
//     y                                 the roughness: side 0 y = sqrt(alpha_max / sqrt 2),
//                                       alpha_max = max(alpha_x, alpha_y) up to sqrt 2, the
//                                       largest alpha of OpenPBR's roughness_to_alpha; side 1
//                                       y = sqrt(alpha_rms), alpha_rms = sqrt((alpha_x^2 +
//                                       alpha_y^2) / 2) up to 1 (OpenPBR's roughness r: its
//                                       alpha_rms is r^2)
//     z = sqrt(alpha_min / alpha_max)   the square root of OpenPBR's 1 - anisotropy: 0 a 1-D
//                                       rough surface (anisotropy 1), 1 isotropic; dense
//                                       toward 0, where a view near the smoother axis sees
//                                       the smaller alpha change fastest
//     e = log(eta_hat - 1) on [log 0.05, log 2], eta_hat = max(eta_s, 1 / eta_s) in [1.05, 3]
//     the side
//
// Entering, Delta_R is measured from the isotropic table at alpha_phi = sqrt(alpha_min^2
// cos^2 phi + alpha_max^2 sin^2 phi), which near the smoother axis of a nearly 1-D rough
// surface falls from alpha_min to alpha_max within a few degrees: R_ss,iso at grazing views
// changes steeply there while R_ss itself does not, and so does Delta_R. The side-0 azimuth
// coordinate follows alpha_phi instead of phi: u^3 is alpha_phi's fraction of the way from
// alpha_min to alpha_max, so nodes crowd where alpha_phi turns (phi ~ alpha_min / alpha_max)
// and are a cube-root step apart in alpha_phi beyond, as the roughness axis is in alpha
// (sqrt). In terms of s = sin(phi) and r = alpha_min / alpha_max (alpha_phi / alpha_max =
// sqrt(r^2 + (1 - r^2) s^2)), without cancellation as r nears 1,
//
//     u^3 = (1 + r) s^2 / (sqrt(r^2 + (1 - r^2) s^2) + r),    s^2 = u^3 (2 r + (1 - r) u^3) / (1 + r);
//
// r = 0 gives u^3 = s, r = 1 u^3 = s^2. Both even in phi about either axis, as Delta_R is.
//
// From the denser side (eta_s < 1) a surface that is smooth along one axis reflects totally
// wherever the view's component along that axis, sin(theta) cos(phi), reaches eta_s: that
// component is tangent to every microfacet, so no facet transmits. Delta_R has a kink there,
// at phi_k = acos(eta_s / sin(theta)) (none while sin(theta) <= eta_s, phi_k = 0); the side-1
// azimuth coordinate, u = phi / (2 phi_k) below phi_k and u = 1/2 + t / 2 above, g(t) = (phi -
// phi_k) / (pi/2 - phi_k), puts it on a node at every mu and eta, so interpolation does not
// cross it.
//
// The exiting side's y follows alpha_rms because its isotropic part is read there
// (reflection_base_alpha) and that read stops at alpha 1: along alpha_max, Delta_R would
// bend where alpha_rms reaches 1, between two y nodes and exactly at OpenPBR's roughness 1,
// and the spline would read it up to 1e-2 low there.
//
// Delta_R is Catmull-Rom cubic (Catmull, Rom 1974; shade::detail::spline_taps) along x, y, z
// and e and linear along u; on side 1 the x axis is two splines, below and above mu_c, so
// that the kink there does not bend the interpolation on either side. Nodes with y = 0 (a
// smooth interface) or z = 1 (isotropic) are 0 by construction and not stored. alpha_max
// beyond sqrt 2 (side 0) or alpha_rms beyond 1 (side 1) reads the axis's end, eta_hat outside [1.05, 3] the nearest end (the caller
// scales the correction toward eta_hat = 1). Layout: index ((((side * e_nodes + m) *
// (z_nodes - 1) + k) * (y_nodes - 1) + j - 1) *
// u_nodes + i_u) * x_nodes + i_x for z node k < z_nodes - 1 and y node j >= 1.

#include <cmath>
#include <concepts>
#include <cstddef>

#include <glm/common.hpp>

#include <shade/brdf/microfacet/albedo_table.hpp>
#include <shade/bsdf/dielectric_albedo_table.hpp>
#include <shade/bsdf/dielectric_anisotropic_albedo_table.hpp>

namespace shade::detail {

/// Nodes along x, the view coordinate, of the anisotropic reflection correction (odd: x =
/// 1/2 is a node).
inline constexpr std::size_t reflection_anisotropic_mu_nodes = 17;
/// Nodes along u, the azimuth coordinate (odd: u = 1/2 is a node).
inline constexpr std::size_t reflection_anisotropic_azimuth_nodes = 15;
/// Nodes along y, the roughness coordinate (reflection_anisotropic_y; node 0, a smooth
/// interface, is not stored).
inline constexpr std::size_t reflection_anisotropic_roughness_nodes = 10;
/// Nodes along z = sqrt(alpha_min / alpha_max) (the last, z = 1, isotropic, is not stored).
inline constexpr std::size_t reflection_anisotropic_ratio_nodes = 6;
/// Nodes along e = log(eta_hat - 1).
inline constexpr std::size_t reflection_anisotropic_eta_nodes = 7;
/// The largest alpha_max the y axis of side 0 reaches.
inline constexpr double reflection_anisotropic_alpha_top = 1.4142135623730951;
/// Rows (x nodes of one stored (side, e, s, y, u) node) per table.
inline constexpr std::size_t reflection_anisotropic_rows =
    2 * reflection_anisotropic_eta_nodes * (reflection_anisotropic_ratio_nodes - 1) *
    (reflection_anisotropic_roughness_nodes - 1) * reflection_anisotropic_azimuth_nodes;
/// Values per table.
inline constexpr std::size_t reflection_anisotropic_size = reflection_anisotropic_rows * reflection_anisotropic_mu_nodes;

/// The row index of the stored node (side, m along e, k < z_nodes - 1 along z, 1 <= j along
/// y, i_u along u).
[[nodiscard]] constexpr std::size_t reflection_anisotropic_row_index(std::size_t side, std::size_t m, std::size_t k,
                                                                     std::size_t j, std::size_t i_u) noexcept {
    return (((side * reflection_anisotropic_eta_nodes + m) * (reflection_anisotropic_ratio_nodes - 1) + k) *
                (reflection_anisotropic_roughness_nodes - 1) +
            (j - 1)) *
               reflection_anisotropic_azimuth_nodes +
           i_u;
}

/// The kink azimuth phi_k in [0, pi/2) from the smoother axis of the exiting side: where
/// sin_theta cos(phi) = 1 / eta_hat (inv_eta_hat = 1 / eta_hat in (0, 1)); 0 while
/// sin_theta <= 1 / eta_hat.
template <std::floating_point T>
[[nodiscard]] inline T reflection_anisotropic_kink(T sin_theta, T inv_eta_hat) noexcept {
    return sin_theta > inv_eta_hat ? std::acos(inv_eta_hat / sin_theta) : T(0);
}

/// The view coordinate x in [0, 1] of mu in [0, 1] on side `side` (mu_c: the critical cosine
/// of side 1, sqrt(1 - 1 / eta_hat^2) in (0, 1)).
template <std::floating_point T>
[[nodiscard]] inline T reflection_anisotropic_x(std::size_t side, T mu, T mu_c) noexcept {
    if (side == 0) return std::sqrt(mu);
    if (mu < mu_c) return T(0.5) * std::sqrt(mu / mu_c);
    return glm::min(T(0.5) + T(0.5) * std::sqrt((mu - mu_c) / (T(1) - mu_c)), T(1));
}

/// The view cosine of the coordinate x (the inverse of reflection_anisotropic_x).
[[nodiscard]] inline double reflection_anisotropic_mu(std::size_t side, double x, double mu_c) noexcept {
    if (side == 0) return x * x;
    if (x <= 0.5) return mu_c * 4 * x * x;
    return mu_c + (1 - mu_c) * (2 * x - 1) * (2 * x - 1);
}

/// The Catmull-Rom taps along x at coordinate x in [0, 1] on side `side`: one spline over
/// the axis on side 0, two on side 1 (nodes 0 .. n/2 and n/2 .. n - 1), each with its own
/// ends.
template <std::floating_point T>
[[nodiscard]] inline spline_taps<T> reflection_anisotropic_x_taps(std::size_t side, T x) noexcept {
    constexpr std::size_t nx = reflection_anisotropic_mu_nodes, half = nx / 2;
    const auto c = albedo_grid_locate(x, nx);
    if (side == 0) return spline_taps<T>(c.i, c.t, nx);
    const std::size_t offset = c.i < half ? 0 : half;
    spline_taps<T> taps(c.i - offset, c.t, half + 1);
    for (std::size_t& n : taps.node) n += offset;
    return taps;
}

/// The node spacing g(t) = t (1 + t) / 2 of the exiting side's azimuth coordinate above the
/// kink on [0, 1] (half as wide at 0 as uniform, half again as wide at 1), and its inverse:
/// past the kink Delta_R changes fastest (as the square root of the distance past it).
template <std::floating_point T>
[[nodiscard]] constexpr T reflection_anisotropic_spacing(T t) noexcept {
    return T(0.5) * t * (T(1) + t);
}
template <std::floating_point T>
[[nodiscard]] inline T reflection_anisotropic_spacing_inverse(T g) noexcept {
    return T(4) * g / (T(1) + std::sqrt(T(1) + T(8) * g)); // (sqrt(1 + 8 g) - 1) / 2 without cancellation
}

/// The azimuth coordinate u in [0, 1] of the azimuth phi in [0, pi/2] from the smoother axis
/// on side `side` (phi_k: reflection_anisotropic_kink of the view, side 1 only; ratio:
/// alpha_min / alpha_max in [0, 1], side 0 only): side 0 u^3 = (alpha_phi - alpha_min) /
/// (alpha_max - alpha_min), alpha_phi the roughness projected on phi; side 1 u = phi / (2
/// phi_k) below the kink and 1/2 + t / 2 above it, g(t) = (phi - phi_k) / (pi/2 - phi_k).
template <std::floating_point T>
[[nodiscard]] inline T reflection_anisotropic_u(std::size_t side, T phi, T phi_k, T ratio) noexcept {
    constexpr T half_pi = T(1.5707963267948966);
    if (side == 0) {
        const T s = std::sin(glm::clamp(phi, T(0), half_pi)), s2 = s * s, r = glm::clamp(ratio, T(0), T(1));
        const T below = std::sqrt(r * r + (T(1) - r * r) * s2) + r; // 0 only at r = s = 0
        return below > T(0) ? glm::min(std::cbrt((T(1) + r) * s2 / below), T(1)) : T(0);
    }
    if (phi < phi_k) return T(0.5) * phi / phi_k;
    return T(0.5) + T(0.5) * reflection_anisotropic_spacing_inverse(glm::clamp((phi - phi_k) / (half_pi - phi_k), T(0), T(1)));
}

/// The azimuth phi of the coordinate u on side `side` (the inverse of
/// reflection_anisotropic_u; on side 1 without a kink, u <= 1/2 reads phi = 0).
[[nodiscard]] inline double reflection_anisotropic_phi(std::size_t side, double u, double phi_k, double ratio) noexcept {
    constexpr double half_pi = 1.5707963267948966;
    if (side == 0) {
        const double q = u * u * u, r = glm::clamp(ratio, 0.0, 1.0);
        return std::asin(std::sqrt(glm::clamp(q * (2 * r + (1 - r) * q) / (1 + r), 0.0, 1.0)));
    }
    if (u <= 0.5) return 2 * u * phi_k;
    return phi_k + reflection_anisotropic_spacing(2 * u - 1) * (half_pi - phi_k);
}

/// The roughness coordinate y in [0, 1] of the alphas alpha_min <= alpha_max (alpha_max > 0)
/// on side `side`: side 0 sqrt(alpha_max / sqrt 2), side 1 sqrt(alpha_rms), alpha_rms =
/// sqrt((alpha_min^2 + alpha_max^2) / 2); each clamped to 1.
template <std::floating_point T>
[[nodiscard]] inline T reflection_anisotropic_y(std::size_t side, T alpha_min, T alpha_max) noexcept {
    if (side == 0) return glm::min(std::sqrt(alpha_max / T(reflection_anisotropic_alpha_top)), T(1));
    return glm::min(std::sqrt(std::sqrt(T(0.5) * (alpha_min * alpha_min + alpha_max * alpha_max))), T(1));
}

/// The larger alpha of the grid point (y, z) on side `side` (the inverse of
/// reflection_anisotropic_y with alpha_min = z^2 alpha_max): side 0 sqrt 2 y^2, side 1
/// y^2 sqrt(2 / (1 + z^4)).
[[nodiscard]] inline double reflection_anisotropic_alpha_max(std::size_t side, double y, double z) noexcept {
    if (side == 0) return reflection_anisotropic_alpha_top * y * y;
    const double z4 = z * z * z * z;
    return y * y * std::sqrt(2 / (1 + z4));
}

/// Where an interface with roughnesses alpha_x != alpha_y and index ratio eta_s reads the
/// correction. Computed once per interface.
template <std::floating_point T>
struct reflection_anisotropic_cell {
    bool swapped = false; ///< alpha_x > alpha_y: the smoother axis is b
    std::size_t side = 0; ///< 0 entering (eta_s > 1), 1 exiting
    T inv_eta_hat = 1;    ///< 1 / eta_hat, eta_hat clamped to the e axis
    T mu_c = 0;           ///< sqrt(1 - 1 / eta_hat^2), the critical cosine of side 1
    T ratio = 0;          ///< alpha_min / alpha_max, for side 0's azimuth coordinate
    spline_taps<T> y{};   ///< along the roughness coordinate y
    spline_taps<T> s{};   ///< along sqrt(alpha_min / alpha_max)
    spline_taps<T> e{};   ///< along log(eta_hat - 1)
};

/// The cell of roughnesses alpha_x != alpha_y (>= 0, finite, not both 0) and index ratio
/// eta_s != 1 (> 0).
template <std::floating_point T>
[[nodiscard]] inline reflection_anisotropic_cell<T> reflection_anisotropic_locate(T alpha_x, T alpha_y, T eta_s) noexcept {
    reflection_anisotropic_cell<T> c;
    c.swapped = alpha_x > alpha_y;
    const T hi = glm::max(alpha_x, alpha_y), lo = glm::min(alpha_x, alpha_y);
    c.ratio = lo / hi;
    c.side = eta_s > T(1) ? 0 : 1;
    const T eta_hat = glm::clamp(eta_s > T(1) ? eta_s : T(1) / eta_s, T(dielectric_albedo_eta_min),
                                 T(dielectric_albedo_eta_max));
    c.inv_eta_hat = T(1) / eta_hat;
    c.mu_c = std::sqrt((T(1) - c.inv_eta_hat) * (T(1) + c.inv_eta_hat));
    const auto y = albedo_grid_locate(reflection_anisotropic_y(c.side, lo, hi), reflection_anisotropic_roughness_nodes);
    const auto s = albedo_grid_locate(std::sqrt(c.ratio), reflection_anisotropic_ratio_nodes);
    const auto e = albedo_grid_locate(dielectric_albedo_eta_coordinate(eta_hat), reflection_anisotropic_eta_nodes);
    c.y = spline_taps<T>(y.i, y.t, reflection_anisotropic_roughness_nodes);
    c.s = spline_taps<T>(s.i, s.t, reflection_anisotropic_ratio_nodes);
    c.e = spline_taps<T>(e.i, e.t, reflection_anisotropic_eta_nodes);
    return c;
}

/// Delta_R,s(w) for the unit local direction w (only its azimuth and mu = |w.z| are used) of
/// the interface located by `cell`, from `delta` (reflection_anisotropic_size values).
/// Returns the albedo difference, dimensionless.
template <std::floating_point T>
[[nodiscard]] inline T reflection_anisotropic_delta(const float* delta, const reflection_anisotropic_cell<T>& cell,
                                                    T w_x, T w_y, T mu) noexcept {
    constexpr std::size_t nx = reflection_anisotropic_mu_nodes, ns = reflection_anisotropic_ratio_nodes;
    constexpr std::size_t nu = reflection_anisotropic_azimuth_nodes;
    const T along = cell.swapped ? w_y : w_x, across = cell.swapped ? w_x : w_y;
    // At the pole (w_x = w_y = 0) the azimuth reads 0.
    const T phi = std::atan2(std::abs(across), std::abs(along));
    const T sin_theta = std::sqrt(along * along + across * across);
    const T phi_k = cell.side == 1 ? reflection_anisotropic_kink(glm::min(sin_theta, T(1)), cell.inv_eta_hat) : T(0);
    const auto u = albedo_grid_locate(reflection_anisotropic_u(cell.side, phi, phi_k, cell.ratio), nu);
    const spline_taps<T> wx =
        reflection_anisotropic_x_taps(cell.side, reflection_anisotropic_x(cell.side, glm::clamp(std::abs(mu), T(0), T(1)), cell.mu_c));
    T sum = 0;
    for (int a = 0; a < 4; ++a) {
        if (cell.e.weight[a] == T(0)) continue;
        for (int b = 0; b < 4; ++b) {
            if (cell.s.weight[b] == T(0) || cell.s.node[b] == ns - 1) continue; // z = 1 holds 0
            T along_y = 0;
            for (int c = 0; c < 4; ++c) {
                if (cell.y.weight[c] == T(0) || cell.y.node[c] == 0) continue; // y = 0 holds 0
                const float* row0 =
                    delta + reflection_anisotropic_row_index(cell.side, cell.e.node[a], cell.s.node[b], cell.y.node[c], u.i) * nx;
                const float* row1 = row0 + nx;
                T d0 = 0, d1 = 0;
                for (int k = 0; k < 4; ++k) {
                    d0 += wx.weight[k] * T(row0[wx.node[k]]);
                    d1 += wx.weight[k] * T(row1[wx.node[k]]);
                }
                along_y += cell.y.weight[c] * (d0 + u.t * (d1 - d0));
            }
            sum += cell.e.weight[a] * cell.s.weight[b] * along_y;
        }
    }
    return sum;
}

} // namespace shade::detail
