#pragma once
// Checks of a model's sampler: that sample() draws directions with the density pdf()
// reports (chi-square goodness of fit), that the sample it returns agrees with f and pdf at
// its direction, that pdf integrates to at most 1 over the sphere, and that pdf covers f
// (no direction where f > 0 has pdf = 0). Each works on any shade::sampled_bsdf (a
// shade::sampled_brdf, or a BSDF with its own sampler, shade::bsdf_sampler, checked over
// the whole sphere with v on either side), and each returns a shade::check::result.

#include <algorithm>
#include <cmath>
#include <concepts>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include <shade/brdf/brdf.hpp>
#include <shade/bsdf/bsdf.hpp>
#include <shade/bsdf/refract.hpp>
#include <shade/check/chi2.hpp>
#include <shade/check/detail/model_ref.hpp>
#include <shade/check/directions.hpp>
#include <shade/check/positivity.hpp>
#include <shade/check/result.hpp>
#include <shade/core/error.hpp>
#include <shade/core/frame.hpp>
#include <shade/core/math.hpp>
#include <shade/core/random.hpp>

namespace shade::check {

/// Settings of chi2_goodness_of_fit and pdf_normalization.
struct chi2_options {
    std::size_t samples = 100000;  ///< directions drawn for the test
    /// Rings of the bins around the lobe axis (the mirror direction of v). Their edges in
    /// cos(angle to the axis) are quantiles of a separate pilot sample, so every ring holds
    /// about the same share of the samples however narrow the lobe.
    std::size_t rings = 10;
    std::size_t sectors = 20;      ///< bins in azimuth around the axis, each 2 pi / sectors
    double min_expected = 5;       ///< bins expecting fewer samples are pooled (pearson_chi2)
    /// Chance of a false rejection allowed for the whole family of `tests` chi-square tests
    /// the caller runs; each test rejects at sidak_significance(alpha, tests).
    double alpha = 0.01;
    std::size_t tests = 1;         ///< size of the family alpha is shared by
    /// Tolerance of the pdf integral: quadrature refines until the estimated error of the
    /// whole integral is about this absolute amount (1e-6 of the probability mass; with
    /// 1e5 samples, a tenth of a count) or each bin's is below quadrature_relative of the
    /// bin's integral (1e-4: with 1e6 samples, a twentieth of a bin's statistical spread).
    double quadrature_tolerance = 1e-6;
    double quadrature_relative = 1e-4; ///< see quadrature_tolerance
    double normalization_tolerance = 1e-3; ///< pdf_normalization passes when ∫pdf <= 1 + this
    /// The zoomed grid for sharp lobes (see chi2_goodness_of_fit) runs when a lobe's pilot
    /// draws lie within this angle of its centre (zoom_share of them; degrees). 0 turns it off.
    double zoom_below_degrees = 20;
    double zoom_share = 0.9;        ///< share of a lobe's pilot draws that decides it is sharp, in (0, 1)
    std::size_t zoom_rings = 10;    ///< rings of each side's bins in the zoomed grid (pilot quantiles)
    std::size_t zoom_sectors = 16;  ///< azimuth sectors of each side's bins around its lobe
    std::uint64_t seed = 1;        ///< seed of the pilot and of the tested samples
    std::string model = "BRDF";    ///< name used in the message
};

/// The outcome of chi2_goodness_of_fit. result::worst is the p-value and result::tolerance
/// the per-test significance level it was compared against (fail when p < level).
template <std::floating_point T>
struct chi2_result : result<T> {
    double statistic = 0;          ///< Pearson's chi-square over the pooled bins
    std::size_t dof = 0;           ///< its degrees of freedom
    double p_value = 1;            ///< probability of a statistic this large from a correct sampler
    double significance = 0;       ///< the per-test level (Šidák-corrected alpha)
    std::size_t bins = 0;          ///< bins after pooling (the "lost" bin included)
    std::size_t pooled = 0;        ///< bins merged into the low-expectation pool
    std::size_t samples = 0;       ///< directions drawn
    std::size_t lost = 0;          ///< draws that returned nullopt (expected: N (1 - ∫pdf))
    std::size_t invalid = 0;       ///< draws with a non-finite direction or pdf
    double pdf_integral = 0;       ///< ∫ pdf over the sphere, by quadrature (on the zoomed grid when zoomed)
    double integration_error = 0;  ///< the quadrature's error estimate of that integral
    /// True when a lobe was sharp and the zoomed grid ran (see chi2_goodness_of_fit).
    bool zoomed = false;
    double zoom_statistic = 0;     ///< Pearson's chi-square of the zoomed grid
    std::size_t zoom_dof = 0;      ///< its degrees of freedom
    double zoom_p_value = 1;       ///< its p-value (p_value is the smaller of the two)
    std::size_t zoom_bins = 0;     ///< its bins after pooling
};

namespace detail {

/// An integral and an estimate of its absolute error.
struct integral_estimate {
    double value = 0;
    double error = 0;
};

/// Stopping rule of adaptive_simpson: an interval is done when its halves agree with the
/// whole to 15 max(absolute, relative |halves|). The absolute part halves with each split
/// (so the parts sum to the total); the relative part does not, and keeps the recursion
/// from chasing the rounding noise of a float integrand.
struct quadrature_tolerance {
    double absolute = 1e-9;
    double relative = 1e-4;
};

/// One level of adaptive Simpson quadrature (Kuncir 1962, "Algorithm 103: Simpson's rule
/// integrator", CACM 5(6); the Richardson correction as in Lyness 1969, "Notes on the
/// adaptive Simpson quadrature routine", JACM 16(3)): S(a, b) = (b - a)/6 (f(a) + 4 f(m)
/// + f(b)); the interval is split until the two halves agree with the whole (see
/// quadrature_tolerance). f returns an integral_estimate (a value and the error already in
/// it, from an inner quadrature); the errors are integrated with the same weights and
/// added to the result's.
template <class F>
void simpson_refine(F& f, double a, double b, const integral_estimate& fa, const integral_estimate& fm,
                    const integral_estimate& fb, double whole, quadrature_tolerance tolerance, int depth,
                    integral_estimate& out) {
    const double m = 0.5 * (a + b);
    const double lm = 0.5 * (a + m);
    const double rm = 0.5 * (m + b);
    const integral_estimate flm = f(lm);
    const integral_estimate frm = f(rm);
    const double h = (b - a) / 12; // each half has width (b - a)/2, Simpson weight width/6
    const double left = h * (fa.value + 4 * flm.value + fm.value);
    const double right = h * (fm.value + 4 * frm.value + fb.value);
    const double delta = left + right - whole;
    const double allowed = 15 * std::max(tolerance.absolute, tolerance.relative * std::abs(left + right));
    if (depth <= 0 || std::abs(delta) <= allowed || !std::isfinite(delta)) {
        out.value += left + right + delta / 15;
        // At the depth limit the correction is not trustworthy: count all of delta.
        out.error += (depth <= 0 ? std::abs(delta) : std::abs(delta) / 15) +
                     h * (fa.error + 4 * flm.error + 2 * fm.error + 4 * frm.error + fb.error);
        return;
    }
    tolerance.absolute /= 2;
    simpson_refine(f, a, m, fa, flm, fm, left, tolerance, depth - 1, out);
    simpson_refine(f, m, b, fm, frm, fb, right, tolerance, depth - 1, out);
}

/// ∫_a^b f with adaptive Simpson quadrature to a tolerance, starting from `panels` equal
/// panels so that a feature narrower than [a, b] is not stepped over by the first five
/// points, with at most `max_depth` halvings per panel.
template <class F>
integral_estimate adaptive_simpson(F&& f, double a, double b, quadrature_tolerance tolerance, int panels = 4,
                                   int max_depth = 14) {
    tolerance.absolute /= panels;
    integral_estimate out;
    const double width = (b - a) / panels;
    integral_estimate fa = f(a);
    for (int k = 0; k < panels; ++k) {
        const double x0 = a + width * k;
        const double x1 = k + 1 == panels ? b : x0 + width;
        const integral_estimate fm = f(0.5 * (x0 + x1));
        const integral_estimate fb = f(x1);
        const double whole = (x1 - x0) / 6 * (fa.value + 4 * fm.value + fb.value);
        simpson_refine(f, x0, x1, fa, fm, fb, whole, tolerance, max_depth, out);
        fa = fb;
    }
    return out;
}

/// The bins of the sampling checks: rings in c = cos(angle to the axis) with the given
/// edges (from -1 to 1), each split into `sectors` equal azimuth sectors around the axis.
struct sphere_bins {
    frame<double> axis;          ///< the bins' frame; its normal is the axis
    std::vector<double> edges;   ///< ring edges in c, increasing, from -1 to 1
    std::size_t sectors = 1;

