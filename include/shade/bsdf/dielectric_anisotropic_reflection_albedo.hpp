#pragma once
// shade::dielectric_reflection_albedo for a view's direction on an anisotropic GGX interface:
// the reflection albedo of shade/bsdf/dielectric_reflection_albedo.hpp read at the view's
// azimuth, with a tabulated correction (data in
// shade/bsdf/detail/dielectric_anisotropic_reflection_albedo_data.hpp). A header of its own so
// that the isotropic form stays cheap for the models that need only it.

#include <array>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <type_traits>

#include <glm/common.hpp>

#include <shade/brdf/fresnel.hpp>
#include <shade/brdf/microfacet/cosine_weights.hpp>
#include <shade/bsdf/detail/dielectric_anisotropic_reflection_albedo_data.hpp>
#include <shade/bsdf/dielectric_albedo_table.hpp>
#include <shade/bsdf/dielectric_anisotropic_reflection_table.hpp>
#include <shade/bsdf/dielectric_reflection_albedo.hpp>
#include <shade/bsdf/rough_dielectric_albedo_grid.hpp>
#include <shade/core/error.hpp>
#include <shade/core/heap_value.hpp>
#include <shade/core/types.hpp>

namespace shade {

namespace detail {

/// The roughness at which the anisotropic reflection albedo reads the isotropic table for the
/// local direction w: the roughness projected on w's azimuth phi (from t),
/// sqrt(alpha_x^2 cos^2 phi + alpha_y^2 sin^2 phi), the alpha of the isotropic surface whose
/// masking of w is the anisotropic one's (Heitz 2014, "Understanding the Masking-Shadowing
/// Function in Microfacet-Based BRDFs", JCGT 3(2), eq. 80). At the pole (w along n), where
/// the azimuth is undefined, the smoother alpha: the azimuth 0 from the smoother axis at
/// which the correction table is read there, so that the two agree.
template <std::floating_point T>
[[nodiscard]] inline T reflection_projected_alpha(T alpha_x, T alpha_y, const vec3<T>& w) noexcept {
    const T s2 = w.x * w.x + w.y * w.y;
    if (!(s2 > T(0))) return glm::min(alpha_x, alpha_y);
    return std::sqrt((alpha_x * alpha_x * w.x * w.x + alpha_y * alpha_y * w.y * w.y) / s2);
}

/// The roughness at which the anisotropic reflection albedo reads the isotropic table for the
/// local direction w: seen from the rarer side (eta_s > 1) the projected roughness
/// (reflection_projected_alpha); from the denser side the root mean square
/// sqrt((alpha_x^2 + alpha_y^2) / 2), the projected roughness averaged over the azimuth. From
/// the denser side the isotropic table steps from 1 to F across the critical angle within
/// about alpha of it, and a view along the smoother axis of a 1-D rough surface would read
/// that step where the surface itself, rough across, has none.
template <std::floating_point T>
[[nodiscard]] inline T reflection_base_alpha(T alpha_x, T alpha_y, T eta_s, const vec3<T>& w) noexcept {
    if (eta_s > T(1)) return reflection_projected_alpha(alpha_x, alpha_y, w);
    return std::sqrt(T(0.5) * (alpha_x * alpha_x + alpha_y * alpha_y));
}

/// The anisotropic reflection albedo of one interface (roughnesses alpha_x, alpha_y >= 0,
/// index ratio eta_s > 0; unchecked) for many directions: what
/// shade::dielectric_reflection_albedo(unchecked, w, alpha_x, alpha_y, eta_s) returns, with
/// the correction's cell located once. Where the correction's grid ends: below eta_hat =
/// 1.05 the correction is scaled by (eta_hat - 1) / 0.05, so that an index-matched
/// interface reflects nothing; above 3 it is read at 3 (far off there: a caller that reads
/// many views of one interface has anisotropic_reflection_albedo_grid); alpha_max above sqrt 2
/// reads sqrt 2.
/// Any anisotropy is on the grid (s = alpha_min / alpha_max in [0, 1]).
template <std::floating_point T>
class anisotropic_reflection_albedo {
public:
    anisotropic_reflection_albedo() = default;

    anisotropic_reflection_albedo(T alpha_x, T alpha_y, T eta_s) noexcept
        : alpha_x_(alpha_x), alpha_y_(alpha_y), eta_s_(eta_s) {
        const T eta_hat = eta_s > T(1) ? eta_s : T(1) / eta_s;
        // Equal alphas (or both 0: a smooth interface) need no correction.
        if (alpha_x == alpha_y || eta_hat == T(1)) return;
        cell_ = reflection_anisotropic_locate(alpha_x, alpha_y, eta_s);
        scale_ = glm::min((eta_hat - T(1)) / T(dielectric_albedo_eta_min - 1), T(1));
    }

