#pragma once
// The GGX reflection lobe's measure of the cosine c = v·h between the view and the half
// vector, tabulated as weights of fixed nodes in c: the directional albedo of the lobe with
// any Fresnel factor that depends on c alone (a thin film, Schlick, F82, the exact
// dielectric) is then a weighted sum of that Fresnel at the nodes. The weights are written
// by examples/albedo_tables --cosine-weights into detail/cosine_weight_data.hpp.
//
// Not part of shade/shade.hpp: include this header where it is used.

#include <array>
#include <cmath>
#include <concepts>
#include <cstddef>

#include <glm/common.hpp>

#include <shade/brdf/microfacet/detail/cosine_weight_data.hpp>
#include <shade/brdf/microfacet/ggx.hpp>
#include <shade/core/heap_value.hpp>
#include <shade/core/math.hpp>
#include <shade/core/types.hpp>

namespace shade::detail {

/// Node k of the grid shared by c and mu: c_k = (k / (n - 1))^(3/2), n =
/// cosine_weight_nodes, denser toward grazing cosines where Fresnel factors bend most.
[[nodiscard]] inline double cosine_weight_node(std::size_t k) noexcept {
    const double x = double(k) / double(cosine_weight_nodes - 1);
    return x * std::sqrt(x);
}

/// The cell of those nodes that holds the cosine c (clamped to [0, 1]; NaN read as 0): the
/// k with c_k <= c < c_(k+1), at most cosine_weight_nodes - 2.
[[nodiscard]] inline std::size_t cosine_weight_cell(double c) noexcept {
    const double clamped = c > 0 ? glm::min(c, 1.0) : 0.0;
    return glm::min(std::size_t(std::cbrt(clamped * clamped) * double(cosine_weight_nodes - 1)),
                    cosine_weight_nodes - 2);
}

/// F given at the nodes (f_nodes[k] = F(c_k)) read at the cosine c (clamped to [0, 1]; NaN
/// read as 0), linear between the nodes in x = c^(2/3): the F a node sum integrates.
template <std::floating_point T>
[[nodiscard]] rgb<double> fresnel_nodes_at(const std::array<rgb<T>, cosine_weight_nodes>& f_nodes, double c) noexcept {
    constexpr std::size_t n = cosine_weight_nodes;
    const double clamped = c > 0 ? glm::min(c, 1.0) : 0.0;
    const double x = std::cbrt(clamped * clamped) * double(n - 1);
    const std::size_t i = glm::min(std::size_t(x), n - 2);
    const double t = x - double(i);
    return (1 - t) * rgb<double>(f_nodes[i]) + t * rgb<double>(f_nodes[i + 1]);
}

/// The alpha of row j of the table: alpha_j = (j / (m - 1))^2, m = cosine_weight_alpha_nodes
/// (uniform in sqrt(alpha) over [0, 1]).
[[nodiscard]] inline double cosine_weight_alpha(std::size_t j) noexcept {
    const double s = double(j) / double(cosine_weight_alpha_nodes - 1);
    return s * s;
}

/// The quadrature of the GGX reflection lobe's measure of c = v·h at the local view v (unit,
/// v.z > 0) for roughnesses alpha_x, alpha_y (> 0): calls visit(c, weight) for each of the
/// columns x rows midpoints of the visible-normal sampler's square (Heitz 2018, "Sampling the
/// GGX Distribution of Visible Normals", JCGT 7(4); columns along its angle u_x, rows along
/// u_y) whose reflected direction lies above the surface, weight = G2(v, l) / G1(v) /
/// (columns rows), so that sum weight F(c) is the lobe's albedo with the Fresnel F. Near the
/// normal c depends on u_y alone, so that rows sets the resolution in c there.
template <class Visit>
void visit_ggx_cosine_measure(const vec3<double>& v, double alpha_x, double alpha_y, std::size_t columns,
                              std::size_t rows, Visit&& visit) {
    const ggx<double> d(unchecked, alpha_x, alpha_y);
    const double lambda_v = d.Lambda(v);
    const double cell = 1 / (double(columns) * double(rows));
    const vec3<double> v_h = d.stretch(v);
    for (std::size_t i = 0; i < columns; ++i) {
        // u = ((i + 1/2) / columns, (j + 1/2) / rows): ggx::sample_visible_normal with the
        // column's angle 2 pi u_x computed once.
        const double phi = 2 * pi<double> * ((double(i) + 0.5) / double(columns));
        const double cos_phi = std::cos(phi), sin_phi = std::sin(phi);
        for (std::size_t j = 0; j < rows; ++j) {
            const vec3<double> h =
                d.sample_visible_normal_stretched(v_h, cos_phi, sin_phi, (double(j) + 0.5) / double(rows));
            const double c = glm::dot(v, h);
            const vec3<double> l = 2 * c * h - v;
            if (!(l.z > 0) || !(c > 0)) continue;
            // G2 / G1(v) = (1 + Lambda(v)) / (1 + Lambda(v) + Lambda(l)), the height-correlated
            // G2 (Heitz 2014, JCGT 3(2), eq. 99) over G1(v) = 1 / (1 + Lambda(v)).
            visit(c, cell * (1 + lambda_v) / (1 + lambda_v + d.Lambda(l)));
        }
    }
}

/// visit_ggx_cosine_measure on strata x strata cells.
template <class Visit>
void visit_ggx_cosine_measure(const vec3<double>& v, double alpha_x, double alpha_y, std::size_t strata,
                              Visit&& visit) {
    visit_ggx_cosine_measure(v, alpha_x, alpha_y, strata, strata, static_cast<Visit&&>(visit));
}

/// The quadrature of ggx_cosine_weights: visit_ggx_cosine_measure of the isotropic lobe at
/// the view of cosine mu; alpha <= 0 visits (mu, 1) once. mu is clamped to [1e-4, 1].
template <class Visit>
void visit_ggx_cosine_measure(double mu, double alpha, std::size_t strata, Visit&& visit) {
    mu = glm::clamp(mu, 1e-4, 1.0);
    if (!(alpha > 0)) {
        visit(mu, 1.0);
        return;
    }
    visit_ggx_cosine_measure(vec3<double>(std::sqrt((1 - mu) * (1 + mu)), 0, mu), alpha, alpha, strata,
                             static_cast<Visit&&>(visit));
}

/// The weights w_k(mu, alpha) of the table's definition, computed: for the single-scattering
/// GGX reflection lobe with F = 1 and height-correlated Smith masking at the view of cosine
/// mu, its albedo E_F(v) = integral of f cos(theta_l) dl for a Fresnel F(v·h) is
///
///     E_F(v) = integral F(v·h) D_v(h) G2(v, l) / G1(v) dh,   l = reflect(v, h),
///
/// (D_v the distribution of visible normals, Heitz 2018, "Sampling the GGX Distribution of
/// Visible Normals", JCGT 7(4), eq. 1; dl = 4 (v·h) dh, Walter et al. 2007, eq. 14; G2 = 0
/// for l below the surface), i.e. the integral of F against the measure m_v of c = v·h.
/// w_k is the integral of the hat function of node k (1 at c_k, 0 at its neighbours,
/// linear between, in the grid's coordinate x = c^(2/3)) against m_v, so that sum_k w_k
/// F(c_k) integrates exactly an F linear between the nodes in x. m_v is integrated by the
/// midpoint rule on strata^2 cells of the visible-normal sampler's square
/// (ggx::sample_visible_normal). alpha = 0 gives the hat weights of c = mu. mu is clamped to
/// [1e-4, 1] (the sampler needs v above the horizon). Writes cosine_weight_nodes values to
/// out.
inline void ggx_cosine_weights(double mu, double alpha, std::size_t strata, double* out) noexcept {
    constexpr std::size_t n = cosine_weight_nodes;
    for (std::size_t k = 0; k < n; ++k) out[k] = 0;
    visit_ggx_cosine_measure(mu, alpha, strata, [&](double c, double weight) {
        const double x = glm::clamp(std::cbrt(c * c), 0.0, 1.0) * double(n - 1);
        const std::size_t k = glm::min(std::size_t(x), n - 2);
        const double t = x - double(k);
        out[k] += weight * (1 - t);
        out[k + 1] += weight * t;
    });
}

/// The directional albedo of the GGX reflection lobe of roughness alpha with a Fresnel
/// factor F(c), c = v·h, as a row over the view cosine: at construction, F (a callable
/// T -> rgb<T>) is read at the cosine_weight_nodes nodes c_k and each view node's
/// E_F(mu_j) = sum_k w_k(mu_j, alpha) F(c_k) is summed, the weights read from
/// cosine_weight_data.hpp, linear in sqrt(alpha) between its rows; at(mu) interpolates the
/// row linearly in x = mu^(2/3) (the grid's coordinate; for alpha -> 0 this is the linear
/// interpolation of F itself, the smooth lobe's albedo). alpha is clamped to [0, 1].
/// The accuracy of the table (its quadrature and interpolation) is stated in the data
/// header; F's own variation between the nodes adds its linear-interpolation error.
template <std::floating_point T>
class fresnel_albedo_row {
public:
    fresnel_albedo_row() = default;

