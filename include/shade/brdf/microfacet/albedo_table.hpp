#pragma once
// The grid and the interpolation of the tabulated microfacet albedos E(mu, alpha) and
// E_avg(alpha) that the multiple-scattering compensation (shade::kulla_conty,
// shade/brdf/multiple_scattering.hpp) reads. The numbers themselves are generated into
// shade/brdf/microfacet/detail/albedo_data.hpp by examples/albedo_tables.cpp.
//
// A table holds, for a roughness alpha and a view cosine mu = n·v, the directional albedo
// of one single-scattering microfacet lobe (F D G2 / (4 (n·l)(n·v)) with height-correlated
// Smith G2),
//
//     E(mu, alpha) = integral over the hemisphere of f_ss(l, v) (n·l) dl,
//
// and its cosine-weighted average over mu,
//
//     E_avg(alpha) = 2 integral_0^1 E(mu, alpha) mu dmu,
//
// which is the hemispherical-hemispherical albedo (Kulla, Conty 2017, "Revisiting
// Physically Based Shading at Imageworks", SIGGRAPH course "Physically Based Shading in
// Theory and Practice", the E_avg of the multiple-scattering slides; unnumbered).
//
// Grid: n x n nodes (n = albedo_grid_nodes for the committed tables), uniform in
// y = sqrt(alpha) (alpha_j = (j / (n - 1))^2, at least albedo_grid_alpha_min) and in the
// view coordinate
//
//     c = (s + sqrt(mu)) / 2,     s = mu / (mu + alpha (1 - mu)),
//
// c_i = i / (n - 1). Both terms rise from 0 at mu = 0 to 1 at mu = 1 and each puts nodes
// where E bends: s follows the masking, sqrt(mu) the Fresnel factor. For small alpha, Smith's
// Lambda is a function of cot(theta) / alpha (Heitz 2014, "Understanding the
// Masking-Shadowing Function in Microfacet-Based BRDFs", JCGT 3(2), eq. 72), so with F = 1
// E depends on mu mostly through mu / alpha, falling from ~1 at mu -> 0 to a minimum near
// mu ~ alpha and rising again: s keeps that dip in the same columns of every row, however
// small alpha is. A dielectric Fresnel factor falls steeply from 1 at grazing whatever
// alpha is: sqrt(mu) resolves that. E is bilinear in (c, y) between nodes. E_avg(alpha_j)
// is the exact cosine-weighted average of row j's interpolant (albedo_row_average), linear
// in y between nodes. alpha is clamped to [albedo_grid_alpha_min, 1] (rougher surfaces
// read the alpha = 1 row: the tables end there). Stored as float: 7 significant digits.
// The accuracy of each table is stated in the generated header.

#include <cmath>
#include <concepts>
#include <cstddef>

#include <glm/common.hpp>

#include <shade/core/math.hpp>