    /// R_ss(w) for the unit local direction w on the view's side (only its azimuth and |w.z|
    /// are used), read with the correction `delta` (a table of reflection_anisotropic_size
    /// values on the grid of shade/bsdf/dielectric_anisotropic_reflection_table.hpp; the
    /// committed one by default). Dimensionless, in [0, 1].
    [[nodiscard]] T at(const vec3<T>& w, const float* delta = ggx_dielectric_anisotropic_reflection_delta) const noexcept {
        const T mu = glm::min(std::abs(w.z), T(1));
        const T alpha = alpha_x_ == alpha_y_ ? alpha_x_ : reflection_base_alpha(alpha_x_, alpha_y_, eta_s_, w);
        T r = dielectric_reflection_albedo(unchecked, mu, alpha, eta_s_);
        if (scale_ > T(0)) r += scale_ * reflection_anisotropic_delta(delta, cell_, w.x, w.y, mu);
        return glm::clamp(r, T(0), T(1));
    }

private:
    T alpha_x_ = 0, alpha_y_ = 0, eta_s_ = 1;
    T scale_ = 0; // the correction's factor: 0 when isotropic or index-matched
    reflection_anisotropic_cell<T> cell_{};
};

/// The albedo E_F(w) = E_m[F(v·m) G2(v, l) / G1(v)] of an anisotropic GGX reflection lobe
/// (alphas alpha_x != alpha_y, both > 0) for a Fresnel term F with a kink at the cosine
/// `kink` (total internal reflection: F = 1 below it), on the views around that cosine, much
/// finer in mu than a dielectric_side_grid's rows: a narrow lobe's E_F steps from 1 toward
/// F(mu) within about alpha sin(theta) of the kink (alpha the roughness projected on the
/// view's azimuth), which rows a few thousandths of mu apart bridge with chords that read it
/// low below the kink (where it is concave; docs/conventions.md has the measurements). F has
/// 1 or 3 channels (R_ss with the interface's own F_dielectric; a thin film's F per colour
/// channel). The window spans
/// `below` under the kink and `above` over it on `cells` cells even in x in [-1, 1],
/// mu = kink + d x |x| (d the side's span): the kink is the middle node and the cells crowd
/// toward it quadratically. In azimuth it has `azimuths` nodes (strong_azimuths at strong
/// anisotropy) at the side grid's azimuth coordinate (dielectric_side_grid::azimuth_warp,
/// crowded toward the smoother axis). E_F is computed on the nodes' azimuths and on the
/// azimuths halfway between them, at `samples` points per cell in mu (the cells' ends among
/// them), each by visit_ggx_cosine_measure on strata_narrow^2 cells (strata_wide^2 for
/// alpha_max above narrow_alpha). A read is bilinear between the four nodes of its cell plus
/// the cell's lift, lift_factor times the most E_F rises above the bilinear read at the
/// cell's points (the nodes' azimuths between their ends and the halfway azimuth along the
/// whole cell), plus `margin` (for the quadrature's error), at most 1: at or above E_F.
/// at_or_below() reads the bilinear value less the cell's drop (the same for E_F below it),
/// close to E_F and not above it but for the quadrature's error. Per channel. Empty
/// (contains() false) until built; a built window keeps its values in a heap block (about 10
/// KB per channel for float), copies copy it.
template <std::floating_point T>
class anisotropic_kink_window {
public:
    static constexpr std::size_t cells = 48;    ///< cells in mu (even: the kink a node)
    static constexpr std::size_t samples = 3;   ///< E_F's points per cell in mu, one end included
    static constexpr std::size_t azimuths = 9;  ///< azimuth nodes
    /// Azimuth nodes at strong anisotropy (dielectric_side_grid::strong: alpha_max / alpha_min
    /// >= 20), where E_F turns within a few degrees of the smoother axis.
    static constexpr std::size_t strong_azimuths = 17;
    static constexpr std::size_t max_channels = 3; ///< F's channels at most
    /// The quadrature's cells per side at each point for alpha_max <= narrow_alpha.
    static constexpr std::size_t strata_narrow = 32;
    /// The same for wider lobes (the midpoint rule's error near the kink grows with
    /// alpha_max, beyond the margin at 32^2; docs/conventions.md).
    static constexpr std::size_t strata_wide = 48;
    static constexpr double narrow_alpha = 0.02; ///< (strata_narrow)
    /// A cell's lift (drop) over its largest sampled rise (fall): the points between the
    /// samples may rise further.
    static constexpr double lift_factor = 1.25;

    anisotropic_kink_window() = default;

