#pragma once
// shade::rough_dielectric_albedo_grid: the single-scattering albedo R + T of one rough GGX
// dielectric interface, integrated on a grid of views when it is built (both sides), for
// shade::compensated_rough_dielectric's per-interface mode.

#include <array>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <optional>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <shade/brdf/fresnel.hpp>
#include <shade/brdf/microfacet/ggx.hpp>
#include <shade/bsdf/refract.hpp>
#include <shade/core/error.hpp>
#include <shade/core/heap_value.hpp>
#include <shade/core/math.hpp>
#include <shade/core/types.hpp>

namespace shade {

namespace detail {

/// R + T in importance mode of shade::rough_dielectric over `distribution` for the unit view v
/// (v.z > 0) in a medium whose index ratio to the far side is eta_s = n_far / n_v: the
/// expectation, over visible normals m (Heitz 2018, "Sampling the GGX Distribution of Visible
/// Normals", JCGT 7(4)), of the weight of rough_dielectric's sampler,
///
///     E(v) = E_m[ F(v·m) G2(v, l_r) / G1(v) + (1 - F(v·m)) G2(v, l_t) / G1(v) ],
///
/// l_r the mirror of v about m, l_t its refraction through m (Walter, Marschner, Li, Torrance
/// 2007, "Microfacet Models for Refraction through Rough Surfaces", EGSR, eqs. 40 and 41;
/// the Fresnel factor of each branch is the probability with which the sampler takes it),
/// and G2 = 1 / (1 + Lambda(v) + Lambda(l)) the height-correlated masking-shadowing (Heitz 2014,
/// "Understanding the Masking-Shadowing Function in Microfacet-Based BRDFs", JCGT 3(2),
/// eq. 99); a branch whose direction lands on the wrong side of the surface adds 0. The
/// sampler's weight f |n·l| / pdf reduces to exactly G2 / G1(v) on both branches, so this is
/// what rough_dielectric's own sampler averages to. Midpoint rule over columns x rows cells of
/// the unit square that sample_visible_normal maps onto the visible normals (columns in the
/// angle u_x, rows in u_y). With `transmitted` false the refracted branch is left out: the
/// reflection albedo R_ss(v) alone. Dimensionless, in [0, 1].
[[nodiscard]] inline double dielectric_visible_albedo(const ggx<double>& distribution, const vec3<double>& v,
                                                      double eta_s, int columns, int rows, bool transmitted) noexcept;

/// The two albedos of dielectric_visible_albedo from one pass over the same visible normals:
/// the reflection albedo R_ss(v) and the total R + T.
struct dielectric_visible_albedos {
    double reflected = 0; ///< R_ss(v)
    double total = 0;     ///< R_ss(v) + T_ss(v)
};

/// dielectric_visible_albedo's sums, the refracted branch only when Transmitted; also calls
/// reflect(c, F, g) for every visible normal whose mirror direction lies above the surface:
/// c = v·m, F = F_dielectric(c, eta_s), and g = G2(v, l) / G1(v) divided by the number of
/// cells, the reflected branch's weight before its Fresnel factor (so that a caller summing
/// F'(c) g integrates the reflection albedo with another Fresnel term F' on the same visible
/// normals).
template <bool Transmitted, class Reflect>
[[nodiscard]] inline dielectric_visible_albedos dielectric_visible_albedo_sums(const ggx<double>& distribution,
                                                                              const vec3<double>& v, double eta_s,
                                                                              int columns, int rows,
                                                                              Reflect&& reflect) noexcept {
    const double masking_v = 1.0 + distribution.Lambda(v); // 1 / G1(v)
    const vec3<double> v_stretched = distribution.stretch(v);
    const double cells = double(columns) * double(rows);
    double reflected = 0.0, transmitted = 0.0;
    for (int i = 0; i < columns; ++i) {
        // u = ((i + 1/2) / columns, (j + 1/2) / rows): the angle 2 pi u_x is the column's.
        const double phi = 2.0 * pi<double> * (double(i) + 0.5) / double(columns);
        const double cos_phi = std::cos(phi), sin_phi = std::sin(phi);
        for (int j = 0; j < rows; ++j) {
            const double u_y = (double(j) + 0.5) / double(rows);
            const vec3<double> m = distribution.sample_visible_normal_stretched(v_stretched, cos_phi, sin_phi, u_y);
            const double v_dot_m = glm::dot(v, m);
            if (!(v_dot_m > 0.0)) continue;
            const double F = F_dielectric(v_dot_m, eta_s);
            const vec3<double> l = 2.0 * v_dot_m * m - v;
            if (l.z > 0.0) {
                const double g = masking_v / (masking_v + distribution.Lambda(l));
                reflected += F * g;
                reflect(v_dot_m, F, g / cells);
            }
            if constexpr (Transmitted) {
                if (F < 1.0) {
                    const std::optional<vec3<double>> t = refract(v, m, eta_s);
                    if (t && t->z < 0.0) transmitted += (1.0 - F) * masking_v / (masking_v + distribution.Lambda(*t));
                }
            }
        }
    }
    return {reflected / cells, (reflected + transmitted) / cells};
}

/// dielectric_visible_albedo's sums, the refracted branch only when Transmitted.
template <bool Transmitted>
[[nodiscard]] inline dielectric_visible_albedos dielectric_visible_albedo_sums(const ggx<double>& distribution,
                                                                              const vec3<double>& v, double eta_s,
                                                                              int columns, int rows) noexcept {
    return dielectric_visible_albedo_sums<Transmitted>(distribution, v, eta_s, columns, rows,
                                                       [](double, double, double) {});
}

inline double dielectric_visible_albedo(const ggx<double>& distribution, const vec3<double>& v, double eta_s,
                                        int columns, int rows, bool transmitted) noexcept {
    return transmitted ? dielectric_visible_albedo_sums<true>(distribution, v, eta_s, columns, rows).total
                       : dielectric_visible_albedo_sums<false>(distribution, v, eta_s, columns, rows).reflected;
}

/// dielectric_visible_albedo on cells x cells squares.
[[nodiscard]] inline double dielectric_visible_albedo(const ggx<double>& distribution, const vec3<double>& v,
                                                      double eta_s, int cells, bool transmitted = true) noexcept {
    return dielectric_visible_albedo(distribution, v, eta_s, cells, cells, transmitted);
}

/// Added to every value of a rough_dielectric_albedo_grid: the grid reads E_s this much
/// high, so that the compensation's R + T = 1 + E_true - E_read errs below 1 rather than
/// above where the grid's interpolation and quadrature err (measured ranges in
/// docs/properties.md).
inline constexpr double rough_dielectric_albedo_grid_margin = 3e-3;

/// The margin at strong anisotropy (alpha_max / alpha_min >= 20, the grid's finer azimuths):
/// seen from the denser side, E_s of a surface nearly smooth along one axis has features a
/// few degrees wide in azimuth that the nodes straddle, so the interpolation errs more.
inline constexpr double rough_dielectric_albedo_grid_margin_strong = 6e-3;

/// One side of a rough GGX dielectric interface on the views of a
/// shade::rough_dielectric_albedo_grid (its class comment: rows in mu with the critical
/// cosine on a row where the side sees total internal reflection, azimuths crowded toward the
/// smoother axis), holding a value per view node and reading it bilinearly; also its
/// cosine-weighted hemispherical average. Used for R + T (rough_dielectric_albedo_grid) and
/// for the reflection albedo R_ss alone (anisotropic_reflection_albedo_grid below an index
/// ratio of 1).
template <std::floating_point T>
class dielectric_side_grid {
public:
    static constexpr int azimuths = 37;              ///< azimuth nodes per row
    static constexpr int strong_azimuths = 73;       ///< azimuth nodes per row at strong anisotropy
    static constexpr int isotropic_azimuths = 2;     ///< the same for equal alphas (no azimuth dependence)
    static constexpr int max_rows = 37;              ///< rows on a side with total internal reflection
    static constexpr int max_rows_dense = 49;        ///< the same with dense_at_critical
    static constexpr int rows_without_critical = 16; ///< rows on a side without it
    static constexpr int rows_without_critical_dense = 46; ///< the same with dense_at_critical
    static constexpr int rows_below_critical = 24;   ///< intervals from grazing to the critical cosine
    static constexpr int rows_above_critical = 12;   ///< intervals from the critical cosine to the normal
    static constexpr int rows_above_critical_dense = 24; ///< the same with dense_at_critical

