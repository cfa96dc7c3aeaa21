#pragma once
// A dielectric albedo table (shade/bsdf/dielectric_albedo_table.hpp) read at one roughness
// and index for many view cosines: the interpolation along sqrt(alpha) and the index is done
// once, into one row over the view coordinate, so that each lookup is one spline in mu.

#include <array>
#include <cmath>
#include <concepts>
#include <cstddef>

#include <glm/common.hpp>

#include <shade/brdf/fresnel.hpp>
#include <shade/brdf/microfacet/cosine_weights.hpp>
#include <shade/bsdf/detail/dielectric_albedo_data.hpp>
#include <shade/bsdf/detail/dielectric_reflection_albedo_data.hpp>
#include <shade/bsdf/dielectric_albedo_table.hpp>

namespace shade::detail {

/// Four interpolation weights, one per node i - 1 .. i + 2 (catmull_rom_axis_weights).
template <std::floating_point T>
struct axis_weights {
    T w[4]; ///< the weights of nodes i - 1 .. i + 2
    [[nodiscard]] constexpr T& operator[](std::size_t i) noexcept { return w[i]; }
    [[nodiscard]] constexpr T operator[](std::size_t i) const noexcept { return w[i]; }
};

/// The weights of catmull_rom_axis on the nodes i - 1 .. i + 2 of an axis piece lo..hi at
/// t (the same combination of node values, so a row combined with them and then read
/// along another axis equals the table read along both): the cubic's weights
/// ((-t + 2t^2 - t^3), (2 - 5t^2 + 3t^3), (t + 4t^2 - 3t^3), (-t^2 + t^3)) / 2, with a
/// neighbour outside the piece replaced by its linear extrapolation as catmull_rom_axis does.
template <std::floating_point T>
[[nodiscard]] inline axis_weights<T> catmull_rom_axis_weights(std::size_t i, std::size_t lo, std::size_t hi, T t) noexcept {
    const T t2 = t * t, t3 = t2 * t;
    axis_weights<T> w{{T(0.5) * (-t + T(2) * t2 - t3), T(0.5) * (T(2) - T(5) * t2 + T(3) * t3),
                       T(0.5) * (t + T(4) * t2 - T(3) * t3), T(0.5) * (-t2 + t3)}};
    if (i <= lo) { // p0 = 2 p1 - p2
        w[1] += T(2) * w[0];
        w[2] -= w[0];
        w[0] = T(0);
    }
    if (i + 1 >= hi) { // p3 = 2 p2 - p1
        w[2] += T(2) * w[3];
        w[1] -= w[3];
        w[3] = T(0);
    }
    return w;
}

/// A table of grid G read at a fixed located cell (roughness and index): the values at every
/// view node, interpolated along sqrt(alpha) and the index as dielectric_albedo_interpolate
/// does, so that at(mu) returns what dielectric_albedo_interpolate(table, g, cell, mu) does
/// (to rounding) with one spline along the view coordinate. Not clamped.
template <std::floating_point T, std::size_t MuNodes>
class dielectric_albedo_row {
public:
    dielectric_albedo_row() = default;

    /// The row of `table` (grid g, whose mu_nodes must be MuNodes) at cell.
    dielectric_albedo_row(const float* table, const dielectric_albedo_grid& g, const dielectric_albedo_cell<T>& cell)
        : cell_(cell), near_critical_(g.near_critical) {
        const auto alpha_w = catmull_rom_axis_weights<T>(cell.alpha.i, 0, g.alpha_nodes - 1, cell.alpha.t);
        axis_weights<T> eta_w{};
        if (g.eta_spline) {
            eta_w = catmull_rom_axis_weights<T>(cell.eta.i, 0, g.eta_nodes - 1, cell.eta.t);
        } else {
            eta_w = {{T(0), T(1) - cell.eta.t, cell.eta.t, T(0)}};
        }
        for (std::size_t a = 0; a < 4; ++a) {
            if (eta_w[a] == T(0)) continue;
            const std::size_t k = cell.eta.i + a - 1;
            for (std::size_t b = 0; b < 4; ++b) {
                if (alpha_w[b] == T(0)) continue;
                const std::size_t j = cell.alpha.i + b - 1;
                const float* row = table + g.row(cell.side, k, j);
                const T w = eta_w[a] * alpha_w[b];
                for (std::size_t i = 0; i < MuNodes; ++i) row_[i] += w * T(row[i]);
            }
        }
    }

    /// The table at view cosine mu (clamped to [0, 1]), not clamped.
    [[nodiscard]] T at(T mu) const noexcept {
        const T m = glm::clamp(mu, T(0), T(1));
        return at_coordinate(
            dielectric_albedo_view(m, cell_.alpha_clamped, cell_.eta_clamped, cell_.side, near_critical_));
    }

    /// at(mu) for a caller that has fresnel = F_dielectric(m, eta_s) already, m = mu clamped
    /// to [0, 1] and eta_s the cell's clamped index (eta_clamped on side 0, 1 / eta_clamped
    /// on side 1), which the view coordinate reads (dielectric_albedo_view_with).
    [[nodiscard]] T at(T mu, T fresnel) const noexcept {
        const T m = glm::clamp(mu, T(0), T(1));
        return at_coordinate(dielectric_albedo_view_with(m, cell_.alpha_clamped, cell_.eta_clamped, cell_.side,
                                                         near_critical_, [fresnel] { return fresnel; }));
    }