    /// The window of the lobe of alphas alpha_x != alpha_y (both > 0) for the Fresnel term
    /// F (a callable double c -> std::array<double, 3>, of which the first `channels`, 1 to
    /// max_channels, are read) with its kink at the cosine `kink` in (0, 1), over
    /// [kink - below, kink + above] (both >= 0; clamped to [0, 1]), its reads at() raised by
    /// `margin`. Unchecked.
    template <class Fresnel>
    anisotropic_kink_window(double alpha_x, double alpha_y, double kink, double below, double above, double margin,
                            std::size_t channels, const Fresnel& F) {
        azimuths_ = dielectric_side_grid<T>::strong(alpha_x, alpha_y) ? strong_azimuths : azimuths;
        channels_ = glm::clamp(channels, std::size_t(1), max_channels);
        constexpr std::size_t points = cells * samples + 1;
        const std::size_t lines = 2 * azimuths_ - 1;
        const double q = glm::min(glm::max(alpha_x, alpha_y) / glm::min(alpha_x, alpha_y), 20.0);
        // The side grid's parameter, rounded to T as the grid rounds it, so that the two
        // place their azimuth nodes alike.
        log_q2_ = T(2 * std::log(q));
        smoother_y_ = alpha_x > alpha_y;
        kink_ = glm::clamp(kink, 0.0, 1.0);
        below_ = glm::clamp(below, 0.0, kink_);
        above_ = glm::clamp(above, 0.0, 1.0 - kink_);
        margin_ = T(margin);
        const std::size_t strata = glm::max(alpha_x, alpha_y) <= narrow_alpha ? strata_narrow : strata_wide;
        // E_F on every line (line 2a the node azimuth a, line 2a + 1 halfway to a + 1) at
        // every point in mu, per channel; on the heap while built (up to about 300 KB).
        struct values {
            double* data = new double[(2 * strong_azimuths - 1) * points * max_channels];
            ~values() { delete[] data; }
        } e;
        const auto value = [&e](std::size_t line, std::size_t k, std::size_t ch) -> double& {
            return e.data[(line * points + k) * max_channels + ch];
        };
        for (std::size_t line = 0; line < lines; ++line) {
            const double target = double(line) / double(lines - 1);
            const double s = dielectric_side_grid<T>::azimuth_of_warp(target, double(log_q2_));
            const double cos2 = smoother_y_ ? s : 1.0 - s;
            const double cx = std::sqrt(cos2), cy = std::sqrt(glm::max(0.0, 1.0 - cos2));
            for (std::size_t k = 0; k < points; ++k) {
                const double mu = glm::clamp(point_mu(k, points), 1e-4, 1.0);
                const double st = std::sqrt((1.0 - mu) * (1.0 + mu));
                std::array<double, max_channels> sum{};
                visit_ggx_cosine_measure(vec3<double>(st * cx, st * cy, mu), alpha_x, alpha_y, strata,
                                         [&sum, &F, this](double c, double weight) {
                                             const std::array<double, max_channels> f = F(c);
                                             for (std::size_t ch = 0; ch < channels_; ++ch) sum[ch] += weight * f[ch];
                                         });
                for (std::size_t ch = 0; ch < channels_; ++ch) value(line, k, ch) = sum[ch];
            }
        }
        table& out = table_.emplace();
        for (std::size_t ch = 0; ch < channels_; ++ch) {
            for (std::size_t a = 0; a < azimuths_; ++a)
                for (std::size_t j = 0; j <= cells; ++j) out.nodes[node(j, a, ch)] = T(value(2 * a, j * samples, ch));
            for (std::size_t j = 0; j < cells; ++j) {
                for (std::size_t a = 0; a + 1 < azimuths_; ++a) {
                    const double n00 = value(2 * a, j * samples, ch), n01 = value(2 * a, (j + 1) * samples, ch);
                    const double n10 = value(2 * a + 2, j * samples, ch), n11 = value(2 * a + 2, (j + 1) * samples, ch);
                    double rise = 0, fall = 0;
                    for (std::size_t side = 0; side <= 2; ++side) {
                        const double b = 0.5 * double(side);
                        for (std::size_t k = 0; k <= samples; ++k) {
                            const double t = double(k) / double(samples);
                            const double bilinear = (1 - b) * ((1 - t) * n00 + t * n01) + b * ((1 - t) * n10 + t * n11);
                            const double d = value(2 * a + side, j * samples + k, ch) - bilinear;
                            rise = glm::max(rise, d);
                            fall = glm::max(fall, -d);
                        }
                    }
                    out.lift[cell_index(j, a, ch)] = T(lift_factor * rise);
                    out.drop[cell_index(j, a, ch)] = T(lift_factor * fall);
                }
            }
        }
    }

    /// Whether the window is empty (not built).
    [[nodiscard]] bool empty() const noexcept { return !table_.has_value(); }

    /// Whether the cosine |w.z| of a view lies in the window (false when empty or NaN).
    [[nodiscard]] bool contains(T mu) const noexcept {
        return table_.has_value() && double(mu) >= kink_ - below_ && double(mu) <= kink_ + above_;
    }

    /// E_F of channel ch (< the constructor's channels) at the local direction w
    /// (contains(|w.z|); only |w.z| and w's azimuth are read): the bilinear read plus the
    /// cell's lift and the margin, in [0, 1].
    [[nodiscard]] T at(const vec3<T>& w, std::size_t ch = 0) const noexcept {
        const cell c = cell_of(w);
        return glm::clamp(bilinear(c, ch) + table_->lift[cell_index(c.j, c.a, ch)] + margin_, T(0), T(1));
    }

    /// E_F of channel ch at w (as at()) read at or below it up to the quadrature's error: the
    /// bilinear read less the cell's drop, in [0, 1].
    [[nodiscard]] T at_or_below(const vec3<T>& w, std::size_t ch = 0) const noexcept {
        const cell c = cell_of(w);
        return glm::clamp(bilinear(c, ch) - table_->drop[cell_index(c.j, c.a, ch)], T(0), T(1));
    }

private:
    // mu of point k of `points` along a line: x = -1 + 2 k / (points - 1), kink + d x |x|.
    [[nodiscard]] double point_mu(std::size_t k, std::size_t points) const noexcept {
        const double x = -1.0 + 2.0 * double(k) / double(points - 1);
        return kink_ + (x < 0 ? below_ : above_) * x * std::abs(x);
    }

    // Where node (j in mu, a in azimuth) of channel ch, and cell (j, a)'s lift and drop, are
    // kept.
    [[nodiscard]] std::size_t node(std::size_t j, std::size_t a, std::size_t ch) const noexcept {
        return (ch * (cells + 1) + j) * azimuths_ + a;
    }
    [[nodiscard]] std::size_t cell_index(std::size_t j, std::size_t a, std::size_t ch) const noexcept {
        return (ch * cells + j) * (azimuths_ - 1) + a;
    }