    /// Whether the grid of alphas alpha_x, alpha_y is at strong anisotropy
    /// (alpha_max / alpha_min >= 20): strong_azimuths and the larger margin.
    [[nodiscard]] static bool strong(double alpha_x, double alpha_y) noexcept {
        return glm::max(alpha_x, alpha_y) >= 20.0 * glm::min(alpha_x, alpha_y);
    }

    dielectric_side_grid() = default;

    /// The side that sees the far medium at index ratio eta_s = n_far / n_side of an interface of
    /// GGX alphas alpha_x, alpha_y > 0 (unchecked), each node holding value(v) for its unit view
    /// v (vec3<double>, v.z > 0), plus `margin` (`strong_margin` at strong anisotropy), at most 1.
    /// With dense_at_critical the rows below the critical cosine are at mu_c (3 x^2 - 2 x^3)
    /// instead of mu_c x^1.5 (x = i / 24), and rows_above_critical_dense rows above it at
    /// mu_c + (1 - mu_c) y^1.5 (y = (i - 24) / 24) instead of 12 evenly spaced ones: dense
    /// toward the critical cosine from both sides as well as toward grazing, for a value that
    /// steps there (the reflection albedo alone: R + T does not); on a side without total
    /// internal reflection (eta_s >= 1), rows_without_critical_dense rows at x^1.5 instead of
    /// 16, for a value with fine structure in mu (a thin film's share of the albedo).
    template <class Value>
    dielectric_side_grid(double alpha_x, double alpha_y, double eta_s, double margin, double strong_margin,
                         const Value& value, bool dense_at_critical = false)
        : dense_at_critical_(dense_at_critical) {
        const double q = glm::min(glm::max(alpha_x, alpha_y) / glm::min(alpha_x, alpha_y), 20.0);
        log_q2_ = T(2 * std::log(q));
        const bool is_strong = strong(alpha_x, alpha_y);
        azimuths_ = alpha_x == alpha_y ? isotropic_azimuths : is_strong ? strong_azimuths : azimuths;
        added_ = T(is_strong ? strong_margin : margin);
        const double added = double(added_);
        smoother_y_ = alpha_x > alpha_y;
        // The critical cosine's row; at most 1 - 1e-4, so that the rows above it keep
        // distinct cosines in T where eta_s is so small that mu_c rounds to 1 (the nodes
        // still hold the value at their own cosines).
        mu_c_ = eta_s < 1.0 ? T(glm::min(std::sqrt((1.0 - eta_s) * (1.0 + eta_s)), 1.0 - 1e-4)) : T(0);
        rows_above_ = dense_at_critical ? rows_above_critical_dense : rows_above_critical;
        plain_rows_ = dense_at_critical ? rows_without_critical_dense : rows_without_critical;
        rows_ = mu_c_ > T(0) ? rows_below_critical + rows_above_ + 1 : plain_rows_;
        const double log_q2 = double(log_q2_);
        for (int j = 0; j < azimuths_; ++j) {
            const double s = azimuth_of_warp(double(j) / double(azimuths_ - 1), log_q2);
            const double cos2 = smoother_y_ ? s : 1.0 - s;
            const double c = std::sqrt(cos2), sn = std::sqrt(glm::max(0.0, 1.0 - cos2));
            for (int i = 0; i < rows_; ++i) {
                const double mu = glm::clamp(row_mu(i), 1e-4, 1.0);
                const double st = std::sqrt((1.0 - mu) * (1.0 + mu));
                const double e = double(value(vec3<double>(st * c, st * sn, mu))) + added;
                e_[i * azimuths_ + j] = float(glm::min(e, 1.0));
            }
        }
        average_ = average_of_reads();
    }