    template <class Fresnel>
    fresnel_albedo_row(T alpha, const Fresnel& F) : fresnel_albedo_row(alpha, nodes_of(F)) {}

    /// The row of F given at the nodes: f_nodes[k] = F(c_k).
    fresnel_albedo_row(T alpha, const std::array<rgb<T>, cosine_weight_nodes>& f_nodes) {
        constexpr std::size_t n = cosine_weight_nodes, m = cosine_weight_alpha_nodes;
        const double s = std::sqrt(glm::clamp(double(alpha), 0.0, 1.0)) * double(m - 1);
        const std::size_t j = glm::min(std::size_t(s), m - 2);
        const double t = s - double(j);
        const float* lower = cosine_weight_table + j * n * n;
        const float* upper = lower + n * n;
        for (std::size_t i = 0; i < n; ++i) {
            rgb<T> sum(0);
            for (std::size_t k = 0; k < n; ++k) {
                const double w = (1 - t) * double(lower[i * n + k]) + t * double(upper[i * n + k]);
                sum += T(w) * f_nodes[k];
            }
            row_[i] = sum;
        }
    }

    /// Raises view node i's sum by margin[i]: with an upper bound of the sum's shortfall
    /// (openpbr_surface's thin-film margin) the row then reads high, never low.
    void raise(const std::array<double, cosine_weight_nodes>& margin) {
        for (std::size_t i = 0; i < cosine_weight_nodes; ++i) row_[i] += rgb<T>(T(margin[i]));
    }