    // The cell (j in mu, a in azimuth) holding w and the weights t of node j + 1 and b of
    // node a + 1.
    struct cell {
        std::size_t j, a;
        T t, b;
    };
    [[nodiscard]] cell cell_of(const vec3<T>& w) const noexcept {
        const T mu_t = std::abs(w.z);
        const double mu = mu_t <= T(1) ? double(mu_t) : 1.0;
        const double offset = mu - kink_;
        const double side = offset < 0 ? below_ : above_;
        const double x = side > 0 ? (offset < 0 ? -1.0 : 1.0) * std::sqrt(glm::min(std::abs(offset) / side, 1.0)) : 0.0;
        const double u = (x + 1.0) * 0.5 * double(cells);
        const std::size_t j = glm::min(std::size_t(glm::max(u, 0.0)), cells - 1);
        const double p = double(dielectric_side_grid<T>::azimuth_position(w, smoother_y_, log_q2_)) * double(azimuths_ - 1);
        const std::size_t a = glm::min(std::size_t(glm::max(p, 0.0)), azimuths_ - 2);
        return {j, a, T(glm::clamp(u - double(j), 0.0, 1.0)), T(glm::clamp(p - double(a), 0.0, 1.0))};
    }

    [[nodiscard]] T bilinear(const cell& c, std::size_t ch) const noexcept {
        const T* row = table_->nodes.data() + node(c.j, c.a, ch);
        const T low = (T(1) - c.b) * row[0] + c.b * row[1];
        const T high = (T(1) - c.b) * row[azimuths_] + c.b * row[azimuths_ + 1];
        return (T(1) - c.t) * low + c.t * high;
    }

    // The nodes' E_F (channel by channel, row j of azimuths_ values), and each cell's lift and
    // drop (channel by channel, row j of azimuths_ - 1 values).
    struct table {
        std::array<T, max_channels * (cells + 1) * strong_azimuths> nodes{};
        std::array<T, max_channels * cells * (strong_azimuths - 1)> lift{}, drop{};
    };

    double kink_ = 0, below_ = 0, above_ = 0;
    T log_q2_ = 0;
    T margin_ = 0;
    std::size_t azimuths_ = azimuths; // azimuth nodes (strong_azimuths at strong anisotropy)
    std::size_t channels_ = 1;
    bool smoother_y_ = false;
    heap_value<table> table_{}; // empty: not built
};

/// anisotropic_reflection_albedo for a caller that reads many views of one interface (a
/// material), with the correction computed at construction where the table's index range
/// ends on the rarer side: for eta_s > 3 (the table's eta_hat_max) and alpha_x != alpha_y,
///
///     R_ss(w) = R_ss,iso(mu, a(w), eta_s) + Delta(w) + beyond_margin,
///
/// a(w) the roughness projected on w's azimuth clamped to 1 (the isotropic table's largest
/// alpha; the table itself continues above eta_hat 3) and Delta read bilinearly from the views
/// of an anisotropic_view_grid, at each of which it is the anisotropic lobe's albedo with the
/// exact Fresnel factor F(c, eta_s), integrated by visit_ggx_cosine_measure on
/// beyond_cells^2 cells, less the isotropic table at a(node): the table carries the fine
/// structure in mu, so the difference is smooth enough for the coarse grid. The margin keeps
/// the reading at or above the true albedo (a material's white furnace reads 1 + true -
/// read; the quadrature's error at 32^2 cells, largest where the measure is cut at the
/// horizon, is within [-2e-3, +5e-3], docs/conventions.md). Cost beyond 3: 208 x
/// beyond_cells^2 visits of the visible-normal sampler at construction (about 8 ms); at() then
/// one isotropic table read and a bilinear read.
///
/// From the denser side (eta_s < 1, alpha_x != alpha_y, both > 0) the table errs most: near
/// index match (1 / 1.05 < eta_s < 1), where its correction is extrapolated (scaled toward 0
/// at eta_s = 1), it misses the total reflection of grazing views along the smoother axis
/// (reading up to 0.5 low), and between 1 / 3 and 1 / 1.05 it reads from 0.03 low to 0.18
/// high. So R_ss is integrated per interface there: a dielectric_side_grid of the
/// interface's own views (rough_dielectric_albedo_grid's layout: the critical cosine on a
/// row, azimuths crowded toward the smoother axis; here with the rows on both sides of it
/// dense toward it as well), each node detail::dielectric_visible_albedo's reflected branch
/// on below_columns x below_rows visible normals, plus below_margin (below_margin_strong at
/// alpha_max / alpha_min >= 20), held on the heap (about 14 KB; copies copy it). Building
/// takes 100 to 180 ms at -O2. at() reads the grid, at or above R_ss; at_without_margin()
/// close to it from either side.
///
/// From the rarer side at strong anisotropy (eta_s > 1, alpha_max / alpha_min >= 20, the
/// side grid's strong anisotropy, and alpha_max >= strong_alpha_min) the table errs high by
/// up to 0.08 at grazing views within a few degrees of the smoother axis (its correction is
/// interpolated across a feature as narrow as alpha_min / alpha_max), and the correction
/// beyond 3, on the 13 azimuths of an anisotropic_view_grid, reads up to 0.05 low there. So
/// R_ss is integrated per interface there too: a dielectric_side_grid (16 rows in mu, 73
/// azimuths crowded toward the smoother axis), each node the reflected branch on
/// above_cells^2 visible normals, plus above_margin (read - true from -1.6e-3 to +9e-3
/// before it, docs/conventions.md); 20 to 50 ms at -O2. Elsewhere (eta_s in [1, 3]
/// otherwise, or equal alphas) exactly anisotropic_reflection_albedo. alpha_x, alpha_y >= 0,
/// eta_s > 0 (unchecked).
template <std::floating_point T>
class anisotropic_reflection_albedo_grid {
public:
    static constexpr std::size_t beyond_cells = 32; ///< the quadrature's cells per side
    /// What the reading beyond 3 adds to stay at or above the true albedo.
    static constexpr double beyond_margin = 2e-3;
    /// Visible normals at each node below 1: below_columns angles by below_rows in u_y (the
    /// angle resolves more: the horizon's and the total reflection's edges cross the columns).
    static constexpr int below_columns = 40;
    static constexpr int below_rows = 40; ///< (below_columns)
    /// What the reading below 1 adds to stay at or above the true albedo.
    static constexpr double below_margin = 5e-3;
    /// What the differences D_k add to stay at or above their true values.
    static constexpr double difference_margin = 2e-3;
    /// The tag of the constructor without another Fresnel term.
    struct no_other_fresnel_t {};
    static constexpr no_other_fresnel_t no_other_fresnel{};
    /// The largest alpha_min at which R_ss below 1 is read from an anisotropic_kink_window
    /// around the critical cosine (narrower lobes step there faster than the grid's rows
    /// resolve).
    static constexpr double window_alpha_max = 0.1;
    /// The grid's rows the window spans on either side of the critical cosine's row.
    static constexpr int window_rows = 3;
    /// How far (in the projected cosine sqrt(mu^2 + (1 - mu^2) s)) from the critical cosine
    /// the grid's cells get lifts below 1 (build_window).
    static constexpr double kink_band = 0.03;
    /// What the window's reads add for its quadrature's error.
    static constexpr double window_margin = 4e-3;
    /// below_margin at strong anisotropy (alpha_max / alpha_min >= 20).
    static constexpr double below_margin_strong = 1e-2;
    /// Visible normals per side at each node above 1 at strong anisotropy (no total
    /// reflection's edge to resolve there).
    static constexpr int above_cells = 32;
    /// What the reading above 1 at strong anisotropy adds to stay at or above the true albedo.
    static constexpr double above_margin = 3e-3;
    /// The least alpha_max at which the grid serves a strong anisotropy above 1: below it
    /// the table errs less than the grid's rows (at most about 8e-3 against up to 9e-3).
    static constexpr double strong_alpha_min = 0.25;