    /// N grids of the same side and layout from one pass over the nodes: values(v) returns a
    /// std::array<double, N> of the values at the node's view v, grid k holding value k plus
    /// margin[k] (strong_margin[k] at strong anisotropy); otherwise as the constructor above.
    template <std::size_t N, class Values>
    [[nodiscard]] static std::array<dielectric_side_grid, N>
    many(double alpha_x, double alpha_y, double eta_s, const std::array<double, N>& margin,
         const std::array<double, N>& strong_margin, const Values& values, bool dense_at_critical = false) {
        static_assert(N >= 1);
        // The other grids' constructors visit the nodes in the first's order (the layout is the
        // same): they read back the values the first pass kept (on the heap: up to
        // max_rows_dense x strong_azimuths nodes of N - 1 values; no <vector> in this header).
        struct kept_values {
            double* data = new double[std::size_t(max_rows_dense) * std::size_t(strong_azimuths) * (N - 1 + (N == 1))];
            ~kept_values() { delete[] data; }
        } kept;
        std::size_t count = 0;
        std::array<dielectric_side_grid, N> out{};
        out[0] = dielectric_side_grid(
            alpha_x, alpha_y, eta_s, margin[0], strong_margin[0],
            [&values, &kept, &count](const vec3<double>& v) {
                const std::array<double, N> all = values(v);
                for (std::size_t k = 1; k < N; ++k) kept.data[count * (N - 1) + (k - 1)] = all[k];
                ++count;
                return all[0];
            },
            dense_at_critical);
        for (std::size_t k = 1; k < N; ++k) {
            std::size_t next = 0;
            out[k] = dielectric_side_grid(
                alpha_x, alpha_y, eta_s, margin[k], strong_margin[k],
                [&kept, &next, count, k](const vec3<double>&) {
                    return next < count ? kept.data[(next++) * (N - 1) + (k - 1)] : 0.0;
                },
                dense_at_critical);
        }
        return out;
    }