    [[nodiscard]] std::size_t count() const noexcept { return (edges.size() - 1) * sectors; }

    /// The bin of the unit direction w (world space).
    [[nodiscard]] std::size_t index(const glm::dvec3& w) const {
        const glm::dvec3 local = axis.to_local(w);
        const double c = std::clamp(local.z, -1.0, 1.0);
        const auto ring = std::size_t(std::clamp<std::ptrdiff_t>(
            std::upper_bound(edges.begin(), edges.end(), c) - edges.begin() - 1, 0,
            std::ptrdiff_t(edges.size()) - 2));
        double phi = std::atan2(local.y, local.x);
        if (phi < 0) phi += 2 * pi<double>;
        const auto sector = std::min(std::size_t(phi / (2 * pi<double>) * double(sectors)), sectors - 1);
        return ring * sectors + sector;
    }
};

/// The side of the surface w is on: +1 where n·w > 0, else -1 (the surface itself counted
/// inside, a set of measure 0).
inline int side_of(const glm::dvec3& n, const glm::dvec3& w) { return glm::dot(n, w) > 0 ? 1 : -1; }

/// The mirror direction of v about the normal of `at`, in double: the axis the bins are
/// built around (every shipped lobe peaks on or near it; a diffuse lobe is smooth around
/// any axis).
template <std::floating_point T>
glm::dvec3 lobe_axis(const vec3<T>& v, const surface_point<T>& at) {
    const glm::dvec3 n(at.n());
    const glm::dvec3 vd(v);
    return glm::normalize(2 * glm::dot(n, vd) * n - vd);
}

/// `pilot` unit directions drawn by the sampler for v (finite ones only), from a stream of
/// their own: independent of the tested draws, so bins built from them do not depend on
/// the data they test.
template <std::floating_point T>
std::vector<glm::dvec3> pilot_draws(const model_ref<T>& model, const vec3<T>& v, const surface_point<T>& at,
                                    std::size_t pilot, std::uint64_t seed) {
    std::vector<glm::dvec3> draws;
    draws.reserve(pilot);
    rng random(seed, 0x9e3779b97f4a7c15ULL);
    for (std::size_t i = 0; i < pilot; ++i) {
        const T uc = random.uniform<T>();
        const vec2<T> u(random.uniform<T>(), random.uniform<T>());
        const auto s = model.sample(v, uc, u, at);
        if (s && is_finite(s->l)) draws.push_back(glm::normalize(glm::dvec3(s->l)));
    }
    return draws;
}

/// Bins around `axis` with rings from c = `lowest` to 1 (c = cos(angle to the axis))
/// holding about equal shares of the values c (quantiles; uniform rings when c is empty).
inline sphere_bins quantile_bins(const glm::dvec3& axis, double lowest, std::vector<double> c, std::size_t rings,
                                 std::size_t sectors) {
    sphere_bins bins{frame<double>::from_normal(axis), {}, sectors};
    std::sort(c.begin(), c.end());
    bins.edges.push_back(lowest);
    for (std::size_t k = 1; k < rings; ++k) {
        const double edge =
            c.empty() ? lowest + (1 - lowest) * double(k) / double(rings) : c[k * c.size() / rings];
        // Equal quantiles (a sampler that repeats a direction) would make empty rings.
        if (edge > bins.edges.back() + 1e-12 && edge < 1 - 1e-12) bins.edges.push_back(edge);
    }
    bins.edges.push_back(1);
    return bins;
}

/// Bins over the whole sphere around the mirror direction of v whose rings hold about
/// equal shares of the pilot draws.
template <std::floating_point T>
sphere_bins pilot_bins(const std::vector<glm::dvec3>& draws, const vec3<T>& v, const surface_point<T>& at,
                       std::size_t rings, std::size_t sectors) {
    const glm::dvec3 axis = lobe_axis(v, at);
    std::vector<double> c;
    c.reserve(draws.size());
    for (const auto& w : draws) c.push_back(glm::dot(w, axis));
    return quantile_bins(axis, -1, std::move(c), rings, sectors);
}

/// The zoomed grid: one set of bins for each side of the surface, around the centre of the
/// lobe drawn to that side (the mirror direction of v on v's side; on the other side the
/// mean direction of the pilot draws there, the centre of a refraction lobe), with rings
/// at quantiles of the pilot draws on that side (options.zoom_rings) and
/// options.zoom_sectors sectors. A direction falls in the bins of its side only (side_of),
/// so the two sets partition the sphere. Empty when neither lobe is sharp: a side's lobe
/// is sharp when it holds at least 5 % of the draws and 200 of them, and
/// options.zoom_share of them lie within options.zoom_below_degrees of its centre.
template <std::floating_point T>
std::vector<sphere_bins> zoom_grid(const std::vector<glm::dvec3>& draws, const vec3<T>& v, const surface_point<T>& at,
                                   const chi2_options& options) {
    std::vector<sphere_bins> grid;
    if (!(options.zoom_below_degrees > 0) || options.zoom_rings < 1 || options.zoom_sectors < 1) return grid;
    const glm::dvec3 n(at.n());
    const int side_v = side_of(n, glm::dvec3(v));
    bool sharp = false;
    for (const int side : {side_v, -side_v}) {
        std::vector<glm::dvec3> group;
        glm::dvec3 sum(0);
        for (const auto& w : draws) {
            if (side_of(n, w) != side) continue;
            group.push_back(w);
            sum += w;
        }
        const glm::dvec3 mirror = lobe_axis(v, at);
        // With few draws on the other side (a BRDF: none), its bins are centred on the
        // mirror image of the mirror direction, and uniform.
        const bool enough =
            group.size() >= 200 && double(group.size()) >= 0.05 * double(draws.size()) && glm::length(sum) > 0;
        const glm::dvec3 axis = side == side_v ? mirror
                                : enough       ? glm::normalize(sum)
                                               : mirror - 2 * glm::dot(mirror, n) * n;
        std::vector<double> c;
        c.reserve(group.size());
        for (const auto& w : group) c.push_back(glm::dot(w, axis));
        if (enough) {
            std::vector<double> sorted = c;
            std::sort(sorted.begin(), sorted.end());
            const auto k = std::size_t((1 - options.zoom_share) * double(sorted.size()));
            const double width = std::acos(std::clamp(sorted[std::min(k, sorted.size() - 1)], -1.0, 1.0));
            if (width * 180 / pi<double> < options.zoom_below_degrees) sharp = true;
        } else {
            c.clear();
        }
        grid.push_back(quantile_bins(axis, -1, std::move(c), options.zoom_rings, options.zoom_sectors));
    }
    if (!sharp) grid.clear();
    return grid;
}

/// The index of the zoomed grid's cell holding w: the bins of grid[0] (v's side) for w on
/// v's side, else those of grid[1] after them.
inline std::size_t zoom_index(const std::vector<sphere_bins>& grid, int side_v, const glm::dvec3& n,
                              const glm::dvec3& w) {
    return side_of(n, w) == side_v ? grid[0].index(w) : grid[0].count() + grid[1].index(w);
}

/// ∫ pdf(l, v) dl over each bin, by nested adaptive Simpson quadrature in (c, phi) around
/// the bins' axis, where dl = dc dphi (the solid angle in those coordinates). The absolute
/// tolerance is shared out among the bins; the relative one applies to each.
/// With side = +1 or -1, only the directions on that side (side_of) count: the integrand
/// is 0 on the other.
template <std::floating_point T>
std::vector<integral_estimate> integrate_pdf(const model_ref<T>& model, const vec3<T>& v,
                                             const surface_point<T>& at, const sphere_bins& bins,
                                             quadrature_tolerance tolerance, int side = 0) {
    const glm::dvec3 normal(at.n());
    std::vector<integral_estimate> cells(bins.count());
    const double sector_width = 2 * pi<double> / double(bins.sectors);
    const double cell_tolerance = tolerance.absolute / double(bins.count());
    for (std::size_t ring = 0; ring + 1 < bins.edges.size(); ++ring) {
        const double c0 = bins.edges[ring];
        const double c1 = bins.edges[ring + 1];
        for (std::size_t sector = 0; sector < bins.sectors; ++sector) {
            const double phi0 = sector_width * double(sector);
            const double phi1 = sector + 1 == bins.sectors ? 2 * pi<double> : phi0 + sector_width;
            const auto over_phi = [&](double c) {
                const double s = std::sqrt(std::max(0.0, (1 - c) * (1 + c)));
                const auto density = [&](double phi) {
                    const glm::dvec3 w = bins.axis.to_world(glm::dvec3(s * std::cos(phi), s * std::sin(phi), c));
                    if (side != 0 && side_of(normal, w) != side) return integral_estimate{0, 0};
                    const vec3<T> l = glm::normalize(vec3<T>(w));
                    return integral_estimate{double(model.pdf(l, v, at)), 0};
                };
                // The inner integral is multiplied by at most (c1 - c0) in the outer one.
                return adaptive_simpson(density, phi0, phi1,
                                        {0.25 * cell_tolerance / (c1 - c0), 0.25 * tolerance.relative});
            };
            cells[ring * bins.sectors + sector] =
                adaptive_simpson(over_phi, c0, c1, {0.5 * cell_tolerance, 0.5 * tolerance.relative});
        }
    }
    return cells;
}

/// ∫ pdf over each cell of the zoomed grid (zoom_grid, in zoom_index order): each side on
/// the bins of its own lobe.
template <std::floating_point T>
std::vector<integral_estimate> integrate_zoomed(const model_ref<T>& model, const vec3<T>& v,
                                                const surface_point<T>& at, const std::vector<sphere_bins>& grid,
                                                quadrature_tolerance tolerance) {
    tolerance.absolute /= 2;
    const int side_v = side_of(glm::dvec3(at.n()), glm::dvec3(v));
    std::vector<integral_estimate> cells = integrate_pdf(model, v, at, grid[0], tolerance, side_v);
    const auto other = integrate_pdf(model, v, at, grid[1], tolerance, -side_v);
    cells.insert(cells.end(), other.begin(), other.end());
    return cells;
}

/// "theta_v = 30 deg, v = (...)".
template <std::floating_point T>
std::string view_text(const vec3<T>& v, const surface_point<T>& at) {
    const double theta = std::acos(std::clamp(double(glm::dot(v, at.n())), -1.0, 1.0)) * 180.0 / pi<double>;
    return "theta_v = " + number(theta, 4) + " deg, v = " + shade::detail::to_text(v);
}

template <std::floating_point T>
void require_view_above(const vec3<T>& v, const surface_point<T>& at) {
    if (!(glm::dot(v, at.n()) > T(0)))
        throw invalid_parameter("v", "must be above the surface (n.v > 0)", shade::detail::to_text(v));
}

/// For a two-sided model (a BSDF's own sampler, model_ref::two_sided) v may be on either
/// side but not on the surface; otherwise it must be above (require_view_above).
template <std::floating_point T>
void require_view_for(const model_ref<T>& model, const vec3<T>& v, const surface_point<T>& at) {
    if (!model.two_sided()) return require_view_above(v, at);
    if (!(glm::dot(v, at.n()) != T(0)))
        throw invalid_parameter("v", "must not lie on the surface (n.v != 0)", shade::detail::to_text(v));
}

/// The body of chi2_goodness_of_fit (see there), on the type-erased model.
template <std::floating_point T>
chi2_result<T> run_chi2_goodness_of_fit(const model_ref<T>& model, const vec3<T>& v, const surface_point<T>& at,
                                        const chi2_options& options) {
    detail::require_view_for(model, v, at);
    if (options.samples < 100)
        throw invalid_parameter("samples", "must be >= 100", shade::detail::to_text(double(options.samples)));
    if (options.rings < 1 || options.sectors < 1)
        throw invalid_parameter(options.rings < 1 ? "rings" : "sectors", "must be >= 1", "0");
    chi2_result<T> r;
    r.property = "sampling (chi-square)";
    r.model = options.model;
    r.at = at;
    r.v = v;
    r.l = v;
    r.significance = sidak_significance(options.alpha, options.tests);
    r.tolerance = r.significance;
    const std::size_t pilot = std::clamp<std::size_t>(options.samples / 10, 1000, 20000);
    const auto draws = detail::pilot_draws(model, v, at, pilot, options.seed);
    const detail::sphere_bins bins = detail::pilot_bins(draws, v, at, options.rings, options.sectors);
    const std::vector<detail::sphere_bins> grid = detail::zoom_grid(draws, v, at, options);
    const bool zoom = !grid.empty();
    const glm::dvec3 normal(at.n());
    const int side_v = detail::side_of(normal, glm::dvec3(v));
    std::vector<double> observed(bins.count() + 1, 0.0);
    std::vector<double> zoom_observed(zoom ? grid[0].count() + grid[1].count() + 1 : 0, 0.0);
    rng random(options.seed);
    for (std::size_t i = 0; i < options.samples; ++i) {
        const T uc = random.uniform<T>();
        const vec2<T> u(random.uniform<T>(), random.uniform<T>());
        const auto s = model.sample(v, uc, u, at);
        if (!s) {
            ++r.lost;
        } else if (!is_finite(s->l) || !std::isfinite(s->pdf)) {
            ++r.invalid;
            r.l = s->l;
        } else {
            const glm::dvec3 w = glm::normalize(glm::dvec3(s->l));
            observed[bins.index(w)] += 1;
            if (zoom) zoom_observed[detail::zoom_index(grid, side_v, normal, w)] += 1;
        }
    }
    r.samples = options.samples;
    observed.back() = double(r.lost);
    if (zoom) zoom_observed.back() = double(r.lost);
    const auto cells = detail::integrate_pdf(model, v, at, bins,
                                             {options.quadrature_tolerance, options.quadrature_relative});
    std::vector<double> expected(cells.size() + 1, 0.0);
    const double n = double(options.samples);
    for (std::size_t k = 0; k < cells.size(); ++k) {
        expected[k] = n * cells[k].value;
        r.pdf_integral += cells[k].value;
        r.integration_error += cells[k].error;
    }
    expected.back() = n * std::max(0.0, 1 - r.pdf_integral);
    const chi2_statistic s = pearson_chi2(observed, expected, options.min_expected);
    r.statistic = s.statistic;
    r.dof = s.dof;
    r.bins = s.bins;
    r.pooled = s.pooled;
    r.tried = r.samples;
    r.p_value = r.dof > 0 ? chi2_p_value(r.statistic, double(r.dof)) : 1.0;
    std::string zoom_numbers;
    if (zoom) {
        // The zoomed grid: a second test of the same draws, so each of the two rejects at
        // the Šidák level of a family twice as large.
        r.zoomed = true;
        r.significance = sidak_significance(options.alpha, 2 * options.tests);
        r.tolerance = r.significance;
        const auto zoomed =
            detail::integrate_zoomed(model, v, at, grid, {options.quadrature_tolerance, options.quadrature_relative});
        std::vector<double> zoom_expected(zoomed.size() + 1, 0.0);
        double total = 0, error = 0;
        for (std::size_t k = 0; k < zoomed.size(); ++k) {
            zoom_expected[k] = n * zoomed[k].value;
            total += zoomed[k].value;
            error += zoomed[k].error;
        }
        zoom_expected.back() = n * std::max(0.0, 1 - total);
        // The zoomed quadrature resolves the sharp lobes: its integral is the one reported.
        r.pdf_integral = total;
        r.integration_error = error;
        const chi2_statistic z = pearson_chi2(zoom_observed, zoom_expected, options.min_expected);
        r.zoom_statistic = z.statistic;
        r.zoom_dof = z.dof;
        r.zoom_bins = z.bins;
        r.zoom_p_value = z.dof > 0 ? chi2_p_value(z.statistic, double(z.dof)) : 1.0;
        r.p_value = std::min(r.p_value, r.zoom_p_value);
        zoom_numbers = "; zoomed grid (each side around its lobe): chi2 = " + detail::number(z.statistic) + " with " +
                       std::to_string(z.dof) + " dof, p = " + detail::number(r.zoom_p_value, 3) + ", " +
                       std::to_string(z.bins) + " bins";
    }
    r.worst = r.p_value;
    const std::string numbers = "chi2 = " + detail::number(r.statistic) + " with " + std::to_string(r.dof) +
                                " dof, p = " + detail::number(r.p_value, 3) + " (level " +
                                detail::number(r.significance, 3) + "), " + std::to_string(r.samples) +
                                " draws into " + std::to_string(r.bins) + " bins (" + std::to_string(r.pooled) +
                                " pooled), " + std::to_string(r.lost) + " nullopt" + zoom_numbers +
                                ", integral of pdf " + detail::number(r.pdf_integral) + " +- " +
                                detail::number(r.integration_error, 2) + ", at " + detail::view_text(v, at);
    if (r.invalid > 0) {
        r.failures = r.invalid;
        r.decide(verdict::fail);
        r.message = "sampling FAILS for " + r.model + ": " + std::to_string(r.invalid) +
                    " draws returned a non-finite direction or pdf (e.g. l = " + shade::detail::to_text(r.l) +
                    ") at " + detail::view_text(v, at) + ".";
    } else if (r.dof == 0 && r.zoom_dof == 0) {
        r.decide(verdict::inconclusive);
        r.message = "sampling is INCONCLUSIVE for " + r.model + ": too few bins left after pooling to test; " +
                    numbers + ". Raise samples.";
    } else if (r.p_value < r.significance) {
        r.failures = 1;
        r.decide(verdict::fail);
        r.message = "sampling FAILS for " + r.model + ": sample() does not draw directions with the density pdf() "
                    "reports; " + numbers + ". Check that pdf matches the sampling method (its normalisation, "
                    "its axis, the lobe-selection probabilities).";
    } else {
        r.decide(verdict::pass);
        r.message = "sampling matches pdf for " + r.model + ": " + numbers + ".";
    }
    return r;
}

} // namespace detail

/// The density part of a model with delta lobes (shade::bsdf_sampler): the same f and pdf,
/// and a sample that returns nullopt in place of a delta lobe's draw (is_specular(flags)).
/// chi2_goodness_of_fit and pdf_normalization test a model's density: a delta draw lands
/// on a direction where pdf is 0, so the model itself fails them. Through density_part the
/// delta draws fall in the nullopt bin, whose expected count is N (1 - ∫pdf), so the test
/// checks both that the delta lobes are drawn with the probability the density leaves to
/// them and, over the sphere's bins, the density itself. Holds a copy of the model.
template <sampled_bsdf M>
struct density_part {
    using scalar_type = scalar_of<M>;