    /// Adds d[i] to view node i's sum, per channel (kink_cell_correction).
    void add(const std::array<rgb<T>, cosine_weight_nodes>& d) {
        for (std::size_t i = 0; i < cosine_weight_nodes; ++i) row_[i] += d[i];
    }

    /// E_F at view cosine mu (clamped to [0, 1]), per channel.
    [[nodiscard]] rgb<T> at(T mu) const noexcept {
        constexpr std::size_t n = cosine_weight_nodes;
        const T c = glm::clamp(mu, T(0), T(1));
        const T x = std::cbrt(c * c) * T(n - 1);
        const std::size_t k = glm::min(std::size_t(x), n - 2);
        const T t = x - T(k);
        return (T(1) - t) * row_[k] + t * row_[k + 1];
    }

private:
    template <class Fresnel>
    [[nodiscard]] static std::array<rgb<T>, cosine_weight_nodes> nodes_of(const Fresnel& F) {
        std::array<rgb<T>, cosine_weight_nodes> f_nodes;
        for (std::size_t k = 0; k < cosine_weight_nodes; ++k) f_nodes[k] = F(T(cosine_weight_node(k)));
        return f_nodes;
    }

    std::array<rgb<T>, cosine_weight_nodes> row_{};
};

/// The parts of the kink cell in kink_cell_correction (equal in x = c^(2/3)).
inline constexpr std::size_t kink_sub_bins = 16;

/// What fresnel_albedo_row's node sum misses where F has a kink between two nodes (the
/// total internal reflection of an index ratio below 1: F = 1 under the critical cosine,
/// falling steeply above it, which the linear interpolation between the cell's nodes cuts
/// off): for each view node mu_i (cosine_weight_node(i)), the integral of g = F minus that
/// interpolation of f_nodes (the row's nodes, f_nodes[k] = F(c_k)) over the cell holding the
/// cosine `kink`, against the measure of c of the GGX lobe of roughness alpha at mu_i. The
/// cell is split into kink_sub_bins equal parts in x = c^(2/3); g's mean over each part is
/// taken once (16 midpoints each), the measure's mass in each part per view node by
/// visit_ggx_cosine_measure on columns x rows cells (rows many: near the normal c depends on
/// the rows alone, and the cell is narrow in c), and the integral is their sum of products
/// (g's square-root singularity at the critical cosine is averaged, not sampled by the
/// measure's quadrature). Adding it to the row (fresnel_albedo_row::add) makes the node sum
/// exact in that cell up to the masses' error; elsewhere the row is unchanged. F is a
/// callable T -> rgb<T>. Zero for alpha <= 0 (the smooth lobe reads F at the nodes).
template <std::floating_point T, class Fresnel>
[[nodiscard]] std::array<rgb<T>, cosine_weight_nodes> kink_cell_correction(
    T alpha, const std::array<rgb<T>, cosine_weight_nodes>& f_nodes, const Fresnel& F, double kink,
    std::size_t columns, std::size_t rows) {
    constexpr std::size_t n = cosine_weight_nodes, bins = kink_sub_bins, points = 16;
    std::array<rgb<T>, n> out{};
    if (!(alpha > T(0))) return out;
    const std::size_t cell = cosine_weight_cell(kink);
    std::array<rgb<double>, bins> g_mean{};
    for (std::size_t b = 0; b < bins; ++b) {
        rgb<double> sum(0.0);
        for (std::size_t q = 0; q < points; ++q) {
            const double t = (double(b) + (double(q) + 0.5) / double(points)) / double(bins);
            const double x = (double(cell) + t) / double(n - 1);
            const rgb<double> chord = (1 - t) * rgb<double>(f_nodes[cell]) + t * rgb<double>(f_nodes[cell + 1]);
            sum += rgb<double>(F(T(x * std::sqrt(x)))) - chord;
        }
        g_mean[b] = sum / double(points);
    }
    for (std::size_t i = 0; i < n; ++i) {
        std::array<double, bins> mass{};
        const double mu = glm::clamp(cosine_weight_node(i), 1e-4, 1.0);
        const vec3<double> v(std::sqrt((1 - mu) * (1 + mu)), 0, mu);
        visit_ggx_cosine_measure(v, double(alpha), double(alpha), columns, rows, [&](double c, double weight) {
            const double x = glm::clamp(std::cbrt(c * c), 0.0, 1.0) * double(n - 1);
            if (!(x >= double(cell) && x < double(cell + 1))) return;
            mass[glm::min(std::size_t((x - double(cell)) * double(bins)), bins - 1)] += weight;
        });
        rgb<double> sum(0.0);
        for (std::size_t b = 0; b < bins; ++b) sum += mass[b] * g_mean[b];
        out[i] = rgb<T>(sum);
    }
    return out;
}

/// Where F has a kink at a cosine (kink_cell_correction), E_F(mu) has one near the same view
/// cosine when the lobe is narrow, which the row's linear interpolation between its view
/// nodes cuts off as well. For each view cell within `reach` cells of the cell holding
/// `kink`, E_F at four points inside the cell (visit_ggx_cosine_measure on strata^2 cells, F
/// itself) less row.at() there, times 1.25 for the peaks between the points; returns per view
/// node the largest positive such shortfall of its two cells (per channel), so that adding it
/// (fresnel_albedo_row::add) lifts the row's reads in those cells to E_F or above. Zero for
/// alpha <= 0 (a smooth lobe's row interpolates F itself: kink_cell_correction's case).
template <std::floating_point T, class Fresnel>
[[nodiscard]] std::array<rgb<T>, cosine_weight_nodes> kink_view_shortfall(T alpha, const fresnel_albedo_row<T>& row,
                                                                          const Fresnel& F, double kink,
                                                                          std::size_t reach, std::size_t strata) {
    constexpr std::size_t n = cosine_weight_nodes;
    std::array<rgb<T>, n> out{};
    if (!(alpha > T(0))) return out;
    const std::size_t center = cosine_weight_cell(kink);
    const std::size_t first = center > reach ? center - reach : 0;
    const std::size_t last = glm::min(center + reach, n - 2);
    for (std::size_t j = first; j <= last; ++j) {
        rgb<double> worst(0.0);
        for (const double t : {0.2, 0.4, 0.6, 0.8}) {
            const double x = (double(j) + t) / double(n - 1);
            const double mu = x * std::sqrt(x);
            rgb<double> e(0.0);
            visit_ggx_cosine_measure(mu, double(alpha), strata,
                                     [&](double c, double weight) { e += weight * rgb<double>(F(T(c))); });
            worst = glm::max(worst, 1.25 * (e - rgb<double>(row.at(T(mu)))));
        }
        out[j] = glm::max(out[j], rgb<T>(worst));
        out[j + 1] = glm::max(out[j + 1], rgb<T>(worst));
    }
    return out;
}

/// E_F(mu) of the isotropic GGX lobe of roughness alpha > 0 around a kink of F at the cosine
/// `kink` (kink_cell_correction), on view cosines much finer than the row's nodes: a narrow
/// lobe's E_F steps from 1 toward F(mu) within about alpha sin(theta) of the critical cosine,
/// which fresnel_albedo_row's 64 view nodes bridge from above only across a whole cell (read
/// up to 0.17 high there at alpha 0.0025). The window spans the row's view cells within
/// `reach` of the kink's cell, on `cells` cells even in x in [-1, 1], mu = kink + d x |x| (d
/// the distance from the kink to the window's end on x's side): the kink is the middle node
/// and the cells crowd toward it quadratically, where E_F bends most (concave below it,
/// falling steeply above it). E_F is computed at `samples` points per cell (the cells' ends
/// among them) by visit_ggx_cosine_measure on strata^2 cells with F itself (a callable
/// double -> rgb<double>). A read is linear in x between the two nodes of its cell plus the
/// cell's lift, 1.25 times the most E_F rises above that chord at the points inside the cell
/// (as kink_view_shortfall lifts the row: the read is at or above E_F at every point, and by
/// a quarter more for the peaks between them), plus `margin` (for the quadrature's error);
/// at_or_below() reads the chord less the cell's drop (1.25 times the most E_F falls below
/// the chord at those points) less `margin`, for a caller that must not read E_F high.
/// Empty (contains() false) until built; a built window keeps its values in a heap block
/// (about 3.5 KB for float), so that an empty one, what most materials hold, is small. Copies
/// copy the block.
template <std::floating_point T>
class kink_view_window {
public:
    static constexpr std::size_t cells = 96;  ///< the window's cells (even: the kink a node)
    static constexpr std::size_t samples = 4; ///< E_F's points per cell, one end included