    /// Whether an interface of alphas alpha_x, alpha_y and index ratio eta_s reads R_ss from
    /// a grid of its own views (the class comment: below 1 when anisotropic, above 1 at
    /// strong anisotropy and alpha_max >= strong_alpha_min).
    [[nodiscard]] static bool integrates(T alpha_x, T alpha_y, T eta_s) noexcept {
        if (!(alpha_x != alpha_y && alpha_x > T(0) && alpha_y > T(0))) return false;
        if (eta_s < T(1)) return true;
        return eta_s > T(1) && dielectric_side_grid<T>::strong(double(alpha_x), double(alpha_y)) &&
               glm::max(alpha_x, alpha_y) >= T(strong_alpha_min);
    }

    anisotropic_reflection_albedo_grid() = default;

    /// R_ss of the interface of alphas alpha_x, alpha_y and index ratio eta_s (the class
    /// comment). With `with_total`, where the interface integrates R_ss below 1
    /// (integrates() and eta_s < 1), the same pass also integrates the side's total
    /// single-scattering albedo E_s = R + T on the same nodes, plus
    /// rough_dielectric_albedo_grid_margin (_strong at strong anisotropy): total_albedo().
    anisotropic_reflection_albedo_grid(T alpha_x, T alpha_y, T eta_s, bool with_total = false)
        : anisotropic_reflection_albedo_grid(alpha_x, alpha_y, eta_s, with_total, no_other_fresnel) {}