    /// The value at the local direction w (n = +z, the tangent along +x): only |w.z| and w's
    /// azimuth are read, so w may point either way. Bilinear between the nodes, in [0, 1].
    [[nodiscard]] T at(const vec3<T>& w) const noexcept {
        const cell c = cell_of(w);
        T e = (T(1) - c.t) * row_at(c, c.i) + c.t * row_at(c, c.i + 1);
        if (lift_.has_value()) e += T((*lift_)[std::size_t(c.i) * std::size_t(strong_azimuths - 1) + std::size_t(c.j)]);
        return glm::clamp(e, T(0), T(1));
    }

    /// at(w) without lift_cells' lifts: the nodes' bilinear read, in [0, 1] (what a value
    /// integrated on the same nodes, less this one, is relative to).
    [[nodiscard]] T at_without_lift(const vec3<T>& w) const noexcept {
        const cell c = cell_of(w);
        return glm::clamp((T(1) - c.t) * row_at(c, c.i) + c.t * row_at(c, c.i + 1), T(0), T(1));
    }

    /// at(w) for a value that may be negative (a difference of two albedos): the same bilinear
    /// read, clamped to [-1, 1] instead.
    [[nodiscard]] T at_signed(const vec3<T>& w) const noexcept {
        const cell c = cell_of(w);
        const T e = (T(1) - c.t) * row_at(c, c.i) + c.t * row_at(c, c.i + 1);
        return glm::clamp(e, T(-1), T(1));
    }

    /// at_signed(w) of each of `grids`, grids of one layout (made by one many() call), with w
    /// located once: out[k] is grids[k].at_signed(w).
    template <std::size_t N>
    [[nodiscard]] static std::array<T, N> at_signed_all(const std::array<dielectric_side_grid, N>& grids,
                                                        const vec3<T>& w) noexcept {
        static_assert(N > 0);
        const cell c = grids[0].cell_of(w);
        std::array<T, N> out;
        for (std::size_t k = 0; k < N; ++k)
            out[k] = glm::clamp((T(1) - c.t) * grids[k].row_at(c, c.i) + c.t * grids[k].row_at(c, c.i + 1), T(-1),
                                T(1));
        return out;
    }

    /// A read of the value at w that is at or below the nodes' own function (their margin
    /// included) where that function is concave in mu below the critical cosine and convex
    /// above it, as the reflection albedo R_ss of a side with total internal reflection is
    /// (a plateau near 1 that falls across mu_c and flattens toward the normal): below mu_c
    /// the chord between the rows (at or below a concave function), above it the larger of
    /// the lines through the next two rows on either side within that range, extended into
    /// the cell (at or below a convex function outside the two points), and not above the
    /// chord. Each row's value at w's azimuth is linear between its azimuth nodes, as in
    /// at(). In [0, 1].
    [[nodiscard]] T at_or_below(const vec3<T>& w) const noexcept {
        const cell c = cell_of(w);
        const int i = c.i;
        // The line through rows r and r + 1, at mu.
        const auto line = [this, &c](int r) {
            const T m0 = T(row_mu(r)), m1 = T(row_mu(r + 1));
            const T v0 = row_at(c, r), v1 = row_at(c, r + 1);
            return v0 + (v1 - v0) * (c.mu - m0) / (m1 - m0);
        };
        const T chord = line(i);
        T below = chord;
        if (mu_c_ > T(0) && i >= rows_below_critical) {
            const bool after = i + 2 <= rows_ - 1, before = i - 1 >= rows_below_critical;
            if (after && before) below = glm::max(line(i + 1), line(i - 1));
            else if (after) below = line(i + 1);
            else if (before) below = line(i - 1);
            below = glm::min(below, chord);
        }
        return glm::clamp(below, T(0), T(1));
    }