    kink_view_window() = default;

    template <class Fresnel>
    kink_view_window(double alpha, const Fresnel& F, double kink, std::size_t reach, std::size_t strata,
                     double margin) {
        constexpr std::size_t n = cosine_weight_nodes, points = cells * samples + 1;
        const std::size_t center = cosine_weight_cell(kink);
        const std::size_t first = center > reach ? center - reach : 0;
        const std::size_t last = glm::min(center + reach + 1, n - 1);
        kink_ = glm::clamp(kink, 0.0, 1.0);
        below_ = glm::max(kink_ - cosine_weight_node(first), 0.0);
        above_ = glm::max(cosine_weight_node(last) - kink_, 0.0);
        table& out = table_.emplace();
        std::array<rgb<double>, points> e{};
        for (std::size_t q = 0; q < points; ++q) {
            const double x = -1.0 + 2.0 * double(q) / double(points - 1);
            const double mu = kink_ + (x < 0 ? below_ : above_) * x * std::abs(x);
            visit_ggx_cosine_measure(mu, alpha, strata, [&](double c, double weight) { e[q] += weight * F(c); });
        }
        for (std::size_t j = 0; j < cells; ++j) {
            rgb<double> above(0.0), below(0.0);
            for (std::size_t q = 1; q < samples; ++q) {
                const double t = double(q) / double(samples);
                const rgb<double> chord = (1 - t) * e[j * samples] + t * e[(j + 1) * samples];
                above = glm::max(above, e[j * samples + q] - chord);
                below = glm::max(below, chord - e[j * samples + q]);
            }
            out.lift[j] = rgb<T>(1.25 * above);
            out.drop[j] = rgb<T>(1.25 * below);
        }
        for (std::size_t j = 0; j <= cells; ++j) out.nodes[j] = rgb<T>(e[j * samples]);
        margin_ = T(margin);
    }