    M model; ///< the model whose density is tested

    /// The model's f(l, v, at) (1/sr, no cosine).
    [[nodiscard]] rgb<scalar_type> f(const vec3<scalar_type>& l, const vec3<scalar_type>& v,
                                     const surface_point<scalar_type>& at) const {
        return model.f(l, v, at);
    }

    /// The model's pdf(l, v, at) (1/sr, solid angle; delta lobes contribute 0).
    [[nodiscard]] scalar_type pdf(const vec3<scalar_type>& l, const vec3<scalar_type>& v,
                                  const surface_point<scalar_type>& at) const {
        return model.pdf(l, v, at);
    }

    /// shade::sample_bsdf(model, ...), with nullopt for a draw flagged specular.
    [[nodiscard]] std::optional<bsdf_sample<scalar_type>>
    sample(const vec3<scalar_type>& v, scalar_type uc, const vec2<scalar_type>& u,
           const surface_point<scalar_type>& at, transport_mode mode = transport_mode::radiance) const {
        auto s = sample_bsdf(model, v, uc, u, at, mode);
        if (s && is_specular(s->flags)) return std::nullopt;
        return s;
    }
};

template <class M>
density_part(M) -> density_part<M>;

/// Chi-square goodness-of-fit test of `sample` against `pdf` for the view v (world space,
/// above the surface) at `at`: the method of pbrt-v4's BSDF tests (Pharr, Jakob, Humphreys
/// 2023, "Physically Based Rendering", 4th ed., src/pbrt/bsdfs_test.cpp) and Mitsuba 3's
/// chi2 module, on bins suited to narrow lobes.
///
/// The sphere of directions is cut into options.rings rings around the mirror direction of
/// v (edges at quantiles of a pilot sample) times options.sectors azimuth sectors, plus one
/// bin for draws that return nullopt. options.samples directions are drawn with independent
/// uniform (uc, u); the expected count of a bin is N ∫_bin pdf dl, by adaptive quadrature,
/// and of the nullopt bin N (1 - ∫_sphere pdf dl), since a sampler returns nullopt exactly
/// for the mass pdf does not account for. Pearson's statistic over the pooled bins
/// (pearson_chi2) gives the p-value; the test fails when p < sidak_significance(alpha,
/// tests), when a draw has a non-finite direction or pdf, and is inconclusive when pooling
/// leaves fewer than two bins. For a BRDF, v must be above the surface and pdf must be 0
/// below it (sample never returns such directions), or the bins there show it. For a BSDF
/// with its own sampler (shade::bsdf_sampler, radiance mode), v may be on either side and
/// the bins cover the whole sphere, transmission included; a model whose lobes are all
/// delta lobes has no density to test (pdf = 0) and fails.
///
/// Sharp lobes (zoom_grid: options.zoom_share of a lobe's pilot draws within
/// options.zoom_below_degrees of its centre) get a second test of the same draws on a
/// zoomed grid: each side of the surface binned around the centre of the lobe drawn to it
/// (the mirror direction of v, the mean direction of the pilot's refractions), in
/// options.zoom_rings rings at quantiles of that side's pilot draws times
/// options.zoom_sectors sectors, plus the nullopt bin. The whole-sphere grid is centred on
/// the mirror direction, so it cuts a narrow refraction lobe in bands and resolves it
/// across them only through its sectors; the zoomed grid resolves it in both directions.
/// Its expected counts come from the same quadrature on its own bins, each side's
/// integrand 0 on the other side, and its ∫pdf is the one reported. The two tests then
/// reject each at sidak_significance(alpha, 2 tests); p_value is the smaller p-value.
template <sampled_bsdf B>
chi2_result<scalar_of<B>> chi2_goodness_of_fit(const B& model, const vec3<scalar_of<B>>& v,
                                               const surface_point<scalar_of<B>>& at,
                                               const chi2_options& options = {}) {
    return detail::run_chi2_goodness_of_fit(detail::model_ref<scalar_of<B>>(model), v, at, options);
}

namespace detail {

/// The body of pdf_normalization (see there), on the type-erased model.
template <std::floating_point T>
result<T> run_pdf_normalization(const model_ref<T>& model, const vec3<T>& v, const surface_point<T>& at,
                                const chi2_options& options) {
    detail::require_view_for(model, v, at);
    result<T> r;
    r.property = "pdf normalization";
    r.model = options.model;
    r.at = at;
    r.v = v;
    r.l = v;
    r.tolerance = require_non_negative("normalization_tolerance", options.normalization_tolerance);
    const std::size_t pilot = std::clamp<std::size_t>(options.samples / 10, 1000, 20000);
    const auto draws = detail::pilot_draws(model, v, at, pilot, options.seed);
    const auto bins = detail::pilot_bins(draws, v, at, std::max<std::size_t>(options.rings, 1),
                                         std::max<std::size_t>(options.sectors, 1));
    const auto grid = detail::zoom_grid(draws, v, at, options);
    const detail::quadrature_tolerance tolerance{options.quadrature_tolerance, options.quadrature_relative};
    for (const auto& cell : grid.empty() ? detail::integrate_pdf(model, v, at, bins, tolerance)
                                         : detail::integrate_zoomed(model, v, at, grid, tolerance)) {
        r.worst += cell.value;
        r.error += cell.error;
    }
    r.tried = 1;
    r.decide(decide_at_most(r.worst, r.error, 1 + r.tolerance, 1));
    r.failures = r.outcome == verdict::fail ? 1 : 0;
    const std::string numbers = "integral of pdf over the sphere " + detail::number(r.worst) + " +- " +
                                detail::number(r.error, 2) + " (quadrature error) at " + detail::view_text(v, at);
    if (r.outcome == verdict::pass) {
        r.message = "pdf normalization holds for " + r.model + ": " + numbers + ", within 1 + " +
                    detail::number(r.tolerance) + ".";
    } else if (r.outcome == verdict::fail) {
        r.message = "pdf normalization FAILS for " + r.model + ": " + numbers + " exceeds 1 + " +
                    detail::number(r.tolerance) + ". pdf over-reports the density: check its normalisation "
                    "constant and the lobe-selection probabilities.";
    } else {
        r.message = "pdf normalization is INCONCLUSIVE for " + r.model + ": " + numbers +
                    " is within its error of 1 + " + detail::number(r.tolerance) + ". Lower quadrature_tolerance.";
    }
    return r;
}

} // namespace detail

/// Checks ∫ pdf(l, v) dl <= 1 over the sphere for the view v (world space, above the
/// surface; for a shade::bsdf_sampler on either side) at `at`: a density may lose mass (a sampler may return nullopt) but never
/// create it. The integral is computed by adaptive quadrature over the bins of
/// chi2_goodness_of_fit (options.rings, options.sectors, pilot from options.seed, tolerance
/// options.quadrature_tolerance), on its zoomed grid when a lobe is sharp. result::worst is the integral and result::error the
/// quadrature's error estimate; the verdict is decide_at_most(integral, error,
/// 1 + options.normalization_tolerance, 1).
template <sampled_bsdf B>
result<scalar_of<B>> pdf_normalization(const B& model, const vec3<scalar_of<B>>& v,
                                       const surface_point<scalar_of<B>>& at, const chi2_options& options = {}) {
    return detail::run_pdf_normalization(detail::model_ref<scalar_of<B>>(model), v, at, options);
}

/// Settings of sample_consistency.
struct sample_options {
    std::size_t views = 500;            ///< views v (from hemisphere_pairs: hard cases first)
    std::size_t samples_per_view = 40;  ///< draws per view
    /// Relative tolerance of the comparisons of f, pdf and weight; < 0 picks 1e-3 for float
    /// and 1e-6 for double (the sampler and f may reach the same value along different
    /// roundings, e.g. through the half vector or the microfacet normal).
    double relative_tolerance = -1;
    std::uint64_t seed = 1;             ///< seed of the views and the draws
    std::string model = "BRDF";         ///< name used in the message
    /// For a BSDF with its own sampler: the relative index n_inside / n_outside its
    /// transmissions must cross (a sample's eta is eta_inside seen from outside, 1 /
    /// eta_inside from inside; 1 for a thin pane with the same medium on both sides). 0:
    /// not given, and the transmissions need only agree with each other (the first one
    /// drawn sets the value). Not used for a BRDF.
    double eta_inside = 0;
};

namespace detail {

/// |a - b| / max(|a|, |b|), 0 when both are 0: the relative error of sample_consistency.
inline double consistency_relative(double a, double b) {
    const double scale = std::max(std::abs(a), std::abs(b));
    return scale > 0 ? std::abs(a - b) / scale : 0.0;
}

/// The bookkeeping both sample_consistency bodies share: counts a measure above the
/// result's tolerance as a failure and keeps the worst (NaN counts as infinite) with its
/// rule and directions.
template <std::floating_point T>
struct consistency_tally {
    result<T>& r;
    std::string worst_what = "nothing"; ///< the rule of the worst measure