    /// mu of row i (0 to rows() - 1): the layout of the class comment and the constructor's.
    [[nodiscard]] double row_cosine(int i) const noexcept { return row_mu(i); }

    /// The number of rows in mu.
    [[nodiscard]] int rows() const noexcept { return rows_; }

    /// The spacing function of the azimuth nodes: s -> [0, 1], increasing, s the squared cosine
    /// of the azimuth from the rougher axis and log_q2 = 2 log q (q the ratio of the alphas,
    /// at most 20); node j of n lies where it equals j / (n - 1).
    [[nodiscard]] static double azimuth_warp(double s, double log_q2) noexcept {
        const double logarithmic = log_q2 > 0.0 ? std::log1p(std::expm1(log_q2) * s) / log_q2 : s;
        return 0.5 * (s + logarithmic);
    }

    /// The s in [0, 1] whose azimuth_warp is `target` (in [0, 1]), by bisection.
    [[nodiscard]] static double azimuth_of_warp(double target, double log_q2) noexcept {
        return bisect_increasing([log_q2](double s) { return azimuth_warp(s, log_q2); }, target);
    }

    /// azimuth_warp of the local direction w's azimuth (only w.x and w.y are read), in [0, 1]:
    /// smoother_y when alpha_x > alpha_y. On the normal, where the azimuth is undefined and a
    /// value the same at every one, 1; NaN components read as 0.
    [[nodiscard]] static T azimuth_position(const vec3<T>& w, bool smoother_y, T log_q2) noexcept {
        const T xx = w.x * w.x, yy = w.y * w.y;
        const T planar = xx + yy;
        const T cos2 = planar > T(0) ? xx / planar : T(1);
        const T s = smoother_y ? cos2 : T(1) - cos2;
        const T s_unit = s >= T(0) ? glm::min(s, T(1)) : T(0);
        return T(azimuth_warp(double(s_unit), double(log_q2)));
    }

    /// Lifts the reads of the cells that select(mu0, mu1, s0, s1) picks (the cell's rows'
    /// cosines mu0 < mu1 and its azimuth nodes' s0 < s1, s the squared cosine of the azimuth
    /// from the rougher axis) over a value with a sharp feature inside them: at 3 x 3 points
    /// of each such cell (a quarter, half and three quarters of the way in both coordinates)
    /// value(v) (vec3<double> v, the quantity the nodes hold, without the margin) plus the
    /// margin is compared with at(), and the cell's reads by at() rise by cell_lift_factor
    /// times the largest excess. The average is recomputed from the lifted reads. For a
    /// value whose kink runs across the grid's cells (the reflection albedo of a strongly
    /// anisotropic side with total internal reflection: anisotropic_reflection_albedo_grid).
    template <class Select, class Value>
    void lift_cells(const Select& select, const Value& value) {
        auto& lift = lift_.emplace();
        lift.fill(0.0f);
        bool any = false;
        for (int i = 0; i + 1 < rows_; ++i) {
            const double mu0 = row_mu(i), mu1 = row_mu(i + 1);
            for (int j = 0; j + 1 < azimuths_; ++j) {
                const double s0 = azimuth_of_warp(double(j) / double(azimuths_ - 1), double(log_q2_));
                const double s1 = azimuth_of_warp(double(j + 1) / double(azimuths_ - 1), double(log_q2_));
                if (!select(mu0, mu1, s0, s1)) continue;
                double excess = 0.0;
                for (const double t : {0.25, 0.5, 0.75}) {
                    const double mu = glm::clamp(row_mu(double(i) + t), 1e-4, 1.0);
                    const double st = std::sqrt((1.0 - mu) * (1.0 + mu));
                    for (const double a : {0.25, 0.5, 0.75}) {
                        const double s = azimuth_of_warp((double(j) + a) / double(azimuths_ - 1), double(log_q2_));
                        const double cos2 = smoother_y_ ? s : 1.0 - s;
                        const vec3<double> v(st * std::sqrt(cos2), st * std::sqrt(glm::max(0.0, 1.0 - cos2)), mu);
                        const double read = double(at(vec3<T>(v)));
                        excess = glm::max(excess, glm::min(double(value(v)) + double(added_), 1.0) - read);
                    }
                }
                lift[std::size_t(i) * std::size_t(strong_azimuths - 1) + std::size_t(j)] = float(cell_lift_factor * excess);
                any = any || excess > 0.0;
            }
        }
        if (!any) {
            lift_ = {};
            return;
        }
        average_ = average_of_reads();
    }