    /// Whether mu lies in the window (false when empty or for a NaN mu).
    [[nodiscard]] bool contains(T mu) const noexcept {
        return table_.has_value() && double(mu) >= kink_ - below_ && double(mu) <= kink_ + above_;
    }

    /// E_F at view cosine mu in the window (contains(mu)), lift and margin included, per
    /// channel.
    [[nodiscard]] rgb<T> at(T mu) const noexcept {
        const cell c = cell_of(mu);
        const table& w = *table_;
        return (T(1) - c.t) * w.nodes[c.j] + c.t * w.nodes[c.j + 1] + w.lift[c.j] + rgb<T>(margin_);
    }

    /// A read at or below E_F at view cosine mu in the window (contains(mu)): the chord less
    /// the cell's drop and the margin, per channel (not clamped: may be below 0).
    [[nodiscard]] rgb<T> at_or_below(T mu) const noexcept {
        const cell c = cell_of(mu);
        const table& w = *table_;
        return (T(1) - c.t) * w.nodes[c.j] + c.t * w.nodes[c.j + 1] - w.drop[c.j] - rgb<T>(margin_);
    }

private:
    // The cell j holding mu and the weight t of its node j + 1.
    struct cell {
        std::size_t j;
        T t;
    };
    [[nodiscard]] cell cell_of(T mu) const noexcept {
        const double offset = double(mu) - kink_;
        const double side = offset < 0 ? below_ : above_;
        const double x = side > 0 ? (offset < 0 ? -1.0 : 1.0) * std::sqrt(glm::min(std::abs(offset) / side, 1.0)) : 0.0;
        const double u = (x + 1.0) * 0.5 * double(cells);
        const std::size_t j = glm::min(std::size_t(glm::max(u, 0.0)), cells - 1);
        return {j, T(glm::clamp(u - double(j), 0.0, 1.0))};
    }