namespace shade::detail {

/// Nodes per axis of the committed albedo tables.
inline constexpr std::size_t albedo_grid_nodes = 128;

/// The smallest roughness of the grid: 1e-4, the smallest the distributions accept
/// (shade::microfacet_parameter_min); lookups clamp alpha to [1e-4, 1].
inline constexpr double albedo_grid_alpha_min = 1e-4;

/// The roughness of row j of an n-node axis: (j / (n - 1))^2, at least albedo_grid_alpha_min.
[[nodiscard]] constexpr double albedo_grid_alpha(std::size_t j, std::size_t n) noexcept {
    const double y = double(j) / double(n - 1);
    return y * y > albedo_grid_alpha_min ? y * y : albedo_grid_alpha_min;
}

/// The view coordinate c of (mu, alpha), for mu in [0, 1] and alpha in [1e-4, 1]:
/// (mu / (mu + alpha (1 - mu)) + sqrt(mu)) / 2, in [0, 1], increasing in mu.
template <std::floating_point T>
[[nodiscard]] inline T albedo_grid_c(T mu, T alpha) noexcept {
    return T(0.5) * (mu / (mu + alpha * (T(1) - mu)) + std::sqrt(mu));
}

/// The view cosine at coordinate c in [0, 1] for roughness alpha: the inverse of
/// albedo_grid_c, by bisection to double precision (for the generator and the tests).
[[nodiscard]] inline double albedo_grid_mu(double c, double alpha) noexcept {
    return bisect_increasing([alpha](double mu) { return albedo_grid_c(mu, alpha); }, c);
}

/// Where the generator evaluates the c = 0 column (mu = 0, no view above the surface): a
/// view 1e-6 above the horizon (E is continuous there).
inline constexpr double albedo_grid_mu_min = 1e-6;

/// Cell index and fraction of the coordinate t in [0, 1] on an n-node axis.
template <std::floating_point T>
struct albedo_grid_cell {
    std::size_t i;
    T t;
};

template <std::floating_point T>
[[nodiscard]] inline albedo_grid_cell<T> albedo_grid_locate(T x, std::size_t n) noexcept {
    // x is c or sqrt(alpha), clamped to [0, 1] (NaN reads node 0).
    const T s = (x > T(0) ? glm::min(x, T(1)) : T(0)) * T(n - 1);
    const std::size_t i = glm::min(std::size_t(s), n - 2);
    return {i, s - T(i)};
}

/// E(mu, alpha) read from an n x n table stored row by row (row j is alpha_j, column i
/// is c_i): bilinear in (c, sqrt(alpha)); mu clamped to [0, 1], alpha to [1e-4, 1].
/// Returns the albedo, dimensionless, in [0, 1].
template <std::floating_point T>
[[nodiscard]] inline T albedo_lookup(const float* table, std::size_t n, T mu, T alpha) noexcept {
    const T a = glm::clamp(alpha, T(albedo_grid_alpha_min), T(1));
    const T m = glm::clamp(mu, T(0), T(1));
    const auto c_s = albedo_grid_locate(albedo_grid_c(m, a), n);
    const auto c_alpha = albedo_grid_locate(std::sqrt(a), n);
    const float* row0 = table + c_alpha.i * n + c_s.i;
    const float* row1 = row0 + n;
    const T e0 = T(row0[0]) + c_s.t * (T(row0[1]) - T(row0[0]));
    const T e1 = T(row1[0]) + c_s.t * (T(row1[1]) - T(row1[0]));
    return e0 + c_alpha.t * (e1 - e0);
}

/// E_avg(alpha) read from an n-entry table (entry j is alpha_j): linear in sqrt(alpha),
/// alpha clamped to [1e-4, 1]. Returns the average albedo, dimensionless, in [0, 1].
template <std::floating_point T>
[[nodiscard]] inline T albedo_average_lookup(const float* averages, std::size_t n, T alpha) noexcept {
    const T a = glm::clamp(alpha, T(albedo_grid_alpha_min), T(1));
    const auto c = albedo_grid_locate(std::sqrt(a), n);
    return T(averages[c.i]) + c.t * (T(averages[c.i + 1]) - T(averages[c.i]));
}

/// The cosine-weighted average 2 integral_0^1 E(mu) mu dmu of row `row` (n node values,
/// roughness alpha) interpolated as albedo_lookup does (linear in c between nodes): cell
/// by cell in mu, over [mu(c_i), mu(c_i+1)], with 5-point Gauss-Legendre quadrature
/// (Abramowitz, Stegun 1964, "Handbook of Mathematical Functions", 25.4.29 and table
/// 25.4); within a cell the integrand E(c(mu)) mu is smooth.
[[nodiscard]] inline double albedo_row_average(const float* row, std::size_t n, double alpha) noexcept {
    constexpr double node[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831,
                                0.9061798459386640};
    constexpr double weight[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                                  0.4786286704993665, 0.2369268850561891};
    double sum = 0;
    for (std::size_t i = 0; i + 1 < n; ++i) {
        const double c0 = double(i) / double(n - 1);
        const double mu0 = albedo_grid_mu(c0, alpha);
        const double mu1 = albedo_grid_mu(double(i + 1) / double(n - 1), alpha);
        const double half = 0.5 * (mu1 - mu0);
        for (int k = 0; k < 5; ++k) {
            const double mu = mu0 + half * (1.0 + node[k]);
            const double t = (albedo_grid_c(mu, alpha) - c0) * double(n - 1); // in [0, 1] within the cell
            const double e = double(row[i]) + t * (double(row[i + 1]) - double(row[i]));
            sum += weight[k] * half * 2.0 * e * mu;
        }
    }
    return sum;
}

/// Catmull-Rom weights of the nodes i - 1, i, i + 1, i + 2 at the fraction t in [0, 1] of
/// cell i (Catmull, Rom 1974, "A Class of Local Interpolating Splines", the spline with
/// tangents (p_i+1 - p_i-1) / 2): cubic, interpolating, weights summing to 1.
template <std::floating_point T>
struct catmull_rom_weights {
    T w[4];
    explicit catmull_rom_weights(T t) noexcept
        : w{T(0.5) * t * ((T(2) - t) * t - T(1)), T(0.5) * (t * t * (T(3) * t - T(5)) + T(2)),
            T(0.5) * t * ((T(4) - T(3) * t) * t + T(1)), T(0.5) * t * t * (t - T(1))} {}
};

/// The four nodes and weights with which the Catmull-Rom spline of catmull_rom_weights reads
/// the fraction t of cell i of an n-node axis (n >= 3): nodes i - 1 .. i + 2, a neighbour
/// beyond an end replaced by its linear extrapolation (2 p_0 - p_1, 2 p_n-1 - p_n-2), so the
/// tangent at an end node is the secant of its cell and no value from beyond the axis is
/// needed. Exact for quadratics inside; the weights sum to 1.
template <std::floating_point T>
struct spline_taps {
    std::size_t node[4]{};
    T weight[4]{};

    spline_taps() = default;
    spline_taps(std::size_t i, T t, std::size_t n) noexcept {
        const catmull_rom_weights<T> c(t);
        const T* w = c.w;
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

} // namespace shade::detail