    /// What lift_cells multiplies a cell's largest sampled excess by: 1, the excess over the
    /// value plus the margin, so that between the samples the margin absorbs what they miss.
    static constexpr double cell_lift_factor = 1.0;

    /// The cosine-weighted hemispherical average of at(): 2 int at(w) mu dw / (2 pi).
    [[nodiscard]] T average() const noexcept { return average_; }

    /// What every node holds above its value (the constructor's margin, or strong_margin).
    [[nodiscard]] T margin() const noexcept { return added_; }

private:
    /// Where a read falls: w's cosine mu, its row cell i (rows i and i + 1) and the weight t
    /// of row i + 1, its azimuth cell j and the weight a of node j + 1.
    struct cell {
        T mu, t, a;
        int i, j;
    };
    [[nodiscard]] cell cell_of(const vec3<T>& w) const noexcept {
        const T mu = unit_cosine(w);
        const T row = glm::min(mu_coordinate(mu), T(rows_ - 1));
        const int i = glm::min(int(row), rows_ - 2);
        const T along = glm::min(azimuth_coordinate(w), T(azimuths_ - 1));
        const int j = glm::min(int(along), azimuths_ - 2);
        return {mu, row - T(i), along - T(j), i, j};
    }
    /// Row r's value at the cell's azimuth, linear between its nodes j and j + 1.
    [[nodiscard]] T row_at(const cell& c, int r) const noexcept {
        return (T(1) - c.a) * T(e_[r * azimuths_ + c.j]) + c.a * T(e_[r * azimuths_ + c.j + 1]);
    }

    /// |w.z| clamped to [0, 1], NaN read as 0 (a grid read is then a node's value, never an
    /// index from NaN).
    [[nodiscard]] static T unit_cosine(const vec3<T>& w) noexcept {
        const T mu = std::abs(w.z);
        return mu <= T(1) ? mu : mu > T(1) ? T(1) : T(0);
    }

    /// The row coordinate (0 to rows_ - 1) of mu.
    [[nodiscard]] T mu_coordinate(T mu) const noexcept {
        if (!(mu_c_ > T(0))) return T(plain_rows_ - 1) * std::cbrt(mu * mu);
        if (mu <= mu_c_) {
            if (!dense_at_critical_) return T(rows_below_critical) * std::cbrt(sqr(mu / mu_c_));
            // The inverse of the smoothstep 3 x^2 - 2 x^3 = y on [0, 1].
            const double y = double(mu / mu_c_);
            return T(rows_below_critical) * T(0.5 - std::sin(std::asin(glm::clamp(1.0 - 2.0 * y, -1.0, 1.0)) / 3.0));
        }
        const T y = (mu - mu_c_) / (T(1) - mu_c_);
        return T(rows_below_critical) + T(rows_above_) * (dense_at_critical_ ? std::cbrt(y * y) : y);
    }

    /// mu of row i.
    [[nodiscard]] double row_mu(int i) const noexcept { return row_mu(double(i)); }

    /// mu at the row coordinate r (0 to rows_ - 1; between the rows the same spacing
    /// function, the inverse of mu_coordinate).
    [[nodiscard]] double row_mu(double r) const noexcept {
        if (!(mu_c_ > T(0))) {
            const double x = r / double(plain_rows_ - 1);
            return x * std::sqrt(x);
        }
        const double mu_c = double(mu_c_);
        if (r <= double(rows_below_critical)) {
            const double x = r / double(rows_below_critical);
            if (dense_at_critical_) return mu_c * x * x * (3.0 - 2.0 * x);
            return mu_c * x * std::sqrt(x);
        }
        const double y = (r - double(rows_below_critical)) / double(rows_above_);
        return mu_c + (1.0 - mu_c) * (dense_at_critical_ ? y * std::sqrt(y) : y);
    }

    /// The azimuth coordinate (0 to azimuths_ - 1) of the local direction w.
    [[nodiscard]] T azimuth_coordinate(const vec3<T>& w) const noexcept {
        return azimuth_position(w, smoother_y_, log_q2_) * T(azimuths_ - 1);
    }