    // The nodes' E_F, and each cell's lift and drop.
    struct table {
        std::array<rgb<T>, cells + 1> nodes{};
        std::array<rgb<T>, cells> lift{}, drop{};
    };

    double kink_ = 0, below_ = 0, above_ = 0;
    T margin_ = 0;
    heap_value<table> table_{}; // empty: not built
};

/// One view's sum of fresnel_albedo_row without keeping a row: e = sum_k w_k F(c_k) per
/// channel (the lobe's albedo with F) and mass = sum_k w_k (its albedo with F = 1), the
/// weights at (alpha, mu) interpolated bilinearly in sqrt(alpha) and x = mu^(2/3) as
/// fresnel_albedo_row builds and reads them.
template <std::floating_point T>
struct fresnel_albedo_sum {
    rgb<T> e{0};
    T mass = 0;
};

/// fresnel_albedo_sum for F given at the nodes (f_nodes[k] = F(c_k)), at roughness alpha
/// (clamped to [0, 1]) and view cosine mu (clamped to [0, 1]); a NaN alpha or mu is read
/// as 0.
template <std::floating_point T>
[[nodiscard]] fresnel_albedo_sum<T> fresnel_albedo_at(T alpha, T mu,
                                                      const std::array<rgb<T>, cosine_weight_nodes>& f_nodes) noexcept {
    constexpr std::size_t n = cosine_weight_nodes, m = cosine_weight_alpha_nodes;
    const double s = std::sqrt(alpha > T(0) ? glm::min(double(alpha), 1.0) : 0.0) * double(m - 1);
    const std::size_t j = glm::min(std::size_t(s), m - 2);
    const double t = s - double(j);
    const double c = mu > T(0) ? glm::min(double(mu), 1.0) : 0.0;
    const double x = std::cbrt(c * c) * double(n - 1);
    const std::size_t i = glm::min(std::size_t(x), n - 2);
    const double u = x - double(i);
    const float* w00 = cosine_weight_table + (j * n + i) * n;
    const float* w01 = w00 + n;
    const float* w10 = w00 + n * n;
    const float* w11 = w10 + n;
    const double a00 = (1 - t) * (1 - u), a01 = (1 - t) * u, a10 = t * (1 - u), a11 = t * u;
    fresnel_albedo_sum<T> out;
    for (std::size_t k = 0; k < n; ++k) {
        const double w = a00 * double(w00[k]) + a01 * double(w01[k]) + a10 * double(w10[k]) + a11 * double(w11[k]);
        out.e += T(w) * f_nodes[k];
        out.mass += T(w);
    }
    return out;
}

/// The views of an anisotropic GGX lobe (roughnesses alpha_x, alpha_y > 0) on which a
/// quantity of the view is computed once and then read anywhere by interpolation. The lobe is
/// symmetric under mirroring either tangent axis, so such a quantity depends on the view's
/// cosine mu and on cos^2(phi) of its azimuth phi from the tangent alone: nodes uniform in
/// x = mu^(2/3) (mu clamped to [1e-4, 1], where the visible-normal sampler needs v above the
/// horizon) and in the azimuth coordinate u = (s + ln(1 + (q^2 - 1) s) / ln(q^2)) / 2, s the
/// squared cosine of the azimuth from the rougher axis and q the ratio of the roughnesses, at
/// most anisotropy_max. The logarithmic half is the projected roughness on a log scale (the
/// coordinate of anisotropic_albedo_table.hpp), which spreads the few degrees around the
/// smoother axis where a strong anisotropy turns most of it; alone it leaves one or two nodes
/// for the 40 degrees next to the rougher axis, where such quantities still change, and the
/// linear half keeps nodes there. Values are read bilinearly in (x, u).
template <std::floating_point T>
class anisotropic_view_grid {
public:
    static constexpr std::size_t mu_nodes = 16;      ///< view cosine nodes, uniform in mu^(2/3)
    static constexpr std::size_t azimuth_nodes = 13; ///< nodes uniform in u over [0, 1]
    static constexpr std::size_t size = mu_nodes * azimuth_nodes; ///< values per grid
    /// The largest q of the azimuth coordinate: a stronger anisotropy reads u with q = 20
    /// (as anisotropic_albedo_table.hpp's ratio_max), which keeps nodes away from the
    /// smoother axis too (with q = 1e4 the logarithmic half would crowd all but the last
    /// nodes within a few degrees of it).
    static constexpr double anisotropy_max = 20;