    void record(double measure, const char* what, const vec3<T>& l, const vec3<T>& v) {
        if (!(measure <= r.tolerance)) ++r.failures;
        if (!(measure <= r.worst)) { // NaN and the first violation both land here
            r.worst = std::isnan(measure) ? std::numeric_limits<double>::infinity() : measure;
            worst_what = what;
            r.l = l;
            r.v = v;
        }
    }
};

/// The body of sample_consistency (see there) for a BSDF with its own sampler
/// (model_ref::two_sided): views from both sides, both transport modes.
template <std::floating_point T>
result<T> run_bsdf_sample_consistency(const model_ref<T>& model, const surface_point<T>& at,
                                      const sample_options& options);

/// The body of sample_consistency (see there), on the type-erased model.
template <std::floating_point T>
result<T> run_sample_consistency(const model_ref<T>& model, const surface_point<T>& at,
                                 const sample_options& options) {
    if (model.two_sided()) return run_bsdf_sample_consistency(model, at, options);
    result<T> r;
    r.property = "sample consistency";
    r.model = options.model;
    r.at = at;
    r.tolerance = options.relative_tolerance >= 0 ? options.relative_tolerance : (sizeof(T) <= 4 ? 1e-3 : 1e-6);
    const vec3<T> n = at.n();
    consistency_tally<T> tally{r};
    const auto relative = consistency_relative;
    const auto record = [&tally](double measure, const char* what, const vec3<T>& l, const vec3<T>& v) {
        tally.record(measure, what, l, v);
    };
    const auto infinite = std::numeric_limits<double>::infinity();
    rng random(options.seed ^ 0x5851f42d4c957f2dULL);
    for (const auto& pair : hemisphere_pairs(at, options.views, options.seed)) {
        const vec3<T> v = pair.v;
        for (std::size_t i = 0; i < options.samples_per_view; ++i) {
            const T uc = random.uniform<T>();
            const vec2<T> u(random.uniform<T>(), random.uniform<T>());
            const auto s = model.sample(v, uc, u, at);
            ++r.tried;
            if (!s) continue;
            const vec3<T> l = s->l;
            if (!is_finite(l) || std::abs(double(glm::length(l)) - 1) > r.tolerance) {
                record(infinite, "|l| = 1", l, v);
                continue;
            }
            if (!(glm::dot(n, l) > T(0))) {
                record(infinite, "l above the surface", l, v);
                continue;
            }
            if (!(s->pdf > T(0)) || !std::isfinite(s->pdf)) {
                record(infinite, "pdf finite and > 0", l, v);
                continue;
            }
            record(relative(double(s->pdf), double(model.pdf(l, v, at))), "pdf = pdf(l, v)", l, v);
            const rgb<T> f = model.f(l, v, at);
            const double abs_n_dot_l = std::abs(double(glm::dot(n, l)));
            for (int c = 0; c < 3; ++c) {
                record(relative(double(s->f[c]), double(f[c])), "f = f(l, v)", l, v);
                record(relative(double(s->weight[c]), double(s->f[c]) * abs_n_dot_l / double(s->pdf)),
                       "weight = f |n.l| / pdf", l, v);
            }
        }
    }
    // Views below the surface: the mirror images of a few tested views.
    for (const auto& pair : hemisphere_pairs(at, 20, options.seed + 1)) {
        const vec3<T> v = glm::normalize(pair.v - T(2) * glm::dot(n, pair.v) * n);
        const auto s = model.sample(v, T(0.5), vec2<T>(T(0.3), T(0.6)), at);
        ++r.tried;
        if (s) record(infinite, "nullopt for v below the surface", s->l, v);
    }
    r.decide(r.failures == 0 ? verdict::pass : verdict::fail);
    if (r.passed) {
        r.message = "sample consistency holds for " + r.model + ": " + std::to_string(r.tried) +
                    " draws agree with f and pdf, weight = f |n.l| / pdf, within " + detail::number(r.tolerance) +
                    " (worst " + detail::number(r.worst, 3) + ").";
    } else {
        r.message = "sample consistency FAILS for " + r.model + ": " + std::to_string(r.failures) + " of " +
                    std::to_string(r.tried) + " checks broke the rule '" + tally.worst_what + "'; worst relative error " +
                    detail::number(r.worst, 3) + " for " + detail::where(r.l, r.v, at) +
                    ". A brdf_sample must hold exactly what f and pdf return at its direction.";
    }
    return r;
}

template <std::floating_point T>
result<T> run_bsdf_sample_consistency(const model_ref<T>& model, const surface_point<T>& at,
                                      const sample_options& options) {
    if (options.eta_inside != 0) require_in_range("eta_inside", options.eta_inside, 1e-4, 1e4);
    result<T> r;
    r.property = "sample consistency (BSDF)";
    r.model = options.model;
    r.at = at;
    r.tolerance = options.relative_tolerance >= 0 ? options.relative_tolerance : (sizeof(T) <= 4 ? 1e-3 : 1e-6);
    const vec3<T> n = at.n();
    consistency_tally<T> tally{r};
    const auto relative = consistency_relative;
    const auto record = [&tally](double measure, const char* what, const vec3<T>& l, const vec3<T>& v) {
        tally.record(measure, what, l, v);
    };
    const auto infinite = std::numeric_limits<double>::infinity();
    // eta_inside as given, or as the first transmission sets it (0 until then).
    double eta_inside = options.eta_inside;
    const auto kinds = bsdf_flags::diffuse | bsdf_flags::glossy | bsdf_flags::specular;
    const auto single_bit = [](bsdf_flags f) {
        const auto bits = static_cast<unsigned>(f);
        return bits != 0 && (bits & (bits - 1)) == 0;
    };
    // Checks one draw s (in `mode`) for the view v; true when it is fit for the comparisons
    // of the two modes.
    const auto check = [&](const bsdf_sample<T>& s, const vec3<T>& v, transport_mode mode) {
        const vec3<T> l = s.l;
        if (!is_finite(l) || std::abs(double(glm::length(l)) - 1) > r.tolerance) {
            record(infinite, "|l| = 1", l, v);
            return false;
        }
        const bool reflection = is_reflection(s.flags);
        if (reflection == is_transmission(s.flags)) {
            record(infinite, "flags: exactly one of reflection and transmission", l, v);
            return false;
        }
        if (!single_bit(s.flags & kinds)) {
            record(infinite, "flags: exactly one of diffuse, glossy and specular", l, v);
            return false;
        }
        const double n_dot_v = double(glm::dot(n, v));
        const double n_dot_l = double(glm::dot(n, l));
        if (reflection ? !(n_dot_l * n_dot_v > 0) : !(n_dot_l * n_dot_v < 0)) {
            record(infinite, reflection ? "a reflection's l on v's side" : "a transmission's l on the other side", l,
                   v);
            return false;
        }
        if (!(s.eta > T(0)) || !std::isfinite(s.eta)) {
            record(infinite, "eta finite and > 0", l, v);
            return false;
        }
        if (reflection) {
            record(relative(double(s.eta), 1.0), "eta = 1 for a reflection", l, v);
        } else {
            const double eta_v_side = n_dot_v > 0 ? double(s.eta) : 1 / double(s.eta);
            if (eta_inside == 0) eta_inside = eta_v_side;
            record(relative(eta_v_side, eta_inside),
                   options.eta_inside != 0 ? "eta = eta_inside (v outside) or 1 / eta_inside (v inside)"
                                           : "the same eta_inside for every transmission",
                   l, v);
        }
        if (!(s.pdf > T(0)) || !std::isfinite(s.pdf)) {
            record(infinite, "pdf finite and > 0", l, v);
            return false;
        }
        const bool specular = is_specular(s.flags);
        const double abs_n_dot_l = std::abs(n_dot_l);
        if (specular) {
            if (!(s.pdf <= T(1))) record(infinite, "a specular sample's pdf (a probability) <= 1", l, v);
            // The delta direction: the mirror image of v, or its refraction with the
            // sample's eta (shade::refract, Snell's law).
            const glm::dvec3 vd(v);
            const glm::dvec3 n_v = n_dot_v > 0 ? glm::dvec3(n) : -glm::dvec3(n);
            glm::dvec3 expected = 2 * glm::dot(n_v, vd) * n_v - vd;
            if (!reflection) {
                const auto t = refract(vd, n_v, double(s.eta));
                expected = t ? *t : glm::dvec3(std::numeric_limits<double>::quiet_NaN());
            }
            record(glm::length(glm::dvec3(l) - expected),
                   reflection ? "a specular reflection's l = 2 (n.v) n - v" : "a specular transmission's l = refract(v, n, eta)",
                   l, v);
        } else {
            record(relative(double(s.pdf), double(model.pdf(l, v, at))), "pdf = pdf(l, v)", l, v);
            const rgb<T> f = mode == transport_mode::radiance ? model.f(l, v, at) : model.f(v, l, at);
            for (int c = 0; c < 3; ++c)
                record(relative(double(s.f[c]), double(f[c])),
                       mode == transport_mode::radiance ? "f = f(l, v)" : "f = f(v, l) in importance mode", l, v);
        }
        // A delta lobe's f is its throughput / max(|n.l|, epsilon) (shade/bsdf/bsdf.hpp).
        const double cosine = specular ? std::max(abs_n_dot_l, double(std::numeric_limits<T>::epsilon())) : abs_n_dot_l;
        for (int c = 0; c < 3; ++c) {
            if (!(s.f[c] >= T(0)) || !std::isfinite(s.f[c]) || !(s.weight[c] >= T(0)) || !std::isfinite(s.weight[c]))
                record(infinite, "f and weight finite and >= 0", l, v);
            record(relative(double(s.weight[c]), double(s.f[c]) * cosine / double(s.pdf)), "weight = f |n.l| / pdf",
                   l, v);
        }
        return true;
    };
    rng random(options.seed ^ 0x5851f42d4c957f2dULL);
    for (const auto& pair : hemisphere_pairs(at, options.views, options.seed)) {
        for (const vec3<T>& v : {pair.v, vec3<T>(glm::normalize(pair.v - T(2) * glm::dot(n, pair.v) * n))}) {
            for (std::size_t i = 0; i < options.samples_per_view; ++i) {
                const T uc = random.uniform<T>();
                const vec2<T> u(random.uniform<T>(), random.uniform<T>());
                const auto radiance = model.sample(v, uc, u, at, transport_mode::radiance);
                const auto importance = model.sample(v, uc, u, at, transport_mode::importance);
                ++r.tried;
                if (!radiance || !importance) {
                    if (radiance || importance)
                        record(infinite, "nullopt in both transport modes or in neither",
                               radiance ? radiance->l : importance->l, v);
                    continue;
                }
                const bool fit = check(*radiance, v, transport_mode::radiance);
                if (!check(*importance, v, transport_mode::importance) || !fit) continue;
                // The mode changes the weight, never the choice (shade/bsdf/bsdf.hpp).
                const vec3<T> l = radiance->l;
                if (importance->flags != radiance->flags || importance->eta != radiance->eta ||
                    glm::length(glm::dvec3(importance->l) - glm::dvec3(l)) > r.tolerance) {
                    record(infinite, "the same l, flags and eta in both transport modes", l, v);
                    continue;
                }
                record(relative(double(importance->pdf), double(radiance->pdf)), "the same pdf in both transport modes",
                       l, v);
                if (!is_specular(radiance->flags)) continue;
                // A delta lobe: its throughput carries (eta_v / eta_l)^2 = 1 / eta^2 in
                // radiance mode only, and in importance mode it is a fraction of energy.
                const double eta2 = double(radiance->eta) * double(radiance->eta);
                for (int c = 0; c < 3; ++c) {
                    const double carried = double(importance->weight[c]) * double(importance->pdf);
                    record(carried <= 1 + r.tolerance ? 0 : carried - 1,
                           "a specular sample's importance-mode throughput weight pdf <= 1", l, v);
                    record(relative(double(radiance->weight[c]) * eta2, double(importance->weight[c])),
                           "a specular sample's radiance weight = importance weight / eta^2", l, v);
                }
            }
        }
    }
    r.decide(r.failures == 0 ? verdict::pass : verdict::fail);
    const std::string eta_text =
        eta_inside == 0 ? "no transmission drawn" : "eta_inside " + detail::number(eta_inside);
    if (r.passed) {
        r.message = "sample consistency holds for " + r.model + ": " + std::to_string(r.tried) +
                    " draws from both sides in both transport modes agree with f, pdf, their flags and eta (" +
                    eta_text + "), weight = f |n.l| / pdf, within " + detail::number(r.tolerance) + " (worst " +
                    detail::number(r.worst, 3) + ").";
    } else {
        r.message = "sample consistency FAILS for " + r.model + ": " + std::to_string(r.failures) + " checks of " +
                    std::to_string(r.tried) + " draws failed, the worst the rule '" + tally.worst_what + "' (" + eta_text +
                    "); worst relative error " + detail::number(r.worst, 3) + " for " + detail::where(r.l, r.v, at) +
                    ". A bsdf_sample must hold what f and pdf return at its direction, or for a delta lobe its "
                    "direction and throughput, with the flags and eta of the side l is on.";
    }
    return r;
}

} // namespace detail

/// Checks, for options.views views (world space, above the surface) times
/// options.samples_per_view draws, that every brdf_sample sample() returns is what the
/// contract says: l is a unit direction above the surface, pdf is finite and > 0 and equals
/// model.pdf(l, v), f equals model.f(l, v), and weight equals f |n·l| / pdf (each
/// relative to the larger magnitude, within options.relative_tolerance); and that for views
/// below the surface sample() returns nullopt. result::worst is the largest relative
/// discrepancy found (+inf for a broken rule that has no size), and l, v the draw.
///
/// For a BSDF with its own sampler (shade::bsdf_sampler, shade/bsdf/bsdf.hpp) each view is
/// also mirrored to the inside, and each draw is made in both transport modes with the
/// same (uc, u). Every sample must have a unit l; flags with exactly one of reflection and
/// transmission and one of diffuse, glossy and specular; l on v's side for a reflection
/// and on the other for a transmission; eta 1 for a reflection, and for a transmission
/// options.eta_inside seen from outside and 1 / options.eta_inside from inside (when
/// options.eta_inside is 0, the value of the first transmission, the same for all); pdf
/// finite and > 0; f and weight finite and >= 0 with weight = f |n·l| / pdf. A sample with
/// a density (not specular) must hold pdf(l, v) and f(l, v) (radiance mode) or the adjoint
/// f(v, l) (importance mode). A delta-lobe sample (specular) is checked through what it
/// carries: its pdf is a probability (<= 1), its l is the mirror image of v or the
/// refraction of v with its eta (shade::refract), |n·l| is floored at machine epsilon in
/// weight = f |n·l| / pdf, its importance-mode throughput weight·pdf is at most 1, and its
/// radiance-mode weight is the importance-mode one divided by eta^2. The two modes must
/// draw the same l with the same flags, eta and pdf (or both nullopt).
template <sampled_bsdf B>
result<scalar_of<B>> sample_consistency(const B& model, const surface_point<scalar_of<B>>& at,
                                        const sample_options& options = {}) {
    return detail::run_sample_consistency(detail::model_ref<scalar_of<B>>(model), at, options);
}

namespace detail {

/// The body of pdf_coverage (see there), on the type-erased model.
template <std::floating_point T>
result<T> run_pdf_coverage(const model_ref<T>& model, const surface_point<T>& at, const pair_options& options) {
    result<T> r;
    r.property = "pdf coverage";
    r.model = options.model;
    r.at = at;
    const vec3<T> n = at.n();
    const auto pairs = model.two_sided() ? sphere_pairs(at, options.pairs, options.seed)
                                         : hemisphere_pairs(at, options.pairs, options.seed);
    for (const auto& [l, v] : pairs) {
        const rgb<T> f = model.f(l, v, at);
        ++r.tried;
        const double top = double(std::max(f.x, std::max(f.y, f.z)));
        if (!(top > 0) || model.pdf(l, v, at) > T(0)) continue;
        ++r.failures;
        const double missed = top * std::abs(double(glm::dot(n, l)));
        if (r.failures == 1 || missed > r.worst) {
            r.worst = missed;
            r.l = l;
            r.v = v;
            r.value = f;
        }
    }
    r.decide(r.failures == 0 ? verdict::pass : verdict::fail);
    if (r.passed) {
        r.message = "pdf coverage holds for " + r.model + ": pdf > 0 wherever f > 0 over " +
                    std::to_string(r.tried) + " direction pairs.";
    } else {
        r.message = "pdf coverage FAILS for " + r.model + ": " + std::to_string(r.failures) + " of " +
                    std::to_string(r.tried) + " pairs have f > 0 but pdf = 0, e.g. f = " +
                    shade::detail::to_text(r.value) + " for " + detail::where(r.l, r.v, at) +
                    ". The sampler never draws directions where the BRDF reflects light.";
    }
    return r;
}

} // namespace detail

/// Checks that pdf covers f: for options.pairs direction pairs (hemisphere_pairs; for a
/// BSDF with its own sampler, shade::bsdf_sampler, sphere_pairs over both sides), wherever
/// some channel of f(l, v) is > 0, pdf(l, v) > 0. A sampler that never draws where f
/// reflects light makes every estimator built on it biased low, which no chi-square test
/// of sample against pdf can see. result::worst is the largest f(l, v) |n·l| (any channel)
/// found where pdf(l, v) = 0, and l, v that pair.
template <sampled_bsdf B>
result<scalar_of<B>> pdf_coverage(const B& model, const surface_point<scalar_of<B>>& at,
                                  const pair_options& options = {}) {
    return detail::run_pdf_coverage(detail::model_ref<scalar_of<B>>(model), at, options);
}

} // namespace shade::check