    T mu_c_ = 0;               ///< critical cosine, 0 when eta_s > 1
    int rows_ = rows_without_critical;
    int plain_rows_ = rows_without_critical; ///< rows without a critical cosine (16, or 46 when dense)
    int rows_above_ = rows_above_critical; ///< intervals from mu_c to the normal
    int azimuths_ = azimuths;  ///< azimuth nodes per row (isotropic_azimuths, or strong_azimuths at strong anisotropy)
    T log_q2_ = 0;             ///< 2 log q, the azimuth spacing's parameter
    bool smoother_y_ = false;  ///< alpha_x > alpha_y: the smoother axis is y
    bool dense_at_critical_ = false; ///< rows dense toward mu_c from both sides (constructor)
    // The average of the class comment's definition from at()'s reads: (2 / pi)
    // int_0^{pi/2} int_0^1 at mu dmu dphi over a quarter of the azimuths (the values are even
    // in both axes), midpoint rule on 512 x 90 reads.
    [[nodiscard]] T average_of_reads() const noexcept {
        constexpr int mu_steps = 512, phi_steps = 90;
        double sum = 0.0;
        for (int a = 0; a < phi_steps; ++a) {
            const double phi = (double(a) + 0.5) * (0.5 * pi<double> / phi_steps);
            for (int k = 0; k < mu_steps; ++k) {
                const double mu = (double(k) + 0.5) / mu_steps;
                const double st = std::sqrt((1.0 - mu) * (1.0 + mu));
                sum += mu * double(at(vec3<T>(T(st * std::cos(phi)), T(st * std::sin(phi)), T(mu))));
            }
        }
        return T(glm::clamp(2.0 * sum / (double(mu_steps) * phi_steps), 0.0, 1.0));
    }

    T average_ = 1;
    T added_ = 0;              ///< the margin every node holds
    float e_[max_rows_dense * strong_azimuths]{}; ///< row by row, azimuths_ values each
    /// lift_cells' lifts, cell (i, j) at i (strong_azimuths - 1) + j; empty without lifts.
    heap_value<std::array<float, (max_rows_dense - 1) * (strong_azimuths - 1)>> lift_{};
};

} // namespace detail

/// The total single-scattering albedo E_s(w) = R + T (importance mode) of one
/// shade::rough_dielectric over GGX, seen from either side, integrated on a grid of views
/// when the grid is built; what shade::compensated_rough_dielectric reads instead of its
/// tables when it is given one (its class comment).
///
/// The tables of compensated_rough_dielectric hold E_s for isotropic GGX and an anisotropic
/// correction interpolated over (alpha_x, alpha_y, eta, mu, azimuth); at strong anisotropy
/// and from the denser side that interpolation misses E_s by up to several per cent (the
/// white furnace of an anisotropic interface then reads 0.94 to 1.002). A grid of one
/// interface needs no interpolation over the interface's parameters, only over the view:
///
/// - rows in mu = |n·w|: without total internal reflection (eta_s = n_far / n_s > 1) 16 rows
///   at mu = x^1.5, x = 0, 1/15, ..., 1 (denser toward grazing); with it (eta_s < 1) the
///   critical cosine mu_c = sqrt(1 - eta_s^2), where E_s has a kink, is a row, with 24 rows
///   below it at mu_c x^1.5 and 12 evenly spaced above;
/// - 37 azimuths per row (73 at strong anisotropy, alpha_max / alpha_min >= 20; 2 for an
///   isotropic interface, whose E_s does not depend on the azimuth), in
///   s = cos^2 of the angle from the rougher axis (sin^2 when alpha_y > alpha_x), spaced by
///   the half-sum of s and log(1 + (q^2 - 1) s) / log(q^2), q = min(alpha_max / alpha_min,
///   20), so that they crowd toward the smoother axis, where E_s changes fastest;
/// - each node the midpoint rule of detail::dielectric_visible_albedo on 48 x 48 visible
///   normals, plus detail::rough_dielectric_albedo_grid_margin (at strong anisotropy
///   detail::rough_dielectric_albedo_grid_margin_strong); a read interpolates bilinearly in
///   those coordinates and is clamped to [0, 1].
///
/// E_s,avg = 2 int E_s(w) mu dw / (2 pi) over the hemisphere (the compensation's average) is
/// integrated from the grid's own reads. Building takes about 0.3 s at -O2 (some 2,000 nodes
/// on 48^2 visible normals each; twice that at strong anisotropy); the object holds about
/// 29 KB. Meant to be built once per material, not per shading point. An isotropic interface
/// takes about a twentieth of that (its two azimuth nodes agree within the midpoint rule's
/// error, a few 1e-4).
template <std::floating_point T>
class rough_dielectric_albedo_grid {
public:
    static constexpr int azimuths = detail::dielectric_side_grid<T>::azimuths; ///< azimuth nodes per row
    /// azimuth nodes per row at strong anisotropy
    static constexpr int strong_azimuths = detail::dielectric_side_grid<T>::strong_azimuths;
    /// rows on a side with total internal reflection
    static constexpr int max_rows = detail::dielectric_side_grid<T>::max_rows;
    static constexpr int cells = 48; ///< visible normals per axis at each node