    anisotropic_view_grid() = default;

    anisotropic_view_grid(T alpha_x, T alpha_y) noexcept {
        x_rougher_ = alpha_x > alpha_y;
        const double q = x_rougher_ ? double(alpha_x) / double(alpha_y) : double(alpha_y) / double(alpha_x);
        log_q2_ = T(2 * std::log(glm::min(q, anisotropy_max)));
    }

    /// Calls node(k, v, mu, cos2_phi) for each node k in [0, size) (row-major: mu, then
    /// azimuth) with its unit local view v (double; n = +z), v.z = mu and cos^2 of v's
    /// azimuth from the tangent.
    template <class Node>
    void for_each_node(Node&& node) const {
        for (std::size_t i = 0; i < mu_nodes; ++i) {
            const double x = double(i) / double(mu_nodes - 1);
            const double mu = glm::clamp(x * std::sqrt(x), 1e-4, 1.0);
            const double sin_theta = std::sqrt((1 - mu) * (1 + mu));
            for (std::size_t j = 0; j < azimuth_nodes; ++j) {
                const double s_j = node_s(double(j) / double(azimuth_nodes - 1));
                const double cos2_phi = x_rougher_ ? s_j : 1 - s_j;
                const vec3<double> v(sin_theta * std::sqrt(cos2_phi), sin_theta * std::sqrt(1 - cos2_phi), mu);
                node(i * azimuth_nodes + j, v, mu, cos2_phi);
            }
        }
    }