    /// As above; where the interface integrates R_ss (integrates()), `other` (a callable
    /// c -> std::array<double, 3>, another Fresnel term F'(c) per channel, c = v·m; or
    /// no_other_fresnel) makes the same pass also integrate, per channel, the difference of
    /// the reflection albedos with F' and with the interface's own F on the same visible
    /// normals, D_k(v) = E_m[(F'_k(v·m) - F(v·m)) G2(v, l) / G1(v)] (detail::
    /// dielectric_visible_albedo_sums' reflect), plus difference_margin: difference(). The
    /// grid's rows are then dense above 1 too (dielectric_side_grid's dense_at_critical).
    /// With `other` every anisotropic interface integrates (R_ss too, also where integrates()
    /// is false: above 1 below strong anisotropy, and at eta_s = 1, where R_ss = 0).
    /// `other_kink`, in (0, 1), is the cosine under which F' reflects totally (a thin film
    /// over a base of index below 1), or 0 for none: with alpha_min <= window_alpha_max the
    /// reflection albedo with F' is then also integrated on an anisotropic_kink_window
    /// around it (its three channels; over the grid's rows within window_rows of it), and
    /// difference() reads D_k there as that albedo less at().
    template <class Other>
    anisotropic_reflection_albedo_grid(T alpha_x, T alpha_y, T eta_s, bool with_total, const Other& other,
                                       double other_kink = 0)
        : table_(alpha_x, alpha_y, eta_s), alpha_x_(alpha_x), alpha_y_(alpha_y), eta_s_(eta_s) {
        const bool anisotropic_interface = alpha_x != alpha_y && alpha_x > T(0) && alpha_y > T(0);
        const bool with_other = !std::is_same_v<Other, no_other_fresnel_t> && anisotropic_interface;
        if (integrates(alpha_x, alpha_y, eta_s) || with_other) {
            const double ax = double(alpha_x), ay = double(alpha_y), eta = double(eta_s);
            const ggx<double> d(unchecked, ax, ay);
            const bool below = eta_s < T(1);
            const int columns = below ? below_columns : above_cells, rows = below ? below_rows : above_cells;
            if constexpr (!std::is_same_v<Other, no_other_fresnel_t>) {
                // R_ss, E_s (when asked for below 1) and the three differences, in one pass, on
                // dense rows above 1 as well (46 rather than 16: a thick film's share has
                // fringes in mu).
                const bool total = below && with_total;
                const double margin = below ? below_margin : above_margin;
                const double strong = below ? below_margin_strong : above_margin;
                const double e_margin = rough_dielectric_albedo_grid_margin;
                const double e_strong = rough_dielectric_albedo_grid_margin_strong;
                const auto grids = dielectric_side_grid<T>::template many<5>(
                    ax, ay, eta, {margin, e_margin, difference_margin, difference_margin, difference_margin},
                    {strong, e_strong, difference_margin, difference_margin, difference_margin},
                    [&d, &other, eta, columns, rows, total](const vec3<double>& v) {
                        std::array<double, 3> diff{};
                        const auto add = [&other, &diff](double c, double F, double g) {
                            const std::array<double, 3> f = other(c);
                            for (std::size_t k = 0; k < 3; ++k) diff[k] += (f[k] - F) * g;
                        };
                        const dielectric_visible_albedos e =
                            total ? dielectric_visible_albedo_sums<true>(d, v, eta, columns, rows, add)
                                  : dielectric_visible_albedo_sums<false>(d, v, eta, columns, rows, add);
                        return std::array<double, 5>{e.reflected, e.total, diff[0], diff[1], diff[2]};
                    },
                    true);
                grid_.emplace(grids[0]);
                if (total) albedo_.emplace(grids[1]);
                difference_.emplace(differences{grids[2], grids[3], grids[4]});
                build_window();
                if (other_kink > 0 && other_kink < 1 && glm::min(alpha_x, alpha_y) <= T(window_alpha_max)) {
                    // The rows around the kink: the cell holding it and window_rows - 1 more
                    // below, window_rows above.
                    int i = 0;
                    while (i + 2 < grid_->rows() && grid_->row_cosine(i + 1) <= other_kink) ++i;
                    const double low = grid_->row_cosine(glm::max(i - (window_rows - 1), 0));
                    const double high = grid_->row_cosine(glm::min(i + window_rows, grid_->rows() - 1));
                    other_window_ = anisotropic_kink_window<T>(ax, ay, other_kink, other_kink - low, high - other_kink,
                                                               window_margin, 3, other);
                }
                return;
            }
            if (below && with_total) {
                const auto grids = dielectric_side_grid<T>::template many<2>(
                    ax, ay, eta, {below_margin, rough_dielectric_albedo_grid_margin},
                    {below_margin_strong, rough_dielectric_albedo_grid_margin_strong},
                    [&d, eta](const vec3<double>& v) {
                        const dielectric_visible_albedos e =
                            dielectric_visible_albedo_sums<true>(d, v, eta, below_columns, below_rows);
                        return std::array<double, 2>{e.reflected, e.total};
                    },
                    true);
                grid_.emplace(grids[0]);
                albedo_.emplace(grids[1]);
                build_window();
                return;
            }
            grid_.emplace(ax, ay, eta, below ? below_margin : above_margin,
                                                below ? below_margin_strong : above_margin,
                                                [&d, eta, columns, rows](const vec3<double>& v) {
                                                    return dielectric_visible_albedo(d, v, eta, columns, rows, false);
                                                },
                                                below);
            build_window();
            return;
        }
        beyond_ = eta_s > T(dielectric_albedo_eta_max) && anisotropic_interface;
        if (!beyond_) return;
        views_ = anisotropic_view_grid<T>(alpha_x, alpha_y);
        const double eta = double(eta_s);
        views_.for_each_node([&](std::size_t k, const vec3<double>& v, double mu, double cos2_phi) {
            double anisotropic = 0;
            visit_ggx_cosine_measure(v, double(alpha_x), double(alpha_y), beyond_cells,
                                     [&](double c, double weight) { anisotropic += weight * F_dielectric(c, eta); });
            delta_[k] = T(anisotropic) - dielectric_reflection_albedo(unchecked, T(mu), base_alpha(T(cos2_phi)), eta_s);
        });
    }

    /// R_ss(w) for the unit local direction w on the view's side (only its azimuth and |w.z|
    /// are used). Dimensionless, in [0, 1].
    [[nodiscard]] T at(const vec3<T>& w) const noexcept {
        if (window_.contains(std::abs(w.z))) return window_.at(w);
        if (grid_.has_value()) return grid_->at(w);
        if (!beyond_) return table_.at(w);
        const T mu = glm::min(std::abs(w.z), T(1));
        const T s2 = w.x * w.x + w.y * w.y;
        // At the pole every azimuth is the same view: read the tangent's.
        const T cos2_phi = s2 > T(0) ? w.x * w.x / s2 : T(1);
        const T r = dielectric_reflection_albedo(unchecked, mu, base_alpha(cos2_phi), eta_s_) +
                    views_.at(delta_, mu, cos2_phi) + T(beyond_margin);
        return glm::clamp(r, T(0), T(1));
    }

    /// Whether R_ss is read from a grid of this interface's own views (integrates(); the
    /// class comment).
    [[nodiscard]] bool integrated() const noexcept { return grid_.has_value(); }

    /// D_k(w) (the constructor with `other`) for channel k at the unit local direction w,
    /// read as at() reads R_ss, margin included: dimensionless, in [-1, 1]. 0 without `other`
    /// (has_difference() false).
    [[nodiscard]] T difference(std::size_t k, const vec3<T>& w) const noexcept { return differences_at(w)[k]; }