    /// The grid of rough_dielectric(distribution, eta). Throws shade::invalid_parameter
    /// naming "eta" unless eta lies in [1e-4, 1e4] and is not 1 (as rough_dielectric).
    rough_dielectric_albedo_grid(const ggx<T>& distribution, T eta)
        : distribution_(distribution), eta_(require_in_range("eta", eta, dielectric_eta_min<T>, dielectric_eta_max<T>)) {
        if (eta == T(1))
            throw invalid_parameter("eta", "must not be 1 (an index-matched interface is a delta: smooth_dielectric)",
                                    detail::to_text(eta));
        const double alpha_x = double(distribution.alpha_x()), alpha_y = double(distribution.alpha_y());
        const ggx<double> d(unchecked, alpha_x, alpha_y);
        for (int s = 0; s < 2; ++s) {
            const double eta_s = s == 0 ? double(eta) : 1.0 / double(eta);
            side_[s] = detail::dielectric_side_grid<T>(
                alpha_x, alpha_y, eta_s, detail::rough_dielectric_albedo_grid_margin,
                detail::rough_dielectric_albedo_grid_margin_strong,
                [&d, eta_s](const vec3<double>& v) { return detail::dielectric_visible_albedo(d, v, eta_s, cells); });
        }
    }

    /// The grid of rough_dielectric(distribution, eta) on one side only, the side `inside`
    /// (false: outside) given as `side` (its values E_s on that side's views, as the
    /// constructor above integrates them; shade's materials fill it in the same pass as the
    /// side's reflection albedo, detail::anisotropic_reflection_albedo_grid). The other side
    /// is not integrated: compensated_rough_dielectric reads its tables there (integrated()).
    /// Throws shade::invalid_parameter naming "eta" as the constructor above.
    rough_dielectric_albedo_grid(const ggx<T>& distribution, T eta, bool inside, const detail::dielectric_side_grid<T>& side)
        : distribution_(distribution), eta_(require_in_range("eta", eta, dielectric_eta_min<T>, dielectric_eta_max<T>)) {
        if (eta == T(1))
            throw invalid_parameter("eta", "must not be 1 (an index-matched interface is a delta: smooth_dielectric)",
                                    detail::to_text(eta));
        side_[inside ? 1 : 0] = side;
        integrated_[inside ? 1 : 0] = true;
        integrated_[inside ? 0 : 1] = false;
    }

    /// Whether E_s of medium `inside` (false: outside) is integrated on the grid: both sides
    /// unless the grid was built for one side only.
    [[nodiscard]] bool integrated(bool inside) const noexcept { return integrated_[inside ? 1 : 0]; }

    /// The distribution the grid was built for.
    [[nodiscard]] constexpr const ggx<T>& distribution() const noexcept { return distribution_; }
    /// The relative index n_inside / n_outside the grid was built for.
    [[nodiscard]] constexpr T eta() const noexcept { return eta_; }

    /// Whether the grid was built for exactly this distribution and eta.
    [[nodiscard]] bool built_for(const ggx<T>& distribution, T eta) const noexcept {
        return distribution.alpha_x() == distribution_.alpha_x() && distribution.alpha_y() == distribution_.alpha_y() &&
               eta == eta_;
    }

    /// E_s(w) for the local direction w (n = +z, the tangent along +x) in medium `inside`
    /// (false: outside); only |w.z| and w's azimuth are read, so w may point either way.
    /// Dimensionless, in [0, 1]; the grid's margin included. 1 on a side that is not
    /// integrated().
    [[nodiscard]] T albedo(bool inside, const vec3<T>& w) const noexcept {
        return integrated_[inside ? 1 : 0] ? side_[inside ? 1 : 0].at(w) : T(1);
    }

    /// E_s,avg of medium `inside`: the cosine-weighted hemispherical average of albedo() (1 on
    /// a side that is not integrated()).
    [[nodiscard]] T average(bool inside) const noexcept {
        return integrated_[inside ? 1 : 0] ? side_[inside ? 1 : 0].average() : T(1);
    }

private:
    ggx<T> distribution_;
    T eta_;
    detail::dielectric_side_grid<T> side_[2]{};
    bool integrated_[2] = {true, true};
};

} // namespace shade