    /// The cell's clamped index ratio eta_s the view coordinate's Fresnel term is taken at.
    [[nodiscard]] T view_eta() const noexcept {
        return cell_.side == 0 ? cell_.eta_clamped : T(1) / cell_.eta_clamped;
    }

private:
    // The spline along the row at the view coordinate t.
    [[nodiscard]] T at_coordinate(T t) const noexcept {
        const auto c = albedo_grid_locate(t, MuNodes);
        const std::size_t last = MuNodes - 1;
        const std::size_t middle = cell_.side == 1 && last % 2 == 0 ? last / 2 : last;
        const std::size_t lo = c.i < middle ? 0 : middle;
        const std::size_t hi = c.i < middle ? middle : last;
        return catmull_rom_axis<T>([this](std::size_t i) { return row_[i]; }, c.i, lo, hi, c.t);
    }

    dielectric_albedo_cell<T> cell_{};
    T row_[MuNodes]{};
    bool near_critical_ = false;
};

/// The change of the GGX reflection lobe's albedo when its Fresnel factor goes from the
/// exact dielectric F(c, eta_end) to F(c, eta_s), c = v·h, for the view cosine mu and
/// roughness alpha (clamped to [0, 1]):
///
///     sum_k w_k(mu, alpha) (F(c_k, eta_s) - F(c_k, eta_end)),
///
/// w_k the lobe's measure of c at the nodes c_k (shade/brdf/microfacet/cosine_weights.hpp:
/// the lobe and the height-correlated masking of the reflection table). The reflection
/// albedo beyond the table's largest eta_hat is the table's at eta_end (its end on the same
/// side) plus this. 128 Fresnel evaluations.
template <std::floating_point T>
[[nodiscard]] inline T reflection_albedo_change(T mu, T alpha, T eta_end, T eta_s) noexcept {
    std::array<rgb<T>, cosine_weight_nodes> change;
    for (std::size_t k = 0; k < cosine_weight_nodes; ++k) {
        const T c = T(cosine_weight_node(k));
        change[k] = rgb<T>(F_dielectric(c, eta_s) - F_dielectric(c, eta_end));
    }
    return fresnel_albedo_at(glm::clamp(alpha, T(0), T(1)), mu, change).e.x;
}

/// shade::dielectric_reflection_albedo(unchecked, mu, alpha, eta_s) at a fixed alpha and
/// eta_s for many mu: the same reading of the same table (its row 0 standing for alpha -> 0,
/// F(mu, eta_s) added back, the difference scaled toward 0 below the grid's smallest
/// eta_hat, reflection_albedo_change beyond its largest), with the interpolation along
/// alpha and the index done once.
template <std::floating_point T>
class reflection_albedo_row {
public:
    reflection_albedo_row() = default;

    /// The reflection albedo at roughness alpha >= 0 and index ratio eta_s > 0 (unchecked).
    reflection_albedo_row(T alpha, T eta_s) : eta_s_(eta_s) {
        constexpr const dielectric_albedo_grid& grid = dielectric_reflection_albedo_grid;
        const T eta_hat = eta_s > T(1) ? eta_s : T(1) / eta_s;
        dielectric_albedo_cell<T> cell = dielectric_albedo_locate(grid, alpha, eta_s);
        cell.alpha = albedo_grid_locate(std::sqrt(glm::clamp(alpha, T(0), T(1))), grid.alpha_nodes);
        row_ = dielectric_albedo_row<T, dielectric_reflection_albedo_grid.mu_nodes>(
            ggx_rough_dielectric_reflection_albedo, grid, cell);
        if (eta_hat < T(grid.eta_min)) scale_ = (eta_hat - T(1)) / T(grid.eta_min - 1);
        view_reads_fresnel_ = row_.view_eta() == eta_s;
        beyond_ = eta_hat > T(grid.eta_max);
        alpha_ = alpha;
    }

    /// R_ss(mu), dimensionless, in [0, 1].
    [[nodiscard]] T at(T mu) const noexcept {
        const T m = glm::clamp(mu, T(0), T(1));
        return at(m, F_dielectric(m, eta_s_));
    }

    /// at(mu) for a caller that has fresnel = F_dielectric(m, eta_s) already, m = mu clamped
    /// to [0, 1]: F is then computed once, for the value and for the table's view
    /// coordinate (which reads F at the same index unless eta_s lies outside the grid).
    [[nodiscard]] T at(T mu, T fresnel) const noexcept {
        const T m = glm::clamp(mu, T(0), T(1));
        const T e = view_reads_fresnel_ ? row_.at(m, fresnel) : row_.at(m);
        if (!beyond_) return glm::clamp(fresnel + scale_ * e, T(0), T(1));
        // Beyond the grid: the table's R_ss at its end eta_end on this side, which the row
        // holds, plus the change of the lobe's albedo from F(eta_end) to F(eta_s).
        const T eta_end = row_.view_eta();
        return glm::clamp(F_dielectric(m, eta_end) + e + reflection_albedo_change(m, alpha_, eta_end, eta_s_), T(0),
                          T(1));
    }

private:
    dielectric_albedo_row<T, dielectric_reflection_albedo_grid.mu_nodes> row_{};
    T eta_s_ = T(1);
    T scale_ = T(1);
    T alpha_ = T(0);
    bool view_reads_fresnel_ = false; // the view coordinate's F is F_dielectric(m, eta_s_)
    bool beyond_ = false;             // eta_hat above the grid: reflection_albedo_change added
};

} // namespace shade::detail