    /// difference(k, w) for the three channels k at once (w located once on the grid): in
    /// the window around other_kink that window's albedo with F'_k less at(w); elsewhere the
    /// grid's D_k.
    [[nodiscard]] std::array<T, 3> differences_at(const vec3<T>& w) const noexcept {
        if (!difference_.has_value()) return {};
        if (other_window_.contains(std::abs(w.z))) {
            const T r = at(w);
            std::array<T, 3> out;
            for (std::size_t k = 0; k < 3; ++k) out[k] = glm::clamp(other_window_.at(w, k) - r, T(-1), T(1));
            return out;
        }
        return dielectric_side_grid<T>::at_signed_all(*difference_, w);
    }

    /// differences_at(w) for a caller that adds them to at(w) (the albedo with F'_k as
    /// at(w) + D_k). The grid's D_k are relative to the grid's nodes' R_ss, which at() does
    /// not read as they are inside the window around the critical cosine (that window) nor in
    /// lifted cells (lift_cells): there they are shifted by the nodes' bilinear R_ss less
    /// at(w), so that the sum is the grid's albedo with F'_k, which steps where F' does, not
    /// where F does; in the window around other_kink, differences_at(w) as it is.
    [[nodiscard]] std::array<T, 3> differences_against_at(const vec3<T>& w) const noexcept {
        std::array<T, 3> out = differences_at(w);
        if (!difference_.has_value() || other_window_.contains(std::abs(w.z))) return out;
        const T shift = grid_->at_without_lift(w) - at(w);
        if (shift == T(0)) return out;
        for (std::size_t k = 0; k < 3; ++k) out[k] = glm::clamp(out[k] + shift, T(-1), T(1));
        return out;
    }

    /// Whether at(w) reads the window around the critical cosine (windowed() and |w.z| in it).
    [[nodiscard]] bool windowed_at(const vec3<T>& w) const noexcept { return window_.contains(std::abs(w.z)); }

    /// Whether the grid holds the differences D_k (the constructor with `other`).
    [[nodiscard]] bool has_difference() const noexcept { return difference_.has_value(); }

    /// The side's total single-scattering albedo E_s = R + T on the grid's nodes, integrated
    /// in the same pass as R_ss (the constructor's with_total), or nullptr. For
    /// rough_dielectric_albedo_grid's one-sided constructor.
    [[nodiscard]] const dielectric_side_grid<T>* total_albedo() const noexcept { return albedo_.get(); }

    /// Whether R_ss is read from a grid of this interface's own views below an index ratio
    /// of 1 (anisotropic; the class comment).
    [[nodiscard]] bool integrated_below_one() const noexcept { return grid_.has_value() && eta_s_ < T(1); }

    /// With integrated_below_one(): R_ss(w) without the margin the nodes hold, read by
    /// dielectric_side_grid::at_or_below (chords that do not rise above R_ss where it is
    /// concave in mu below the critical cosine and convex above), so that what is left is
    /// the nodes' quadrature error, within about +-9e-3, and a low read where R_ss falls
    /// across the critical cosine faster than the rows resolve (surfaces with an alpha below
    /// about 0.05; docs/conventions.md has the measured ranges). Dimensionless, in [0, 1].
    /// Integrated above 1 (strong anisotropy): at(w) less the margin (read - true from
    /// -1.6e-3 to +9e-3 before the margin, the class comment). Otherwise at(w).
    [[nodiscard]] T at_without_margin(const vec3<T>& w) const noexcept {
        if (!grid_.has_value()) return at(w);
        if (!integrated_below_one()) return glm::max(grid_->at(w) - grid_->margin(), T(0));
        if (window_.contains(std::abs(w.z))) return window_.at_or_below(w);
        return glm::max(grid_->at_or_below(w) - grid_->margin(), T(0));
    }

    /// Whether R_ss is read from an anisotropic_kink_window around the critical cosine
    /// (integrated below 1 and alpha_min <= window_alpha_max).
    [[nodiscard]] bool windowed() const noexcept { return !window_.empty(); }

private:
    // Below an index ratio of 1 with alpha_min <= window_alpha_max: the window of R_ss over
    // the grid's rows within window_rows of the critical cosine's row on either side.
    void build_window() {
        if (!(eta_s_ < T(1)) || !grid_.has_value()) return;
        {
            // Away from the pole the side reflects totally where even the facets tilted most
            // toward the view along the rougher axis see it beyond the critical angle: for a
            // surface nearly smooth along the other axis, where mu^2 + (1 - mu^2) s = mu_c^2
            // (s the squared cosine of the view's azimuth from the rougher axis), a kink of
            // R_ss that runs diagonally across the grid's cells, whose bilinear reads fall
            // below R_ss there by more than the margin. The cells within kink_band of that
            // curve get lift_cells' lifts.
            const double mu_c = std::sqrt((1.0 - double(eta_s_)) * (1.0 + double(eta_s_)));
            const double eta = double(eta_s_);
            const ggx<double> d(unchecked, double(alpha_x_), double(alpha_y_));
            const auto projected = [](double mu, double s) { return std::sqrt(mu * mu + (1.0 - mu * mu) * s); };
            grid_->lift_cells(
                [&projected, mu_c](double mu0, double mu1, double s0, double s1) {
                    return projected(mu0, s0) <= mu_c + kink_band && projected(mu1, s1) >= mu_c - kink_band;
                },
                [&d, eta](const vec3<double>& v) {
                    return dielectric_visible_albedo(d, v, eta, below_columns, below_rows, false);
                });
        }
        if (!(glm::min(alpha_x_, alpha_y_) <= T(window_alpha_max))) return;
        const int critical = dielectric_side_grid<T>::rows_below_critical;
        const double mu_c = grid_->row_cosine(critical);
        const double eta = double(eta_s_);
        window_ = anisotropic_kink_window<T>(
            double(alpha_x_), double(alpha_y_), mu_c, mu_c - grid_->row_cosine(critical - window_rows),
            grid_->row_cosine(critical + window_rows) - mu_c, window_margin, 1,
            [eta](double c) { return std::array<double, 3>{F_dielectric(c, eta), 0.0, 0.0}; });
    }