    /// Calls point(node, a, b, v, mu, cos2_phi) at points inside the cells of the mu cells
    /// first to last (cell i lies between mu nodes i and i + 1; last is clamped to
    /// mu_nodes - 2): at x = i + p / (points + 1), p = 1 .. points, in mu and at every node
    /// and half-way between nodes in u, with node the index of the cell's first node (its
    /// others are node + 1, node + azimuth_nodes and node + azimuth_nodes + 1), a and b the
    /// point's place in the cell in x and in u (at() weighs the nodes (1 - a)(1 - b),
    /// (1 - a) b, a (1 - b), a b) and v, mu, cos2_phi as for_each_node's.
    template <class Point>
    void for_each_cell_point(std::size_t first, std::size_t last, std::size_t points, Point&& point) const {
        constexpr std::size_t half_steps = 2 * (azimuth_nodes - 1);
        for (std::size_t i = first; i <= glm::min(last, mu_nodes - 2); ++i) {
            for (std::size_t p = 1; p <= points; ++p) {
                const double t = double(p) / double(points + 1);
                const double x = (double(i) + t) / double(mu_nodes - 1);
                const double mu = glm::clamp(x * std::sqrt(x), 1e-4, 1.0);
                const double sin_theta = std::sqrt((1 - mu) * (1 + mu));
                for (std::size_t h = 0; h <= half_steps; ++h) {
                    const double s = node_s(double(h) / double(half_steps));
                    const double cos2_phi = x_rougher_ ? s : 1 - s;
                    const vec3<double> v(sin_theta * std::sqrt(cos2_phi), sin_theta * std::sqrt(1 - cos2_phi), mu);
                    const std::size_t j = glm::min(h / 2, azimuth_nodes - 2);
                    point(i * azimuth_nodes + j, t, 0.5 * double(h) - double(j), v, mu, cos2_phi);
                }
            }
        }
    }

    /// The mu cell (between mu nodes i and i + 1, at most mu_nodes - 2) holding the view
    /// cosine mu (clamped to [0, 1]; NaN read as 0), as at() reads it.
    [[nodiscard]] static std::size_t mu_cell(double mu) noexcept {
        const double c = mu > 0 ? glm::min(mu, 1.0) : 0.0;
        return glm::min(std::size_t(std::cbrt(c * c) * double(mu_nodes - 1)), mu_nodes - 2);
    }

    /// The values `grid` (one per node, for_each_node's order) at view cosine mu and
    /// cos^2(phi) (each clamped to [0, 1]; NaN read as 0), bilinear in (x, u).
    template <class V>
    [[nodiscard]] V at(const std::array<V, size>& grid, T mu, T cos2_phi) const noexcept {
        const T c = mu > T(0) ? glm::min(mu, T(1)) : T(0);
        const T x = std::cbrt(c * c) * T(mu_nodes - 1);
        const std::size_t i = glm::min(std::size_t(x), mu_nodes - 2);
        const T u = x - T(i);
        const T y = glm::min(azimuth(cos2_phi), T(1)) * T(azimuth_nodes - 1);
        const std::size_t j = glm::min(std::size_t(y), azimuth_nodes - 2);
        const T t = y - T(j);
        const V* row = grid.data() + i * azimuth_nodes + j;
        return (T(1) - u) * ((T(1) - t) * row[0] + t * row[1]) +
               u * ((T(1) - t) * row[azimuth_nodes] + t * row[azimuth_nodes + 1]);
    }

private:
    // u of cos^2(phi) (clamped to [0, 1]; NaN read as 0).
    [[nodiscard]] T azimuth(T cos2_phi) const noexcept {
        const T c = cos2_phi > T(0) ? glm::min(cos2_phi, T(1)) : T(0);
        return azimuth_of_s(x_rougher_ ? c : T(1) - c);
    }

    // u of s, the squared cosine of the azimuth from the rougher axis (s in [0, 1]).
    template <class U>
    [[nodiscard]] U azimuth_of_s(U s) const noexcept {
        const U log_q2 = U(log_q2_);
        const U log_part = log_q2 > U(0) ? std::log1p(std::expm1(log_q2) * s) / log_q2 : s;
        return U(0.5) * (s + log_part);
    }

    // s at the azimuth coordinate u in [0, 1]: the inverse of azimuth_of_s (increasing, from
    // 0 to 1) by bisection to double precision.
    [[nodiscard]] double node_s(double u) const noexcept {
        return bisect_increasing([this](double s) { return azimuth_of_s(s); }, u);
    }

    bool x_rougher_ = true; // alpha_x > alpha_y
    T log_q2_ = 1;          // ln(q^2)
};

} // namespace shade::detail