    // The roughness projected on the azimuth of cos^2(phi) from the tangent, at most 1. Not
    // reflection_projected_alpha: that reads the smoother alpha at the pole, and the grid's
    // nodes at mu = 1 keep their azimuths, so that the difference they hold stays continuous
    // toward the views just off the pole (with the pole's alpha there, read - true reached
    // -1.6e-2 at mu 0.95).
    [[nodiscard]] T base_alpha(T cos2_phi) const noexcept {
        return glm::min(std::sqrt(alpha_x_ * alpha_x_ * cos2_phi + alpha_y_ * alpha_y_ * (T(1) - cos2_phi)), T(1));
    }

    anisotropic_reflection_albedo<T> table_{};
    anisotropic_view_grid<T> views_{};
    std::array<T, anisotropic_view_grid<T>::size> delta_{};
    T alpha_x_ = 0, alpha_y_ = 0, eta_s_ = 1;
    bool beyond_ = false;
    heap_value<dielectric_side_grid<T>> grid_{};   // R_ss per view where integrates(), or empty
    heap_value<dielectric_side_grid<T>> albedo_{}; // E_s = R + T on the same views (with_total), or empty
    using differences = std::array<dielectric_side_grid<T>, 3>;
    heap_value<differences> difference_{}; // D_k on the same views (the constructor with `other`), or empty
    anisotropic_kink_window<T> window_{}; // R_ss around the critical cosine (build_window), or empty
    anisotropic_kink_window<T> other_window_{}; // the albedo with F' around other_kink, or empty
};

} // namespace detail

/// The reflection albedo R_ss(w) of an anisotropic GGX interface, shade::rough_dielectric over
/// ggx(alpha_x, alpha_y) (alpha_x along the tangent t, alpha_y along b), for the unit local
/// direction w on the view's side (w = (w·t, w·b, w·n); the sign of w.z is not used: eta_s
/// names the side, as in the isotropic form). R_ss of an anisotropic interface depends on
/// the azimuth of the view as well as on its cosine mu = |w.z|. It is read as
///
///     R_ss(w) = R_ss,iso(mu, alpha_phi, eta_s) + Delta_R(w)
///
/// with R_ss,iso the isotropic table above at the roughness projected on w's azimuth,
/// alpha_phi = sqrt(alpha_x^2 cos^2 phi + alpha_y^2 sin^2 phi) (Heitz 2014, "Understanding
/// the Masking-Shadowing Function in Microfacet-Based BRDFs", JCGT 3(2), eq. 80: the view's
/// masking is exact there, so the reading is close for nearly smooth interfaces), and
/// Delta_R a tabulated correction
/// (shade/bsdf/detail/dielectric_anisotropic_reflection_albedo_data.hpp, written by
/// examples/dielectric_albedo_tables --anisotropic --reflection on the grid and with the
/// interpolation of shade/bsdf/dielectric_anisotropic_reflection_table.hpp: sqrt(mu), the
/// view's azimuth (on the exiting side with the onset of total internal reflection on a
/// node), the rougher alpha up to sqrt 2, the anisotropy alpha_min / alpha_max from 0 (one
/// alpha 0: OpenPBR's anisotropy 1) to 1 and
/// eta_hat in [1.05, 3], both sides). Where the grid ends: detail::anisotropic_reflection_albedo.
/// Its accuracy against fresh estimates is stated in the data header and in
/// docs/properties.md ("Reflection albedo of the rough dielectric"). Equal alphas return the
/// isotropic form exactly. Returns a dimensionless value in [0, 1].
///
/// Preconditions (unchecked): w finite and of unit length, alpha_x, alpha_y >= 0 and finite,
/// eta_s finite and > 0. The checked overload below throws instead.
template <std::floating_point T>
[[nodiscard]] inline T dielectric_reflection_albedo(unchecked_t, const vec3<T>& w, T alpha_x, T alpha_y,
                                                    T eta_s) noexcept {
    return detail::anisotropic_reflection_albedo<T>(alpha_x, alpha_y, eta_s).at(w);
}

/// The anisotropic form, validated first: throws shade::invalid_parameter naming "w" unless
/// w is a finite unit vector (|w|^2 within 1e-3 of 1), "alpha_x" or "alpha_y" unless finite
/// and >= 0, "eta_s" unless it lies in [1e-4, 1e4].
template <std::floating_point T>
[[nodiscard]] inline T dielectric_reflection_albedo(const vec3<T>& w, T alpha_x, T alpha_y, T eta_s) {
    (void)require_unit_length("w", w);
    require_non_negative("alpha_x", alpha_x);
    require_non_negative("alpha_y", alpha_y);
    require_in_range("eta_s", eta_s, dielectric_eta_min<T>, dielectric_eta_max<T>);
    return dielectric_reflection_albedo(unchecked, w, alpha_x, alpha_y, eta_s);
}

} // namespace shade
