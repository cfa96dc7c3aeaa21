// dielectric_albedo_tables: computes the albedo tables of the rough dielectric
// (shade/bsdf/dielectric_albedo_table.hpp) with the model's own importance sampling and
// writes them as a header of constants.
//
//   dielectric_albedo_tables --out include/shade/bsdf/detail/dielectric_albedo_data.hpp
//   dielectric_albedo_tables --beckmann --strata 256 --out include/shade/bsdf/detail/beckmann_dielectric_albedo_data.hpp
//
// Each node's E(mu, alpha, eta_s) is the importance-mode weight (R + T) of
// shade::rough_dielectric's sample() averaged over strata^2 jittered u, the lobe choice uc
// integrated out exactly (the reflection weighted by F, the refraction by 1 - F, at the
// visible normal drawn from u), v outside a model of index eta_s (eta_hat for the entering
// table, 1 / eta_hat for the exiting one), with its standard error, clamped to 1 (an
// estimate above 1 is noise: the model loses energy, never creates it). Besides the nodes,
// the program evaluates E the same way at the centre of every cell of the grid (halfway in
// the view coordinate, sqrt(alpha) and log(eta_hat - 1)) and compares the interpolated
// table there: the largest difference, and the largest standard error, are written into
// the header as the table's stated accuracy, with the largest difference over the cells
// whose centre has mu >= 0.05
// (the views the compensation promises R + T for).
//
//   dielectric_albedo_tables --beckmann --strata 256 --envelope 64 --envelope-margin 0.0003 --envelope-view-steps 4 --out include/shade/bsdf/detail/beckmann_dielectric_albedo_data.hpp
//
// stores an upper envelope of E instead of point values (raise_to_envelope): the
// compensation's R + T is 1 + E_true - E_table, so a table that errs high by design keeps
// R + T from exceeding 1 where interpolation would err low.
//
//   dielectric_albedo_tables --beyond --strata 256 --out include/shade/bsdf/detail/dielectric_albedo_beyond_data.hpp
//   dielectric_albedo_tables --beyond --beckmann --strata 256 --out include/shade/bsdf/detail/beckmann_dielectric_albedo_beyond_data.hpp
//
// write the continuations of the two total-albedo tables above eta_hat 3 (point values on
// detail::dielectric_albedo_beyond_grid and dielectric_beckmann_albedo_beyond_grid: eta_hat
// 3 to 1000), the same estimates on another eta axis.
//
//   dielectric_albedo_tables --reflection --out include/shade/bsdf/detail/dielectric_reflection_albedo_data.hpp
//
// writes instead the reflection table of shade/bsdf/dielectric_reflection_albedo.hpp on its
// own grid (detail::dielectric_reflection_albedo_grid: eta_hat from 1.001): each node the
// reflected part R_ss alone (the reflection weighted by F, the refraction dropped),
// stored as R_ss - F(mu, eta_s), F the exact Fresnel reflectance at the view (the node's
// mu); the cell centres compare F + the interpolated difference with a fresh R_ss.
//
//   dielectric_albedo_tables --anisotropic --envelope 40 --envelope-margin 0.0005 --envelope-below-z 0.5 --envelope-rough-above 1.1 --lift 0.0025,0.0045 --out include/shade/bsdf/detail/dielectric_anisotropic_albedo_data.hpp
//
// writes instead the anisotropic corrections of
// shade/bsdf/dielectric_anisotropic_albedo_table.hpp (anisotropy alpha_min / alpha_max down to
// 0, alpha_max up to sqrt 2): at each node, Delta = E(w) - E_iso(mu, alpha_base, eta_s), E(w)
// estimated as above for the anisotropic interface and the view w at the node's azimuth,
// E_iso read from the committed isotropic table at the base roughness
// (dielectric_anisotropic_base_alpha), plus --lift; with --envelope, raised as an upper envelope of E (compute_anisotropic, as
// compute_reflection's) at the check points with z below --envelope-below-z or alpha_rms
// above --envelope-rough-above; each
// row's cosine average; and, as the stated accuracy, the largest node standard error and the
// range of the table minus a fresh estimate at random points of the domain with mu >= 0.1.
// With --views FILE it also prints R + T = 1 + E_true - E_read of the compensated interface at
// fixed views (report_views; the sweep's pairs among them), E_true kept in FILE: with --cache, a
// variant of the table is measured in seconds.
//
//   dielectric_albedo_tables --anisotropic --reflection --envelope 48 --envelope-margin 0.0002 --envelope-random 300000 --envelope-sigma 2 --out include/shade/bsdf/detail/dielectric_anisotropic_reflection_albedo_data.hpp
//
// writes instead the correction of the anisotropic shade::dielectric_reflection_albedo on its
// own grid (shade/bsdf/dielectric_anisotropic_reflection_table.hpp: anisotropy
// alpha_min / alpha_max down to 0, the exiting side's critical cosine and total-reflection
// kink on nodes): at each node Delta_R = R_ss(w) - R_ss,iso(mu, alpha_b, eta_s), R_ss(w) the
// reflected part alone (estimated as for --reflection) and R_ss,iso the committed reflection
// table at detail::reflection_base_alpha for the node's azimuth; with --envelope, an upper
// envelope of R_ss (compute_reflection); the stated accuracy per side.

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <thread>
#include <utility>
#include <vector>

#include <shade/brdf/microfacet/beckmann.hpp>
#include <shade/brdf/microfacet/ggx.hpp>
#include <shade/bsdf/detail/dielectric_albedo_data.hpp>
#include <shade/bsdf/dielectric_albedo_table.hpp>
#include <shade/bsdf/dielectric_anisotropic_albedo_table.hpp>
#include <shade/bsdf/dielectric_anisotropic_reflection_albedo.hpp>
#include <shade/bsdf/dielectric_anisotropic_reflection_table.hpp>
#include <shade/bsdf/dielectric_reflection_albedo.hpp>
#include <shade/bsdf/rough_dielectric.hpp>
#include <shade/check/energy.hpp>
#include <shade/core/random.hpp>

#include "support/cli.hpp"
#include "support/float_literals.hpp"
#include "support/progress.hpp"

namespace ex = shade::examples;
namespace d = shade::detail;

namespace {

using T = double;

constexpr std::string_view usage =
    R"(usage: dielectric_albedo_tables [--beckmann | --reflection] [--beyond] [--out FILE.hpp] [--mu-nodes N] [--alpha-nodes N]
                                [--eta-nodes N] [--strata S] [--envelope S] [--threads K] [--quiet]
       dielectric_albedo_tables --anisotropic [--reflection] [--envelope S] [--out FILE.hpp] [--strata S]
                                [--points N] [--verbose] [--threads K] [--quiet]

Computes E(mu, alpha, eta_s) = R + T (importance mode) of
shade::rough_dielectric over GGX, for light entering (eta_s in
[1.05, 3]) and leaving (eta_s in [1/3, 1/1.05]) the denser medium, on the grid of
dielectric_albedo_table.hpp, each node from S^2 samples of the model's own sampler, and
writes the header of constants.

  --out FILE.hpp    output, a C++ header (.hpp or .h; default dielectric_albedo_data.hpp)
  --mu-nodes N      nodes along the view coordinate, 4 to 128 (default 25)
  --alpha-nodes N   nodes along sqrt(alpha), 4 to 128 (default 16)
  --eta-nodes N     nodes along log(eta - 1), 2 to 64 (default 12)
  --strata S        S^2 samples per node, 16 to 2048 (default 384; 128 with --anisotropic)
  --beckmann        the table of shade::rough_dielectric over Beckmann (m read as alpha)
                    instead of GGX (default output beckmann_dielectric_albedo_data.hpp)
  --beyond          the continuation of the total-albedo table (GGX, or Beckmann with
                    --beckmann) above eta_hat 3, on dielectric_albedo_beyond_grid (eta_hat 3
                    to 1000; default output dielectric_albedo_beyond_data.hpp, or
                    beckmann_dielectric_albedo_beyond_data.hpp)
  --reflection      the reflected part R alone of GGX, stored as R - F(mu, eta_s), on the
                    reflection grid (eta_hat from 1.001, 20 eta nodes by default, a spline
                    along eta; default output dielectric_reflection_albedo_data.hpp)
  --anisotropic     write instead the corrections Delta = E(w) - E_iso(mu, alpha_base, eta_s)
                    of anisotropic GGX interfaces on the fixed grid of
                    dielectric_anisotropic_albedo_table.hpp, and their row averages (default
                    output dielectric_anisotropic_albedo_data.hpp; the node options do not apply);
                    with --reflection, the corrections Delta_R = R(w) - R_iso(mu, alpha_b,
                    eta_s) of the reflected part on the grid of
                    dielectric_anisotropic_reflection_table.hpp, alpha_b the projected (entering)
                    or root-mean-square (exiting) roughness (default output
                    dielectric_anisotropic_reflection_albedo_data.hpp)
  --points N        with --anisotropic: random points the table is checked at (default 4000)
  --verbose         with --anisotropic: print each check point
  --envelope S      store an upper envelope of E instead of point values: after the nodes,
                    E is estimated (S^2 samples) at the middle of every cell edge, face and
                    interior with mu >= 0.05, and the nodes of each cell whose interpolated
                    value falls below an estimate are raised by the shortfall, until none does;
                    with --anisotropic, of E (or R with --reflection) at cell centres and
                    edge middles
  --envelope-random N  with --anisotropic --reflection --envelope S: N random check points
                    besides the fixed ones, those with mu >= 0.05 kept (between the fixed ones the read can fall below the truth)
  --envelope-margin M  with --envelope (total-albedo tables, --anisotropic): raise until the table is at least
                    the estimate + M (M in [0, 0.01], default 0; never above 1) at every check
                    point, so that it errs high between the check points too
  --envelope-sigma K  with --anisotropic --reflection --envelope S: raise until the table is at
                    least the estimate + K of its standard errors (+ M) at every check point
                    (K in [0, 4], default 0), so that a check estimate's own noise does not
                    leave the table below the truth
  --envelope-view-steps S  with --envelope (total-albedo tables): check places per cell along
                    the view coordinate, 2 to 8 (default 2: the middle; 4 adds the quarters,
                    where E falls steeply)
  --envelope-below-z Z  with --anisotropic --envelope S: only the check points with
                    z = sqrt(alpha_min / alpha_max) < Z raise nodes (Z in (0, 1])
  --envelope-rough-above A  with --anisotropic --envelope S: the check points of interfaces
                    with alpha_rms > A raise nodes too (A in [0, 2])
  --lift L[,L2]     with --anisotropic: every estimated node raised by L (in [0, 0.01],
                    default 0; L2 on the exiting side, default L) before the envelope, so that
                    the table errs high
  --cache FILE      with --anisotropic: the node and check-point estimates are written to FILE,
                    or read from it if it exists (for the same --strata and --envelope), so that
                    --lift, --envelope-margin and --envelope-below-z can be tried without
                    estimating again
  --views FILE      with --anisotropic: after the table, print R + T = 1 + E_true - E_read per class
                    (the sweep's 2:1, 10:1 and anisotropy-1 pairs, others, 10:1 with z on a node)
                    and side at 34,080 fixed views, E_true estimated (128^2 samples) into FILE or
                    read from it if it exists
  --threads K       worker threads, 1 to 64 (default 2)
  --quiet           no progress bar
)";

struct settings {
    std::filesystem::path out = "dielectric_albedo_data.hpp";
    d::dielectric_albedo_grid grid{};
    std::size_t strata = 384;
    unsigned threads = 2;
    bool quiet = false;
    bool anisotropic = false;
    bool beckmann = false;
    bool reflection = false;
    bool beyond = false;        // the continuation above eta_hat 3 (--beyond)
    bool verbose = false;       // print every check point (--anisotropic)
    std::size_t points = 4000;  // random check points (--anisotropic)
    std::size_t envelope = 0; // S^2 samples per check point of the upper envelope (0: point values)
    double envelope_margin = 0; // the envelope's height above the check points' estimates
    std::size_t envelope_view_steps = 2; // check places per view cell (2: its middle)
    std::size_t envelope_random = 0; // random check points besides the fixed ones (--anisotropic --reflection)
    std::filesystem::path cache; // --anisotropic: node and check-point estimates kept here (read back if present)
    std::filesystem::path views; // --anisotropic: R + T reported at fixed views, their E estimates kept here
    double lift[2] = {0, 0}; // --anisotropic: added to every estimated node before the envelope, per side
    double envelope_below_z = 2; // --anisotropic: only check points with z below this raise nodes ...
    double envelope_rough_above = 2; // ... or with alpha_rms above this
    double envelope_sigma = 0; // the envelope's height above the check points' estimates in their standard errors (--anisotropic --reflection)
};

// E of a model of index eta_s at view cosine mu: the importance-mode weight of its sampler.
template <class Distribution>
shade::check::albedo_sample<T> estimate(double mu, double alpha, double eta_s, std::size_t strata, std::uint64_t seed) {
    const shade::rough_dielectric<Distribution> model{Distribution(alpha), eta_s};
    shade::surface_point<T> at;
    at.shading = shade::frame<T>::from_normal_tangent({0, 0, 1}, {1, 0, 0});
    const double c = std::min(std::max(mu, d::albedo_grid_mu_min), 1.0);
    const shade::vec3<T> v(std::sqrt((1 - c) * (1 + c)), 0, c);
    // The lobe choice uc is integrated out exactly: for each u, the reflection (uc = 0 < F)
    // and the refraction (uc just below 1, drawn unless F = 1) weighted by the F and 1 - F
    // with which sample() chooses them at the visible normal m it draws from u. m is read
    // off the drawn reflection as the half vector normalize(v + l) (the same m up to
    // rounding; F > 0 at every m, so the reflection is always drawn), and drawn again only
    // where that reflection is lost below the surface: the visible normal, the costly part of
    // a Beckmann sample, is then drawn about once per u instead of three times.
    return shade::check::detail::stratified_estimate<T>(v, strata, seed, true, [&](const shade::vec2<T>& u, shade::rng&) {
        const auto r = model.sample(v, 0, u, at, shade::transport_mode::importance);
        const shade::vec3<T> m = r ? glm::normalize(v + r->l) : model.distribution().sample_visible_normal(v, u);
        const double F = shade::F_dielectric(glm::dot(v, m), eta_s);
        const double reflected = r ? F * r->weight.x : 0.0;
        double refracted = 0;
        if (F < 1) {
            const auto t = model.sample(v, std::nextafter(1.0, 0.0), u, at, shade::transport_mode::importance);
            refracted = t ? (1 - F) * t->weight.x : 0.0;
        }
        return glm::dvec3(reflected + refracted);
    });
}

// R_ss of a GGX model of index eta_s at view cosine mu: the importance-mode weight of its
// sampler's reflections, each weighted by the F with which sample() chooses it at the
// visible normal drawn from u (the refraction dropped).
shade::check::albedo_sample<T> estimate_reflection(double mu, double alpha, double eta_s, std::size_t strata,
                                                   std::uint64_t seed) {
    const shade::rough_dielectric<shade::ggx<T>> model{shade::ggx<T>(alpha), eta_s};
    shade::surface_point<T> at;
    at.shading = shade::frame<T>::from_normal_tangent({0, 0, 1}, {1, 0, 0});
    const double c = std::min(std::max(mu, d::albedo_grid_mu_min), 1.0);
    const shade::vec3<T> v(std::sqrt((1 - c) * (1 + c)), 0, c);
    return shade::check::detail::stratified_estimate<T>(v, strata, seed, true, [&](const shade::vec2<T>& u, shade::rng&) {
        const shade::vec3<T> m = model.distribution().sample_visible_normal(v, u);
        const double F = shade::F_dielectric(glm::dot(v, m), eta_s);
        if (!(F > 0)) return glm::dvec3(0);
        const auto s = model.sample(v, 0, u, at, shade::transport_mode::importance);
        return glm::dvec3(s ? F * s->weight.x : 0.0);
    });
}

// The part of a node's value that is not tabulated: F(mu, eta_s) at the estimate's view
// cosine for the reflection table (which stores R_ss - F), 0 for the total albedo.
double baseline(const settings& s, double mu, double eta_s) {
    return s.reflection ? shade::F_dielectric(std::min(std::max(mu, d::albedo_grid_mu_min), 1.0), eta_s) : 0.0;
}

// E of an interface of roughnesses (alpha_x, alpha_y) and index eta_s for the unit local view
// v (v.z > 0), estimated as estimate() does.
shade::check::albedo_sample<T> estimate_view(double alpha_x, double alpha_y, double eta_s, const shade::vec3<T>& v,
                                             std::size_t strata, std::uint64_t seed) {
    const shade::rough_dielectric<shade::ggx<T>> model{shade::ggx<T>(alpha_x, alpha_y), eta_s};
    shade::surface_point<T> at;
    at.shading = shade::frame<T>::from_normal_tangent({0, 0, 1}, {1, 0, 0});
    const auto weight = [&](const shade::vec2<T>& u, T uc) {
        const auto s = model.sample(v, uc, u, at, shade::transport_mode::importance);
        return s ? s->weight.x : 0.0;
    };
    return shade::check::detail::stratified_estimate<T>(v, strata, seed, true, [&](const shade::vec2<T>& u, shade::rng&) {
        const shade::vec3<T> m = model.distribution().sample_visible_normal(v, u);
        const double F = shade::F_dielectric(glm::dot(v, m), eta_s);
        const double reflected = F > 0 ? F * weight(u, 0) : 0.0;
        const double refracted = F < 1 ? (1 - F) * weight(u, std::nextafter(1.0, 0.0)) : 0.0;
        return glm::dvec3(reflected + refracted);
    });
}

// R_ss of an interface of roughnesses (alpha_x, alpha_y) and index eta_s for the unit local
// view v (v.z > 0), estimated as estimate_reflection() does.
shade::check::albedo_sample<T> estimate_view_reflection(double alpha_x, double alpha_y, double eta_s,
                                                        const shade::vec3<T>& v, std::size_t strata,
                                                        std::uint64_t seed) {
    const shade::rough_dielectric<shade::ggx<T>> model{shade::ggx<T>(alpha_x, alpha_y), eta_s};
    shade::surface_point<T> at;
    at.shading = shade::frame<T>::from_normal_tangent({0, 0, 1}, {1, 0, 0});
    return shade::check::detail::stratified_estimate<T>(v, strata, seed, true, [&](const shade::vec2<T>& u, shade::rng&) {
        const shade::vec3<T> m = model.distribution().sample_visible_normal(v, u);
        const double F = shade::F_dielectric(glm::dot(v, m), eta_s);
        if (!(F > 0)) return glm::dvec3(0);
        const auto s = model.sample(v, 0, u, at, shade::transport_mode::importance);
        return glm::dvec3(s ? F * s->weight.x : 0.0);
    });
}

using estimator = std::function<shade::check::albedo_sample<T>(double, double, double, std::size_t, std::uint64_t)>;

struct table {
    std::string name;            // C++ name prefix
    std::string what;            // one line for the comment
    std::vector<float> e;        // grid.size()
    double max_error = 0;        // largest standard error of a node
    double max_interpolation = 0; // largest |interpolated - estimated| at the cell centres
    double max_domain = 0;       // the same over the cell centres with mu >= 0.05
    double max_side[2] = {0, 0}; // max_domain of each side (0 entering, 1 exiting)
    std::string worst;           // where the largest difference is (for the log)
    double lowest = 0;           // smallest table - estimate at the cell centres with mu >= 0.05
    double highest = 0;          // largest
    std::size_t checks = 0;      // check points of the upper envelope (0: point values)
    double max_raise = 0;        // largest raise of a node by the envelope
    std::size_t raised = 0;      // nodes raised
    int passes = 0;              // raising passes until no check point was above the table
};

void parallel_for(std::size_t count, unsigned threads, const std::function<void(std::size_t)>& job) {
    std::atomic<std::size_t> next{0};
    std::vector<std::thread> pool;
    for (unsigned t = 0; t < threads; ++t)
        pool.emplace_back([&] {
            for (std::size_t k = next++; k < count; k = next++) job(k);
        });
    for (auto& th : pool) th.join();
}

// The eta_s of side `side` (0 entering, 1 exiting) at eta_hat.
double eta_of_side(std::size_t side, double eta_hat) { return side == 0 ? eta_hat : 1 / eta_hat; }

// A check point of the upper envelope: a side and its place along each axis (along alpha
// and eta 2 i + 1 a cell's middle, 2 i a node; along the view coordinate in steps of 1 / S
// of a cell, S = --envelope-view-steps), not every coordinate a node.
struct check_point {
    std::size_t side, mu2, alpha2, eta2;
    double mu, alpha, eta_s;
};

// Every check point of grid g with mu >= 0.05: the middles of the cells' edges, faces and
// interiors, and along the view coordinate every 1 / steps of a cell (each axis at a node or
// between two, in the table's own coordinates:
// the view coordinate, sqrt(alpha), log(eta_hat - 1)), where interpolation errs most.
std::vector<check_point> envelope_points(const d::dielectric_albedo_grid& g, std::size_t steps) {
    std::vector<check_point> points;
    for (std::size_t side = 0; side < 2; ++side)
        for (std::size_t e2 = 0; e2 + 1 < 2 * g.eta_nodes; ++e2)
            for (std::size_t a2 = 0; a2 + 1 < 2 * g.alpha_nodes; ++a2)
                for (std::size_t m2 = 0; m2 + 1 < steps * (g.mu_nodes - 1) + 1; ++m2) {
                    if (e2 % 2 == 0 && a2 % 2 == 0 && m2 % steps == 0) continue;
                    const double y = 0.5 * double(a2) / double(g.alpha_nodes - 1);
                    const double alpha = std::max(y * y, d::albedo_grid_alpha_min);
                    const double eta_hat =
                        e2 % 2 == 0 ? d::dielectric_albedo_eta(g, e2 / 2)
                                    : 1 + std::sqrt((d::dielectric_albedo_eta(g, e2 / 2) - 1) *
                                                    (d::dielectric_albedo_eta(g, e2 / 2 + 1) - 1));
                    const double mu = d::dielectric_albedo_view_mu(double(m2) / double(steps * (g.mu_nodes - 1)), alpha,
                                                                   eta_hat, side, g.near_critical);
                    if (mu < 0.05) continue;
                    points.push_back({side, m2, a2, e2, mu, alpha, eta_of_side(side, eta_hat)});
                }
    return points;
}

// Turns the point values of `out` into an upper envelope of E (the total albedo only): E is
// estimated afresh (s.envelope^2 samples) at every check point of envelope_points, and the
// nodes of each cell whose interpolated value falls below an estimate there are raised by
// the shortfall (at most to 1), pass after pass until no check point is above the table
// (a raised node also lifts its neighbours' cells, and the spline's outer weights are
// negative, so one pass is not always enough). The compensation's R + T is
// 1 + E_true - E_table, so a table that errs high keeps R + T below 1 + its residual error.
void raise_to_envelope(table& out, const estimator& albedo, const settings& s, ex::progress& bar) {
    const d::dielectric_albedo_grid& g = s.grid;
    const std::vector<check_point> points = envelope_points(g, s.envelope_view_steps);
    std::vector<double> estimate(points.size());
    parallel_for(points.size(), s.threads, [&](std::size_t p) {
        const check_point& c = points[p];
        estimate[p] = albedo(c.mu, c.alpha, c.eta_s, s.envelope, 2000003 + p).albedo.x;
        bar.advance();
    });
    const std::vector<float> start = out.e;
    std::vector<double> raise(g.size());
    for (int pass = 1; pass <= 200; ++pass) {
        std::fill(raise.begin(), raise.end(), 0.0);
        bool any = false;
        for (std::size_t p = 0; p < points.size(); ++p) {
            const check_point& c = points[p];
            const auto cell = d::dielectric_albedo_locate(g, c.alpha, c.eta_s);
            // The target stops at 1, which nodes cannot pass (E <= 1).
            const double target = std::min(estimate[p] + s.envelope_margin, 1.0);
            const double shortfall = target - d::dielectric_albedo_interpolate(out.e.data(), g, cell, c.mu);
            // Below 1e-6 the shortfall is the float rounding of the raised nodes.
            if (!(shortfall > 1e-6)) continue;
            any = true;
            const auto c_mu = d::albedo_grid_locate(
                d::dielectric_albedo_view(c.mu, double(cell.alpha_clamped), double(cell.eta_clamped), cell.side,
                                          g.near_critical),
                g.mu_nodes);
            for (std::size_t k = cell.eta.i; k <= cell.eta.i + 1; ++k)
                for (std::size_t j = cell.alpha.i; j <= cell.alpha.i + 1; ++j)
                    for (std::size_t i = c_mu.i; i <= c_mu.i + 1; ++i) {
                        double& r = raise[g.row(cell.side, k, j) + i];
                        r = std::max(r, shortfall);
                    }
        }
        out.passes = pass;
        if (!any) break;
        for (std::size_t n = 0; n < g.size(); ++n)
            if (raise[n] > 0) out.e[n] = float(std::min(double(out.e[n]) + raise[n], 1.0));
        // Nodes at 1 cannot rise: a check point whose cell is all at 1 stops the passes.
        bool stuck = true;
        for (std::size_t n = 0; n < g.size(); ++n)
            if (raise[n] > 0 && out.e[n] < 1.0f) stuck = false;
        if (stuck) break;
    }
    out.checks = points.size();
    for (std::size_t n = 0; n < g.size(); ++n) {
        const double r = double(out.e[n]) - double(start[n]);
        out.max_raise = std::max(out.max_raise, r);
        if (r > 0) ++out.raised;
    }
}

table compute(const std::string& name, const std::string& what, const estimator& albedo, const settings& s,
              ex::progress& bar) {
    const d::dielectric_albedo_grid& g = s.grid;
    table out{name, what, std::vector<float>(g.size()), 0, 0, 0, {0, 0}, {}};
    std::vector<double> errors(g.size());
    parallel_for(g.size(), s.threads, [&](std::size_t index) {
        const std::size_t i = index % g.mu_nodes;
        const std::size_t j = index / g.mu_nodes % g.alpha_nodes;
        const std::size_t k = index / (g.mu_nodes * g.alpha_nodes) % g.eta_nodes;
        const std::size_t side = index / (g.mu_nodes * g.alpha_nodes * g.eta_nodes);
        const double alpha = d::albedo_grid_alpha(j, g.alpha_nodes);
        const double eta_hat = d::dielectric_albedo_eta(g, k);
        const double mu =
            d::dielectric_albedo_view_mu(double(i) / double(g.mu_nodes - 1), alpha, eta_hat, side, g.near_critical);
        const double eta_s = eta_of_side(side, eta_hat);
        const auto a = albedo(mu, alpha, eta_s, s.strata, 1 + index);
        out.e[index] = float(std::min(a.albedo.x, 1.0) - baseline(s, mu, eta_s));
        errors[index] = a.standard_error.x;
        bar.advance();
    });
    out.max_error = *std::max_element(errors.begin(), errors.end());
    if (s.envelope > 0) raise_to_envelope(out, albedo, s, bar);
    // With an envelope the centres are compared at the check points' sample count.
    const std::size_t centre_strata = s.envelope > 0 ? s.envelope : s.strata;
    // Every cell centre, estimated afresh and compared with the interpolated table.
    const std::size_t cells = 2 * (g.eta_nodes - 1) * (g.alpha_nodes - 1) * (g.mu_nodes - 1);
    std::vector<double> differences(cells);
    std::vector<double> signed_differences(cells);
    std::vector<char> in_domain(cells);
    std::vector<std::string> where(cells);
    parallel_for(cells, s.threads, [&](std::size_t index) {
        const std::size_t i = index % (g.mu_nodes - 1);
        const std::size_t j = index / (g.mu_nodes - 1) % (g.alpha_nodes - 1);
        const std::size_t k = index / ((g.mu_nodes - 1) * (g.alpha_nodes - 1)) % (g.eta_nodes - 1);
        const std::size_t side = index / ((g.mu_nodes - 1) * (g.alpha_nodes - 1) * (g.eta_nodes - 1));
        const double y = (double(j) + 0.5) / double(g.alpha_nodes - 1);
        const double alpha = std::max(y * y, d::albedo_grid_alpha_min);
        const double eta_hat = 1 + std::sqrt((d::dielectric_albedo_eta(g, k) - 1) * (d::dielectric_albedo_eta(g, k + 1) - 1));
        const double mu = d::dielectric_albedo_view_mu((double(i) + 0.5) / double(g.mu_nodes - 1), alpha, eta_hat, side,
                                                       g.near_critical);
        const double eta_s = eta_of_side(side, eta_hat);
        const auto a = albedo(mu, alpha, eta_s, centre_strata, 1000003 + index);
        const auto cell = d::dielectric_albedo_locate(g, alpha, eta_s);
        const double table_value =
            std::min(std::max(d::dielectric_albedo_interpolate(out.e.data(), g, cell, mu) + baseline(s, mu, eta_s), 0.0), 1.0);
        differences[index] = std::abs(table_value - a.albedo.x);
        signed_differences[index] = table_value - a.albedo.x;
        in_domain[index] = mu >= 0.05;
        where[index] = "side " + std::to_string(side) + ", mu " + std::to_string(mu) + ", alpha " + std::to_string(alpha) +
                       ", eta_hat " + std::to_string(eta_hat) + ": estimate " + std::to_string(a.albedo.x) + ", table " +
                       std::to_string(table_value);
        bar.advance();
    });
    const auto worst = std::max_element(differences.begin(), differences.end());
    out.max_interpolation = *worst;
    out.worst = where[std::size_t(worst - differences.begin())];
    const std::size_t side_cells = cells / 2;
    for (std::size_t index = 0; index < cells; ++index)
        if (in_domain[index]) {
            out.max_domain = std::max(out.max_domain, differences[index]);
            double& side_max = out.max_side[index / side_cells];
            side_max = std::max(side_max, differences[index]);
            out.lowest = std::min(out.lowest, signed_differences[index]);
            out.highest = std::max(out.highest, signed_differences[index]);
        }
    return out;
}

// The envelope's options as given (" --envelope S --envelope-margin M"), or "".
std::string envelope_options(const settings& s) {
    if (s.envelope == 0) return "";
    std::string text = " --envelope " + std::to_string(s.envelope);
    if (s.envelope_margin > 0) {
        char margin[32];
        std::snprintf(margin, sizeof margin, "%g", s.envelope_margin);
        text += std::string(" --envelope-margin ") + margin;
    }
    if (s.envelope_view_steps != 2) text += " --envelope-view-steps " + std::to_string(s.envelope_view_steps);
    if (s.envelope_random > 0) text += " --envelope-random " + std::to_string(s.envelope_random);
    if (s.envelope_sigma > 0) {
        char sigma[32];
        std::snprintf(sigma, sizeof sigma, "%g", s.envelope_sigma);
        text += std::string(" --envelope-sigma ") + sigma;
    }
    return text;
}

void write(std::FILE* f, const std::vector<table>& tables, const settings& s) {
    const d::dielectric_albedo_grid& g = s.grid;
    std::fprintf(f, "#pragma once\n");
    std::fprintf(f,
                 "// Generated by examples/dielectric_albedo_tables.cpp (%s--mu-nodes %zu --alpha-nodes %zu --eta-nodes %zu "
                 "--strata %zu%s);\n// do not edit by hand.\n",
                 s.beyond ? (s.beckmann ? "--beyond --beckmann " : "--beyond ") : s.beckmann ? "--beckmann " : s.reflection ? "--reflection " : "",
                 g.mu_nodes, g.alpha_nodes, g.eta_nodes,
                 s.strata, envelope_options(s).c_str());
    if (s.reflection) {
        std::fprintf(f, "// The reflection table of shade/bsdf/dielectric_reflection_albedo.hpp (meaning) on the grid\n");
        std::fprintf(f, "// detail::dielectric_reflection_albedo_grid of shade/bsdf/dielectric_albedo_table.hpp (grid,\n");
        std::fprintf(f, "// interpolation): R_ss(mu, alpha, eta_s) - F_dielectric(mu, eta_s) at each node.\n");
    } else if (s.beyond) {
        std::fprintf(f, "// The continuation above eta_hat 3 of a total-albedo table of shade/bsdf/dielectric_albedo_table.hpp\n");
        std::fprintf(f, "// (meaning, interpolation) on the grid detail::%s (eta_hat 3 to 1000).\n",
                     s.beckmann ? "dielectric_beckmann_albedo_beyond_grid" : "dielectric_albedo_beyond_grid");
    } else
        std::fprintf(f, "// The albedo tables of shade/bsdf/dielectric_albedo_table.hpp (grid, interpolation, meaning):\n");
    const bool four_rows = (s.reflection && g.alpha_nodes % 4 == 0) || s.beyond;
    std::fprintf(f, "// 2 sides x %zu eta x %zu alpha x %zu mu nodes, one (side, eta) block of rows per line group%s;\n",
                 g.eta_nodes, g.alpha_nodes, g.mu_nodes, four_rows ? ", four rows a line" : "");
    std::fprintf(f, "// each node the mean importance-mode weight of %zu jittered samples of the model's own sampler%s.\n",
                 s.strata * s.strata, s.reflection ? " (reflections only)" : "");
    std::fprintf(f, "// Accuracy (measured by the generator, per table below): the largest standard error of a\n");
    std::fprintf(f, "// node; the largest difference between the interpolated table and a fresh estimate at the\n");
    std::fprintf(f, "// centre of every cell (interpolation plus both estimates' noise), and the same over the\n");
    std::fprintf(f, "// cells whose centre has mu >= 0.05%s.\n\n",
                 s.reflection ? " (the table read as F plus the interpolated difference)" : "");
    std::fprintf(f, "namespace shade::detail {\n");
    for (const auto& t : tables) {
        std::fprintf(f, "\n/// %s of %s.\n", s.reflection ? "R_ss(mu, alpha, eta_s) - F(mu, eta_s)" : "E(mu, alpha, eta_s)",
                     t.what.c_str());
        std::fprintf(f, "/// Node standard error <= %.1e; interpolated vs estimated at cell centres <= %.1e;\n", t.max_error,
                     t.max_interpolation);
        std::fprintf(f, "/// at the cell centres with mu >= 0.05 <= %.1e (entering side <= %.1e, exiting side <= %.1e).\n",
                     t.max_domain, t.max_side[0], t.max_side[1]);
        if (t.checks > 0) {
            std::fprintf(f, "/// An upper envelope, not point values: %zu nodes raised (by at most %.1e) so that the\n", t.raised,
                         t.max_raise);
            std::fprintf(f, "/// interpolated table is at least a fresh estimate (%zu samples each) + %g (never above 1)\n/// at %zu check points\n",
                         s.envelope * s.envelope, s.envelope_margin, t.checks);
            std::fprintf(f, "/// with mu >= 0.05, the middles of every cell's edges, faces and interior, and every 1/%zu of a\n",
                         s.envelope_view_steps);
            std::fprintf(f, "/// cell along the view coordinate (%d passes).\n", t.passes);
            std::fprintf(f, "/// Table minus a fresh estimate at the cell centres with mu >= 0.05: from %.1e to %.1e.\n",
                         t.lowest, t.highest);
        }
        std::fprintf(f, "inline constexpr float %s[%zu] = {\n", t.name.c_str(), g.size());
        // The reflection table and the continuations, four rows per line: their headers are
        // included by compensated_rough_dielectric.hpp, whose preprocessed lines are budgeted
        // (2 x 12 eta blocks make the continuations' row counts multiples of 4).
        const std::size_t rows_per_line = four_rows ? 4 : 1;
        for (std::size_t r = 0; r < g.size() / g.mu_nodes; r += rows_per_line) {
            for (std::size_t k = 0; k < rows_per_line; ++k) {
                if (k > 0) std::fprintf(f, ", ");
                ex::write_float_literals(f, t.e.data() + (r + k) * g.mu_nodes, g.mu_nodes);
            }
            std::fprintf(f, ",\n");
        }
        std::fprintf(f, "};\n");
    }
    std::fprintf(f, "\n} // namespace shade::detail\n");
}

// x rounded to the float the header will hold when written with `digits` significant digits.
float as_written(double x, int digits) {
    char text[32];
    std::snprintf(text, sizeof text, "%.*g", digits, double(float(x)));
    return std::strtof(text, nullptr);
}

// ---- The anisotropic reflection correction (--anisotropic --reflection), on its own grid
// (shade/bsdf/dielectric_anisotropic_reflection_table.hpp).

namespace rg {
constexpr std::size_t nx = d::reflection_anisotropic_mu_nodes, nu = d::reflection_anisotropic_azimuth_nodes;
constexpr std::size_t ny = d::reflection_anisotropic_roughness_nodes, ns = d::reflection_anisotropic_ratio_nodes;
constexpr std::size_t ne = d::reflection_anisotropic_eta_nodes;
} // namespace rg

// The interface of a (z, y, e, side) point of the grid: the smoother alpha along t, at
// least openpbr's smallest alpha 1e-4 (z = 0: OpenPBR's anisotropy 1); eta_s of the side;
// y is alpha_max's coordinate on side 0, alpha_rms's on side 1
// (d::reflection_anisotropic_alpha_max).
struct reflection_interface {
    double alpha_x, alpha_y, eta_s;
};
reflection_interface reflection_interface_at(double z_coord, double y_coord, double e_coord, std::size_t side) {
    // Both alphas at least 1e-4: a check point with y near 0 would otherwise have alpha_max
    // below the floored alpha_min (the smoother axis would be the rougher one).
    const double alpha_max = std::max(d::reflection_anisotropic_alpha_max(side, y_coord, z_coord), 1e-4);
    const double alpha_min = std::max(z_coord * z_coord * alpha_max, 1e-4);
    const double eta_hat = 1 + std::exp(d::dielectric_albedo_x_min + e_coord * (d::dielectric_albedo_x_max - d::dielectric_albedo_x_min));
    return {alpha_min, alpha_max, eta_of_side(side, eta_hat)};
}

// The unit local view (v.z > 0) at the grid coordinates x = sqrt(mu) and u of the interface
// `at` (the smoother axis t) on side `side`, and its azimuth phi (also at the pole, where v
// has none).
struct reflection_view {
    shade::vec3<T> v;
    double phi;
};
reflection_view reflection_view_at(double x_coord, double u_coord, const reflection_interface& at, std::size_t side) {
    const double inv_eta_hat = at.eta_s > 1 ? 1 / at.eta_s : at.eta_s;
    const double mu_c = std::sqrt((1 - inv_eta_hat) * (1 + inv_eta_hat));
    const double mu = std::min(std::max(d::reflection_anisotropic_mu(side, x_coord, mu_c), d::albedo_grid_mu_min), 1.0);
    const double sin_theta = std::sqrt((1 - mu) * (1 + mu));
    const double phi_k = side == 1 ? d::reflection_anisotropic_kink(sin_theta, inv_eta_hat) : 0.0;
    const double phi = d::reflection_anisotropic_phi(side, u_coord, phi_k, at.alpha_x / at.alpha_y);
    return {{sin_theta * std::cos(phi), sin_theta * std::sin(phi), mu}, phi};
}

// R_ss,iso at the roughness projected on the azimuth phi (from t): what Delta_R is measured
// from. At the pole too the node's own azimuth: a view near the pole reads its own.
double reflection_base(const reflection_interface& at, double mu, double phi) {
    const double c = std::cos(phi), sn = std::sin(phi);
    const double projected = std::sqrt(at.alpha_x * at.alpha_x * c * c + at.alpha_y * at.alpha_y * sn * sn);
    const double alpha = at.eta_s > 1 ? projected : d::reflection_base_alpha(at.alpha_x, at.alpha_y, at.eta_s, shade::vec3<T>(0, 0, 1));
    return shade::dielectric_reflection_albedo(shade::unchecked, std::min(mu, 1.0), alpha, at.eta_s);
}
double reflection_base(const reflection_interface& at, const shade::vec3<T>& v) {
    return shade::dielectric_reflection_albedo(shade::unchecked, std::min(v.z, 1.0),
                                               d::reflection_base_alpha(at.alpha_x, at.alpha_y, at.eta_s, v), at.eta_s);
}

// One tap of the reader: a stored value's index and its weight.
struct tap {
    std::size_t index;
    double weight;
};

// The taps with which reflection_anisotropic_delta reads the interface `at` at view v.
std::vector<tap> reflection_taps(const reflection_interface& at, const shade::vec3<T>& v) {
    const auto cell = d::reflection_anisotropic_locate(at.alpha_x, at.alpha_y, at.eta_s);
    const double phi = std::atan2(std::abs(v.y), std::abs(v.x));
    const double sin_theta = std::min(std::sqrt(v.x * v.x + v.y * v.y), 1.0);
    const double phi_k = cell.side == 1 ? d::reflection_anisotropic_kink(sin_theta, cell.inv_eta_hat) : 0.0;
    const auto u = d::albedo_grid_locate(d::reflection_anisotropic_u(cell.side, phi, phi_k, cell.ratio), rg::nu);
    const d::spline_taps<double> wx =
        d::reflection_anisotropic_x_taps(cell.side, d::reflection_anisotropic_x(cell.side, std::min(v.z, 1.0), cell.mu_c));
    std::vector<tap> out;
    for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b)
            for (int c = 0; c < 4; ++c) {
                const double w = cell.e.weight[a] * cell.s.weight[b] * cell.y.weight[c];
                if (w == 0 || cell.s.node[b] == rg::ns - 1 || cell.y.node[c] == 0) continue;
                for (std::size_t du = 0; du < 2; ++du) {
                    const double wu = du == 0 ? 1 - u.t : u.t;
                    if (wu == 0) continue;
                    const std::size_t row =
                        d::reflection_anisotropic_row_index(cell.side, cell.e.node[a], cell.s.node[b], cell.y.node[c], u.i + du);
                    for (int k = 0; k < 4; ++k)
                        if (wx.weight[k] != 0) out.push_back({row * rg::nx + wx.node[k], w * wu * wx.weight[k]});
                }
            }
    return out;
}

struct reflection_table {
    std::vector<float> delta;        // reflection_anisotropic_size values
    double max_error = 0;            // largest standard error of a node
    double max_delta = 0;            // largest |Delta_R|
    std::size_t checks = 0;          // envelope check points (0: point values)
    std::size_t raised = 0;          // nodes raised by the envelope
    double max_raise = 0;            // the largest raise
    int passes = 0;                  // raising passes
    double envelope_left = 0;        // the largest check estimate - table left after the passes and rounding
    std::size_t random_checks = 0;   // of the checks, random ones (--envelope-random, those with mu >= 0.05)
    double side_lowest[2] = {0, 0};  // table - fresh estimate at the random points, per side
    double side_highest[2] = {0, 0};
    std::size_t points = 0;
};

// The envelope's check points with mu >= 0.05: on every stored (side, e, z, y) slice, the
// middle of every (x, u) cell, of every x edge at the u nodes and of every u edge at the x
// nodes; the middle of every y, z and e edge at the other axes' nodes; and the centre of
// every cell of the whole grid. As grid coordinates (x, u, y, z, e, side).
struct reflection_check {
    double x, u, y, s, e;
    std::size_t side;
};
// Whether the check point's view has mu >= 0.05 (x is sqrt(mu) only entering: exiting, x =
// 1/2 is the critical cosine).
bool reflection_check_steep(const reflection_check& c) {
    const reflection_interface at = reflection_interface_at(c.s, c.y, c.e, c.side);
    return reflection_view_at(c.x, c.u, at, c.side).v.z >= 0.05;
}
std::vector<reflection_check> reflection_checks() {
    std::vector<reflection_check> out;
    const auto at = [](std::size_t i, std::size_t n) { return double(i) / double(n - 1); };
    const auto mid = [](std::size_t i, std::size_t n) { return (double(i) + 0.5) / double(n - 1); };
    for (std::size_t side = 0; side < 2; ++side)
        for (std::size_t m = 0; m < rg::ne; ++m)
            for (std::size_t k = 0; k + 1 < rg::ns; ++k)
                for (std::size_t j = 1; j < rg::ny; ++j)
                    for (std::size_t i_u = 0; i_u < rg::nu; ++i_u)
                        for (std::size_t i_x = 0; i_x < rg::nx; ++i_x) {
                            const double y = at(j, rg::ny), s = at(k, rg::ns), e = at(m, rg::ne);
                            if (i_x + 1 < rg::nx && i_u + 1 < rg::nu) out.push_back({mid(i_x, rg::nx), mid(i_u, rg::nu), y, s, e, side});
                            if (i_x + 1 < rg::nx) out.push_back({mid(i_x, rg::nx), at(i_u, rg::nu), y, s, e, side});
                            if (i_u + 1 < rg::nu) out.push_back({at(i_x, rg::nx), mid(i_u, rg::nu), y, s, e, side});
                            const double x = at(i_x, rg::nx), u = at(i_u, rg::nu);
                            if (j + 1 < rg::ny) out.push_back({x, u, mid(j, rg::ny), s, e, side});
                            if (k + 1 < rg::ns - 1) out.push_back({x, u, y, mid(k, rg::ns), e, side});
                            if (k + 2 == rg::ns) out.push_back({x, u, y, mid(k, rg::ns), e, side}); // toward z = 1
                            if (m + 1 < rg::ne) out.push_back({x, u, y, s, mid(m, rg::ne), side});
                        }
    for (std::size_t side = 0; side < 2; ++side)
        for (std::size_t m = 0; m + 1 < rg::ne; ++m)
            for (std::size_t k = 0; k + 1 < rg::ns; ++k)
                for (std::size_t j = 0; j + 1 < rg::ny; ++j)
                    for (std::size_t i_u = 0; i_u + 1 < rg::nu; ++i_u)
                        for (std::size_t i_x = 0; i_x + 1 < rg::nx; ++i_x)
                            out.push_back({mid(i_x, rg::nx), mid(i_u, rg::nu), mid(j, rg::ny), mid(k, rg::ns), mid(m, rg::ne), side});
    // Only views with mu >= 0.05: raising nodes for the grazing views would lower the
    // interpolation above them through Catmull-Rom's negative weights.
    std::erase_if(out, [](const reflection_check& c) { return !reflection_check_steep(c); });
    return out;
}

// Random check points (count of them, seeded apart from the random test points of
// compute_reflection): side, e, u and x uniform, those with mu >= 0.05 kept (as the fixed
// ones); y from half its first node above 0 (OpenPBR's roughness 0.1 is y = 0.1, 0.9 of
// that node, where the spline along y reads the second node with a negative weight) and z
// up to its last node below 1, uniform (nearer the unstored rows the read leans on them,
// and a check there would raise the few stored nodes it reads without bound), z = 0
// (anisotropy 1) for every fifth. They reach the places between the fixed check points, where
// Catmull-Rom's negative weights can still leave the read below the truth.
std::vector<reflection_check> reflection_random_checks(std::size_t count) {
    std::vector<reflection_check> out;
    out.reserve(count);
    for (std::size_t p = 0; p < count; ++p) {
        shade::rng random(0xc4ec0000 + p);
        const std::size_t side = p % 2;
        const double e = random.uniform<double>(), u = random.uniform<double>();
        const double x = random.uniform<double>();
        const double y_low = 0.5 / double(rg::ny - 1), z_last = double(rg::ns - 2) / double(rg::ns - 1);
        const double y = y_low + (1 - y_low) * random.uniform<double>();
        const double z = z_last * random.uniform<double>();
        const reflection_check c{x, u, y, p % 5 == 2 ? 0.0 : z, e, side};
        if (reflection_check_steep(c)) out.push_back(c);
    }
    return out;
}

// R_ss(v) of the interface as the table reads it (unclamped, the correction unscaled).
double reflection_read(const std::vector<float>& delta, const reflection_interface& at, const shade::vec3<T>& v) {
    const auto cell = d::reflection_anisotropic_locate(at.alpha_x, at.alpha_y, at.eta_s);
    return reflection_base(at, v) + d::reflection_anisotropic_delta(delta.data(), cell, v.x, v.y, v.z);
}

// The upper envelope's raising passes, shared by the anisotropic tables: every check point p
// whose table read (base(p) plus its taps' weights times the nodes) falls below
// min(fresh[p] + margin, 1) + 2e-5 (room for writing the nodes with 4 digits) raises the
// nodes it reads with positive weight by its shortfall, in the least-squares sense (each by
// shortfall x weight / sum of squared weights), no node by more than `cap` in all; passes
// repeat until no check point is below, 40 at most. `raise` gets each node's total raise.
// With `verbose`, the first pass prints the check points more than 0.01 below (axis names
// the grid's anisotropy coordinate). Returns the number of passes made (41: not converged).
template <class Taps, class Base>
int raise_to_envelope(std::vector<double>& node, std::vector<double>& raise, const std::vector<reflection_check>& checks,
                      const std::vector<double>& fresh, double margin, double cap, bool verbose, const char* axis,
                      const Taps& taps_of, const Base& base_of) {
    raise.assign(node.size(), 0.0);
    int passes = 1;
    for (; passes <= 40; ++passes) {
        std::size_t below = 0;
        for (std::size_t p = 0; p < checks.size(); ++p) {
            const std::vector<tap> taps = taps_of(p);
            double read = base_of(p);
            for (const tap& t : taps) read += t.weight * node[t.index];
            const double shortfall = std::min(fresh[p] + margin, 1.0) + 2e-5 - read;
            if (!(shortfall > 0)) continue;
            if (verbose && passes == 1 && shortfall > 0.01)
                std::fprintf(stderr, "check side %zu x %.4f u %.4f y %.4f %s %.4f e %.4f: fresh %.5f table %.5f\n",
                             checks[p].side, checks[p].x, checks[p].u, checks[p].y, axis, checks[p].s, checks[p].e, fresh[p],
                             read);
            ++below;
            double norm = 0;
            for (const tap& t : taps)
                if (t.weight > 0) norm += t.weight * t.weight;
            if (!(norm > 0)) continue;
            for (const tap& t : taps)
                if (t.weight > 0) {
                    const double step = std::min(shortfall * t.weight / norm, cap - raise[t.index]);
                    if (!(step > 0)) continue;
                    node[t.index] += step;
                    raise[t.index] += step;
                }
        }
        if (below == 0) break;
    }
    return passes;
}

// What a table reads at a random point and a fresh estimate there.
struct point_check {
    double table, fresh, error;
};

// The anisotropic tables' check at s.points random points: eta_hat - 1 log-uniform over
// [0.05, 2], either side, alpha_min / alpha_max uniform in [0, 1] (every fifth point 0: the
// smaller alpha 1e-4), either axis the smoother, y uniform in [0.1, 1], mu >= 0.1 uniform in
// sqrt(mu), azimuth uniform. interface_at(z, y, e, side) is the grid's interface;
// compare(at, v, seed) what the table reads and a fresh estimate (seeded) there. Writes
// out.points and the per-side range of table - fresh.
template <class Table, class InterfaceAt, class Compare>
void check_random_points(const settings& s, ex::progress& bar, Table& out, const InterfaceAt& interface_at,
                         const Compare& compare) {
    out.points = s.points;
    std::vector<double> difference(s.points);
    parallel_for(s.points, s.threads, [&](std::size_t p) {
        shade::rng random(0x5eed0000 + p);
        const std::size_t side = p % 2;
        const double e = random.uniform<double>();
        const double z_coord = p % 10 == 4 || p % 10 == 5 ? 0.0 : std::sqrt(random.uniform<double>());
        const double y = 0.1 + 0.9 * random.uniform<double>();
        const auto at0 = interface_at(z_coord, y, e, side);
        const bool swap = p % 4 >= 2;
        const decltype(at0) at{swap ? at0.alpha_y : at0.alpha_x, swap ? at0.alpha_x : at0.alpha_y, at0.eta_s};
        const double x = std::sqrt(0.1) + (1 - std::sqrt(0.1)) * random.uniform<double>(), mu = x * x;
        const double phi = random.uniform<double>() * 2 * shade::pi<double>;
        const double sin_theta = std::sqrt((1 - mu) * (1 + mu));
        const shade::vec3<T> v(sin_theta * std::cos(phi), sin_theta * std::sin(phi), mu);
        const point_check c = compare(at, v, 0x0f00000 + p);
        difference[p] = c.table - c.fresh;
        if (s.verbose)
            std::fprintf(stderr, "point side %zu eta_s %.4f alpha_x %.5f alpha_y %.5f mu %.4f phi %.4f: table %.5f fresh %.5f +- %.1e\n",
                         side, at.eta_s, at.alpha_x, at.alpha_y, mu, phi, c.table, c.fresh, c.error);
        bar.advance();
    });
    for (std::size_t p = 0; p < s.points; ++p) {
        out.side_lowest[p % 2] = std::min(out.side_lowest[p % 2], difference[p]);
        out.side_highest[p % 2] = std::max(out.side_highest[p % 2], difference[p]);
    }
}

// The most by which the envelope raises one node (tests/bsdf/test_dielectric_reflection_albedo.cpp
// holds the committed table to it).
constexpr double reflection_raise_cap = 0.15;

reflection_table compute_reflection(const settings& s, ex::progress& bar, const std::vector<reflection_check>& checks) {
    reflection_table out;
    out.delta.assign(d::reflection_anisotropic_size, 0.0f);
    std::vector<double> errors(d::reflection_anisotropic_size, 0.0), node(d::reflection_anisotropic_size, 0.0);
    parallel_for(d::reflection_anisotropic_size, s.threads, [&](std::size_t index) {
        const std::size_t i_x = index % rg::nx, i_u = index / rg::nx % rg::nu, j = 1 + index / (rg::nx * rg::nu) % (rg::ny - 1),
                          k = index / (rg::nx * rg::nu * (rg::ny - 1)) % (rg::ns - 1),
                          m = index / (rg::nx * rg::nu * (rg::ny - 1) * (rg::ns - 1)) % rg::ne,
                          side = index / (rg::nx * rg::nu * (rg::ny - 1) * (rg::ns - 1) * rg::ne);
        const auto at = reflection_interface_at(double(k) / double(rg::ns - 1), double(j) / double(rg::ny - 1),
                                                double(m) / double(rg::ne - 1), side);
        const auto view = reflection_view_at(double(i_x) / double(rg::nx - 1), double(i_u) / double(rg::nu - 1), at, side);
        const auto a = estimate_view_reflection(at.alpha_x, at.alpha_y, at.eta_s, view.v, s.strata, 1 + index);
        node[index] = std::min(a.albedo.x, 1.0) - reflection_base(at, view.v.z, view.phi);
        errors[index] = a.standard_error.x;
        bar.advance();
    });
    for (std::size_t n = 0; n < node.size(); ++n) out.delta[n] = float(node[n]);
    out.max_error = *std::max_element(errors.begin(), errors.end());
    // The upper envelope: fresh estimates at the check points, then passes that raise the
    // stored nodes a check point reads with positive weight by its shortfall (the smallest
    // raise in the least-squares sense: each by shortfall x weight / sum of squared weights)
    // until no check point is above the table.
    if (!checks.empty()) {
        out.checks = checks.size();
        std::vector<double> fresh(checks.size());
        std::vector<reflection_interface> where(checks.size());
        std::vector<shade::vec3<T>> view(checks.size());
        parallel_for(checks.size(), s.threads, [&](std::size_t p) {
            const auto& c = checks[p];
            where[p] = reflection_interface_at(c.s, c.y, c.e, c.side);
            view[p] = reflection_view_at(c.x, c.u, where[p], c.side).v;
            // With --envelope-sigma K the estimate counts K standard errors higher: the
            // table then stands above the truth at the check point but for K-sigma noise.
            const auto a = estimate_view_reflection(where[p].alpha_x, where[p].alpha_y, where[p].eta_s, view[p], s.envelope,
                                                    3000017 + p);
            fresh[p] = std::min(a.albedo.x + s.envelope_sigma * a.standard_error.x, 1.0);
            bar.advance();
        });
        // No node raised by more than reflection_raise_cap in all: where the spline cannot
        // follow R_ss (a kink between nodes), raising for one check point lowers others through
        // the negative weights, and the passes would escalate.
        std::vector<double> raise;
        out.passes = raise_to_envelope(
            node, raise, checks, fresh, s.envelope_margin, reflection_raise_cap, s.verbose, "s",
            [&](std::size_t p) { return reflection_taps(where[p], view[p]); },
            [&](std::size_t p) { return reflection_base(where[p], view[p]); });
        for (std::size_t n = 0; n < node.size(); ++n) {
            out.delta[n] = as_written(node[n], 4);
            if (raise[n] > 0) ++out.raised;
            out.max_raise = std::max(out.max_raise, raise[n]);
        }
        for (std::size_t p = 0; p < checks.size(); ++p)
            out.envelope_left = std::max(out.envelope_left, fresh[p] - reflection_read(out.delta, where[p], view[p]));
    } else {
        for (std::size_t n = 0; n < node.size(); ++n) out.delta[n] = as_written(node[n], 4);
    }
    for (const float x : out.delta) out.max_delta = std::max(out.max_delta, double(std::abs(x)));
    check_random_points(s, bar, out, reflection_interface_at,
                        [&](const reflection_interface& at, const shade::vec3<T>& v, std::uint64_t seed) {
                            const auto fresh = estimate_view_reflection(at.alpha_x, at.alpha_y, at.eta_s, v, s.strata, seed);
                            const double table =
                                d::anisotropic_reflection_albedo<double>(at.alpha_x, at.alpha_y, at.eta_s).at(v, out.delta.data());
                            return point_check{table, fresh.albedo.x, fresh.standard_error.x};
                        });
    return out;
}

void write_reflection(std::FILE* f, const reflection_table& t, const settings& s) {
    std::fprintf(f, "#pragma once\n");
    std::fprintf(f, "// Generated by examples/dielectric_albedo_tables.cpp (--anisotropic --reflection --strata %zu%s); do not edit by hand.\n",
                 s.strata, envelope_options(s).c_str());
    std::fprintf(f, "// The anisotropic correction of shade/bsdf/dielectric_anisotropic_reflection_albedo.hpp (meaning)\n");
    std::fprintf(f, "// on the grid of shade/bsdf/dielectric_anisotropic_reflection_table.hpp (grid, interpolation):\n");
    std::fprintf(f, "// 2 sides x %zu (e) x %zu (z < 1) x %zu (y > 0) x %zu (u) rows of %zu (x) nodes, the %zu azimuth rows of\n",
                 rg::ne, rg::ns - 1, rg::ny - 1, rg::nu, rg::nx, rg::nu);
    std::fprintf(f, "// one node per line; each node R_ss(w), the mean importance-mode weight of %zu jittered samples of\n",
                 s.strata * s.strata);
    std::fprintf(f, "// the interface's own sampler (reflections only), minus the isotropic table\n");
    std::fprintf(f, "// (dielectric_reflection_albedo_data.hpp) at detail::reflection_base_alpha (entering: the roughness\n");
    std::fprintf(f, "// projected on the node's azimuth; exiting: the root mean square), written with 4 significant digits.\n\n");
    std::fprintf(f, "#include <shade/bsdf/dielectric_anisotropic_reflection_table.hpp>\n\n");
    std::fprintf(f, "namespace shade::detail {\n\n");
    std::fprintf(f, "/// Delta_R,s(w), the reflected part's, of shade::rough_dielectric<ggx> with alpha_x != alpha_y.\n");
    std::fprintf(f, "/// Node standard error <= %.1e; |Delta_R| <= %.3f.", t.max_error, t.max_delta);
    if (t.checks > 0)
        std::fprintf(f,
                     "\n/// An upper envelope, not point values: %zu nodes raised (by at most %.1e) so that no fresh\n"
                     "/// %zu-sample estimate (+ %g standard errors + %g) at %zu check points with mu >= 0.05 (cell centres\n"
                     "/// and edge middles, %zu of them random) is above the table by more than %.1e.",
                     t.raised, t.max_raise, s.envelope * s.envelope, s.envelope_sigma, s.envelope_margin, t.checks, t.random_checks,
                     std::max(t.envelope_left, 0.0));
    std::fprintf(f, "\n/// The table read minus a fresh estimate at %zu random points with mu >= 0.1 (interpolation\n"
                    "/// and both estimates' noise): entering side %.1e to %.1e, exiting side %.1e to %.1e.\n",
                 t.points, t.side_lowest[0], t.side_highest[0], t.side_lowest[1], t.side_highest[1]);
    std::fprintf(f, "inline constexpr float ggx_dielectric_anisotropic_reflection_delta[reflection_anisotropic_size] = {\n");
    for (std::size_t row = 0; row < d::reflection_anisotropic_rows; row += rg::nu) {
        ex::write_float_literals(f, t.delta.data() + row * rg::nx, rg::nx * rg::nu, 4);
        std::fprintf(f, ",\n");
    }
    std::fprintf(f, "};\n\n");
    std::fprintf(f, "} // namespace shade::detail\n");
}

// ---- The anisotropic total-albedo correction (--anisotropic), on the grid of
// shade/bsdf/dielectric_anisotropic_albedo_table.hpp.

namespace tg {
constexpr std::size_t nx = d::dielectric_anisotropic_mu_nodes, nu = d::dielectric_anisotropic_azimuth_nodes;
constexpr std::size_t ny = d::dielectric_anisotropic_roughness_nodes, nz = d::dielectric_anisotropic_ratio_nodes;
constexpr std::size_t ne = d::dielectric_anisotropic_eta_nodes;
} // namespace tg

// The interface of a (z, y, e, side) point of the grid: the smoother alpha along t, at least
// OpenPBR's smallest alpha 1e-4 (z = 0: OpenPBR's anisotropy 1); eta_s of the side.
struct total_interface {
    double alpha_x, alpha_y, eta_s;
};
total_interface total_interface_at(double z_coord, double y_coord, double e_coord, std::size_t side) {
    const double alpha_max = d::dielectric_anisotropic_alpha_top * y_coord * y_coord;
    const double alpha_min = std::max(z_coord * z_coord * alpha_max, 1e-4);
    const double eta_hat = 1 + std::exp(d::dielectric_albedo_x_min + e_coord * (d::dielectric_albedo_x_max - d::dielectric_albedo_x_min));
    return {alpha_min, alpha_max, eta_of_side(side, eta_hat)};
}

// The unit local view (v.z > 0) at the grid coordinates x = sqrt(mu) and u (from t).
shade::vec3<T> total_view_at(double x_coord, double u_coord) {
    const double mu = std::min(std::max(x_coord * x_coord, d::albedo_grid_mu_min), 1.0);
    const double sin_theta = std::sqrt((1 - mu) * (1 + mu)), phi = d::dielectric_anisotropic_phi(u_coord);
    return {sin_theta * std::cos(phi), sin_theta * std::sin(phi), mu};
}

// E_iso of the committed table at (mu, alpha, eta_s).
double iso_albedo(double mu, double alpha, double eta_s) {
    const d::dielectric_albedo_grid g{};
    return d::dielectric_albedo_lookup(d::ggx_rough_dielectric_albedo, g, d::dielectric_albedo_locate(g, alpha, eta_s), mu);
}

// What Delta is measured from: E_iso at the base roughness (dielectric_anisotropic_base_alpha).
double total_base(const total_interface& at, double mu) {
    return iso_albedo(std::min(mu, 1.0), d::dielectric_anisotropic_base_alpha(at.alpha_x, at.alpha_y), at.eta_s);
}

// The taps with which dielectric_anisotropic_delta reads the interface `at` at view v.
std::vector<tap> total_taps(const total_interface& at, const shade::vec3<T>& v) {
    const auto cell = d::dielectric_anisotropic_locate(at.alpha_x, at.alpha_y, at.eta_s);
    const std::size_t side = at.eta_s > 1 ? 0 : 1;
    const double along = cell.swapped ? v.y : v.x, across = cell.swapped ? v.x : v.y;
    const auto u = d::albedo_grid_locate(d::dielectric_anisotropic_u(std::atan2(std::abs(across), std::abs(along))), tg::nu);
    const auto x = d::albedo_grid_locate(std::sqrt(std::min(v.z, 1.0)), tg::nx);
    const d::spline_taps<double> wx(x.i, x.t, tg::nx);
    std::vector<tap> out;
    for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b)
            for (int c = 0; c < 4; ++c) {
                const double w = cell.e.weight[a] * cell.z.weight[b] * cell.y.weight[c];
                if (w == 0 || cell.y.node[c] == 0) continue;
                for (std::size_t du = 0; du < 2; ++du) {
                    const double wu = du == 0 ? 1 - u.t : u.t;
                    if (wu == 0) continue;
                    const std::size_t row =
                        d::dielectric_anisotropic_row_index(side, cell.e.node[a], cell.z.node[b], cell.y.node[c], u.i + du);
                    for (int k = 0; k < 4; ++k)
                        if (wx.weight[k] != 0) out.push_back({row * tg::nx + wx.node[k], w * wu * wx.weight[k]});
                }
            }
    return out;
}

// E(v) of the interface as the table reads it (unclamped).
double total_read(const std::vector<float>& delta, const total_interface& at, const shade::vec3<T>& v) {
    const auto cell = d::dielectric_anisotropic_locate(at.alpha_x, at.alpha_y, at.eta_s);
    return total_base(at, v.z) + d::dielectric_anisotropic_delta(delta.data(), cell, at.eta_s > 1 ? 0 : 1, v.x, v.y, v.z);
}

struct anisotropic_table {
    std::vector<float> delta;        // dielectric_anisotropic_size values
    std::vector<float> average;      // one per stored row
    double max_error = 0;            // largest standard error of a node
    double max_delta = 0;            // largest |Delta|
    std::size_t checks = 0;          // envelope check points (0: point values)
    std::size_t envelope_checks = 0; // of those, the ones that raise nodes (z below --envelope-below-z)
    std::size_t raised = 0;          // nodes raised by the envelope
    double max_raise = 0;            // the largest raise
    int passes = 0;                  // raising passes
    double envelope_left = 0;        // the largest check estimate - table left after the passes and rounding
    double side_lowest[2] = {0, 0};  // table - fresh estimate at the random points, per side
    double side_highest[2] = {0, 0};
    std::size_t points = 0;
};

// The envelope's check points with mu >= 0.05, as for the reflection table: on every stored
// (side, e, z, y) slice the middles of the (x, u) cells and edges; the middle of every y, z
// and e edge at the other axes' nodes; the centre of every cell of the whole grid.
std::vector<reflection_check> total_checks() {
    std::vector<reflection_check> out;
    const auto at = [](std::size_t i, std::size_t n) { return double(i) / double(n - 1); };
    const auto mid = [](std::size_t i, std::size_t n) { return (double(i) + 0.5) / double(n - 1); };
    for (std::size_t side = 0; side < 2; ++side)
        for (std::size_t m = 0; m < tg::ne; ++m)
            for (std::size_t k = 0; k < tg::nz; ++k)
                for (std::size_t j = 1; j < tg::ny; ++j)
                    for (std::size_t i_u = 0; i_u < tg::nu; ++i_u)
                        for (std::size_t i_x = 0; i_x < tg::nx; ++i_x) {
                            const double y = at(j, tg::ny), z = at(k, tg::nz), e = at(m, tg::ne);
                            if (i_x + 1 < tg::nx && i_u + 1 < tg::nu) out.push_back({mid(i_x, tg::nx), mid(i_u, tg::nu), y, z, e, side});
                            if (i_x + 1 < tg::nx) out.push_back({mid(i_x, tg::nx), at(i_u, tg::nu), y, z, e, side});
                            if (i_u + 1 < tg::nu) out.push_back({at(i_x, tg::nx), mid(i_u, tg::nu), y, z, e, side});
                            const double x = at(i_x, tg::nx), u = at(i_u, tg::nu);
                            if (j + 1 < tg::ny) out.push_back({x, u, mid(j, tg::ny), z, e, side});
                            if (j == 1) out.push_back({x, u, mid(0, tg::ny), z, e, side}); // toward y = 0
                            if (k + 1 < tg::nz) out.push_back({x, u, y, mid(k, tg::nz), e, side});
                            if (m + 1 < tg::ne) out.push_back({x, u, y, z, mid(m, tg::ne), side});
                        }
    for (std::size_t side = 0; side < 2; ++side)
        for (std::size_t m = 0; m + 1 < tg::ne; ++m)
            for (std::size_t k = 0; k + 1 < tg::nz; ++k)
                for (std::size_t j = 0; j + 1 < tg::ny; ++j)
                    for (std::size_t i_u = 0; i_u + 1 < tg::nu; ++i_u)
                        for (std::size_t i_x = 0; i_x + 1 < tg::nx; ++i_x)
                            out.push_back({mid(i_x, tg::nx), mid(i_u, tg::nu), mid(j, tg::ny), mid(k, tg::nz), mid(m, tg::ne), side});
    // Only views with mu >= 0.05: raising nodes for the grazing views would lower the
    // interpolation above them through Catmull-Rom's negative weights.
    std::erase_if(out, [](const reflection_check& c) { return c.x * c.x < 0.05; });
    return out;
}

anisotropic_table compute_anisotropic(const settings& s, ex::progress& bar, const std::vector<reflection_check>& checks) {
    anisotropic_table out;
    out.delta.assign(d::dielectric_anisotropic_size, 0.0f);
    out.average.assign(d::dielectric_anisotropic_rows, 0.0f);
    std::vector<double> errors(d::dielectric_anisotropic_size, 0.0), node(d::dielectric_anisotropic_size, 0.0);
    const bool cached = !s.cache.empty() && std::filesystem::exists(s.cache);
    std::FILE* cache_file = s.cache.empty() ? nullptr : std::fopen(s.cache.string().c_str(), cached ? "rb" : "wb");
    const auto cache_io = [&](std::vector<double>& values) {
        if (cache_file == nullptr) return;
        const std::size_t n = cached ? std::fread(values.data(), sizeof(double), values.size(), cache_file)
                                     : std::fwrite(values.data(), sizeof(double), values.size(), cache_file);
        if (n != values.size()) throw std::runtime_error("cache: short read or write");
    };
    // node first holds each node's E (min(estimate, 1)), which the cache keeps, then Delta.
    if (!cached) parallel_for(d::dielectric_anisotropic_size, s.threads, [&](std::size_t index) {
        const std::size_t i_x = index % tg::nx, i_u = index / tg::nx % tg::nu, j = 1 + index / (tg::nx * tg::nu) % (tg::ny - 1),
                          k = index / (tg::nx * tg::nu * (tg::ny - 1)) % tg::nz,
                          m = index / (tg::nx * tg::nu * (tg::ny - 1) * tg::nz) % tg::ne,
                          side = index / (tg::nx * tg::nu * (tg::ny - 1) * tg::nz * tg::ne);
        const auto at = total_interface_at(double(k) / double(tg::nz - 1), double(j) / double(tg::ny - 1),
                                           double(m) / double(tg::ne - 1), side);
        const shade::vec3<T> v = total_view_at(double(i_x) / double(tg::nx - 1), double(i_u) / double(tg::nu - 1));
        // Isotropic (z = 1) up to alpha 1: E is the isotropic table itself.
        if (k + 1 == tg::nz && at.alpha_y <= 1) {
            node[index] = iso_albedo(v.z, at.alpha_y, at.eta_s);
            bar.advance();
            return;
        }
        // The seed leaves out the azimuth: the pole column (mu = 1) is then the same
        // estimate for every u, as Delta there is.
        const auto a = estimate_view(at.alpha_x, at.alpha_y, at.eta_s, v, s.strata, 1 + index / (tg::nx * tg::nu) * tg::nx + i_x);
        node[index] = std::min(a.albedo.x, 1.0);
        errors[index] = a.standard_error.x;
        bar.advance();
    });
    cache_io(node);
    cache_io(errors);
    // Delta = E - E_iso at the base roughness, plus the lift of the node's side: every node
    // that holds an estimate (not the isotropic rows up to alpha 1) raised by s.lift[side],
    // so that the table reads E a little high where the interpolation errs both ways.
    for (std::size_t index = 0; index < node.size(); ++index) {
        const std::size_t i_x = index % tg::nx, j = 1 + index / (tg::nx * tg::nu) % (tg::ny - 1),
                          k = index / (tg::nx * tg::nu * (tg::ny - 1)) % tg::nz,
                          m = index / (tg::nx * tg::nu * (tg::ny - 1) * tg::nz) % tg::ne,
                          side = index / (tg::nx * tg::nu * (tg::ny - 1) * tg::nz * tg::ne);
        const auto at = total_interface_at(double(k) / double(tg::nz - 1), double(j) / double(tg::ny - 1),
                                           double(m) / double(tg::ne - 1), side);
        node[index] -= total_base(at, total_view_at(double(i_x) / double(tg::nx - 1), 0).z);
        if (k + 1 < tg::nz || at.alpha_y > 1) node[index] += s.lift[side];
    }
    out.max_error = *std::max_element(errors.begin(), errors.end());
    // The upper envelope, as compute_reflection's: fresh estimates at the check points, then
    // passes that raise the nodes a check point reads with positive weight by its shortfall
    // (least squares) until no check point is above the table.
    if (!checks.empty()) {
        out.checks = checks.size();
        std::vector<double> fresh(checks.size());
        std::vector<total_interface> where(checks.size());
        std::vector<shade::vec3<T>> view(checks.size());
        parallel_for(checks.size(), s.threads, [&](std::size_t p) {
            const auto& c = checks[p];
            where[p] = total_interface_at(c.s, c.y, c.e, c.side);
            view[p] = total_view_at(c.x, c.u);
            if (cached) return;
            fresh[p] = std::min(estimate_view(where[p].alpha_x, where[p].alpha_y, where[p].eta_s, view[p], s.envelope, 3000017 + p)
                                    .albedo.x,
                                1.0);
            bar.advance();
        });
        cache_io(fresh);
        // Only the check points with z below s.envelope_below_z or alpha_rms above
        // s.envelope_rough_above raise nodes (a fresh value below every read drops the others):
        // raising for the rest, where the lifted point values already read high enough but at
        // a few kinks, lowered the reads of whole cells.
        for (std::size_t p = 0; p < checks.size(); ++p)
            if (!(checks[p].s < s.envelope_below_z ||
                  d::dielectric_anisotropic_rms_alpha(where[p].alpha_x, where[p].alpha_y) > s.envelope_rough_above))
                fresh[p] = -1;
            else ++out.envelope_checks;
        std::vector<double> raise;
        out.passes = raise_to_envelope(
            node, raise, checks, fresh, s.envelope_margin, std::numeric_limits<double>::infinity(), s.verbose, "z",
            [&](std::size_t p) { return total_taps(where[p], view[p]); },
            [&](std::size_t p) { return total_base(where[p], view[p].z); });
        for (std::size_t n = 0; n < node.size(); ++n) {
            out.delta[n] = as_written(node[n], 4);
            if (raise[n] > 0) ++out.raised;
            out.max_raise = std::max(out.max_raise, raise[n]);
        }
        for (std::size_t p = 0; p < checks.size(); ++p)
            out.envelope_left = std::max(out.envelope_left, fresh[p] - total_read(out.delta, where[p], view[p]));
    } else {
        for (std::size_t n = 0; n < node.size(); ++n) out.delta[n] = as_written(node[n], 4);
    }
    if (cache_file != nullptr) std::fclose(cache_file);
    for (const float x : out.delta) out.max_delta = std::max(out.max_delta, double(std::abs(x)));
    for (std::size_t n = 0; n < d::dielectric_anisotropic_rows; ++n)
        out.average[n] = float(d::dielectric_anisotropic_row_average(out.delta.data() + n * tg::nx));
    check_random_points(s, bar, out, total_interface_at,
                        [&](const total_interface& at, const shade::vec3<T>& v, std::uint64_t seed) {
                            const auto fresh = estimate_view(at.alpha_x, at.alpha_y, at.eta_s, v, s.strata, seed);
                            const double table =
                                at.alpha_x == at.alpha_y ? total_base(at, v.z) : total_read(out.delta, at, v);
                            return point_check{table, std::min(fresh.albedo.x, 1.0), fresh.standard_error.x};
                        });
    return out;
}

// --views FILE: R + T = 1 + E_true(v) - E_read(v) of the compensated interface (the noise-free
// split of tests/bsdf/anisotropic_furnace.hpp, table_furnace), E_read the table in memory read as
// shade::compensated_rough_dielectric reads it (clamped to [0, 1]) and E_true a 128^2-sample
// estimate (as the sweep's), at a fixed set of views: the pairs of
// tests/sweep/test_dielectric_anisotropic_sweep.cpp (2:1, 10:1, anisotropy 1), other 2:1 and
// 10:1 pairs, and the sweep's 10:1 pairs with alpha_min moved onto the z nodes 0.2 and 0.4 (an
// error there that is absent on the nodes is the z interpolation's); eta 1.05 to 3, mu 0.1 to 1,
// azimuths 0 to 90 degrees every 10, both sides. E_true is written to FILE, or read from it if
// it exists, so that table variants are compared on the same estimates.
void report_views(const anisotropic_table& t, const std::filesystem::path& file, unsigned threads) {
    struct pair_class {
        double alpha_x, alpha_y;
        int c;
    };
    constexpr int classes = 7;
    const char* const name[classes] = {"2:1 (sweep)", "10:1 (sweep)", "anisotropy 1 (sweep)", "2:1 (others)",
                                       "10:1 (others)", "10:1 on z 0.2", "10:1 on z 0.4"};
    constexpr pair_class pairs[] = {
        {0.2, 0.4, 0},   {0.6, 0.3, 0},   {0.5, 1.0, 0},   {0.05, 0.5, 1},   {0.8, 0.08, 1},  {0.1, 1.0, 1},
        {0.3, 1e-4, 2},  {0.7, 1e-4, 2},  {1e-4, 0.127, 2}, {1e-4, 0.509, 2}, {1e-4, 1.414, 2}, {0.05, 0.1, 3},
        {0.1, 0.05, 3},  {0.3, 0.15, 3},  {0.4, 0.8, 3},   {0.7, 1.4, 3},    {1.3, 0.65, 3},  {0.6, 1.2, 3},
        {0.02, 0.2, 4},  {0.3, 0.03, 4},  {0.06, 0.6, 4},  {1.2, 0.12, 4},   {0.4, 0.04, 4},  {0.15, 1.5, 4},
        {0.02, 0.5, 5},  {0.8, 0.032, 5}, {0.04, 1.0, 5},  {0.08, 0.5, 6},   {0.8, 0.128, 6}, {0.16, 1.0, 6}};
    struct view_point {
        total_interface at;
        shade::vec3<T> v;
        std::size_t pair;
        int side;
        double eta, mu, phi;
    };
    std::vector<view_point> views;
    for (std::size_t q = 0; q < std::size(pairs); ++q)
        for (const double eta : {1.05, 1.2, 1.33, 1.5, 1.7, 2.2, 2.5, 3.0})
            for (const int side : {0, 1})
                for (const double mu : {0.1, 0.15, 0.2, 0.3, 0.45, 0.6, 0.8, 1.0})
                    for (int degrees = 0; degrees <= 90; degrees += 10) {
                        if (mu == 1.0 && degrees > 0) continue;
                        const double phi = double(degrees) * 0.017453292519943295, sin_theta = std::sqrt((1 - mu) * (1 + mu));
                        views.push_back({{pairs[q].alpha_x, pairs[q].alpha_y, side == 0 ? eta : 1 / eta},
                                         {sin_theta * std::cos(phi), sin_theta * std::sin(phi), mu}, q, side, eta, mu, double(degrees)});
                    }
    std::vector<double> truth(views.size());
    if (std::filesystem::exists(file)) {
        std::FILE* f = std::fopen(file.string().c_str(), "rb");
        const std::size_t n = f == nullptr ? 0 : std::fread(truth.data(), sizeof(double), truth.size(), f);
        if (f != nullptr) std::fclose(f);
        if (n != truth.size()) throw std::runtime_error("--views: cannot read " + std::to_string(truth.size()) + " estimates from " + file.string());
    } else {
        parallel_for(views.size(), threads, [&](std::size_t p) {
            const view_point& w = views[p];
            truth[p] = estimate_view(w.at.alpha_x, w.at.alpha_y, w.at.eta_s, w.v, 128, 777 + p).albedo.x;
        });
        std::FILE* f = std::fopen(file.string().c_str(), "wb");
        const std::size_t n = f == nullptr ? 0 : std::fwrite(truth.data(), sizeof(double), truth.size(), f);
        if (f != nullptr) std::fclose(f);
        if (n != truth.size()) throw std::runtime_error("--views: cannot write " + file.string());
    }
    struct range {
        double lowest = 2, highest = 0;
        std::size_t at_lowest = 0, at_highest = 0, below = 0, above = 0;
    } r[classes][2];
    for (std::size_t p = 0; p < views.size(); ++p) {
        const view_point& w = views[p];
        const double total = 1 + truth[p] - std::clamp(total_read(t.delta, w.at, w.v), 0.0, 1.0);
        range& m = r[pairs[w.pair].c][w.side];
        if (total < m.lowest) m.lowest = total, m.at_lowest = p;
        if (total > m.highest) m.highest = total, m.at_highest = p;
        if (total < 0.99) ++m.below;
        if (total > 1.001) ++m.above;
    }
    const auto where = [&](std::size_t p) {
        const view_point& w = views[p];
        char text[96];
        std::snprintf(text, sizeof text, "%g x %g, eta %g, mu %g, phi %g", pairs[w.pair].alpha_x, pairs[w.pair].alpha_y, w.eta, w.mu, w.phi);
        return std::string(text);
    };
    for (int c = 0; c < classes; ++c)
        for (int side = 0; side < 2; ++side) {
            const range& m = r[c][side];
            std::fprintf(stderr, "dielectric_albedo_tables: views: %s, v %s: R + T %.4f (%s) to %.4f (%s); %zu below 0.99, %zu above 1.001\n",
                         name[c], side == 0 ? "outside" : "inside", m.lowest, where(m.at_lowest).c_str(), m.highest,
                         where(m.at_highest).c_str(), m.below, m.above);
        }
}

void write_anisotropic(std::FILE* f, const anisotropic_table& t, const settings& s) {
    std::fprintf(f, "#pragma once\n");
    std::string options = envelope_options(s);
    if (s.envelope > 0 && s.envelope_below_z < 2) {
        char text[64];
        std::snprintf(text, sizeof text, " --envelope-below-z %g", s.envelope_below_z);
        options += text;
    }
    if (s.envelope > 0 && s.envelope_rough_above < 2) {
        char text[64];
        std::snprintf(text, sizeof text, " --envelope-rough-above %g", s.envelope_rough_above);
        options += text;
    }
    if (s.lift[0] > 0 || s.lift[1] > 0) {
        char text[64];
        std::snprintf(text, sizeof text, " --lift %g,%g", s.lift[0], s.lift[1]);
        options += text;
    }
    std::fprintf(f, "// Generated by examples/dielectric_albedo_tables.cpp (--anisotropic --strata %zu%s); do not edit by hand.\n",
                 s.strata, options.c_str());
    std::fprintf(f, "// The anisotropic corrections of shade/bsdf/dielectric_anisotropic_albedo_table.hpp (meaning, grid,\n");
    std::fprintf(f, "// interpolation): 2 sides x %zu (e) x %zu (z) x %zu (y > 0) x %zu (u) rows of %zu (x) nodes, the %zu\n",
                 tg::ne, tg::nz, tg::ny - 1, tg::nu, tg::nx, tg::nu);
    std::fprintf(f, "// azimuth rows of one node per line; each node E(w), the mean importance-mode weight of %zu jittered\n",
                 s.strata * s.strata);
    std::fprintf(f, "// samples of the interface's own sampler, minus the isotropic table (dielectric_albedo_data.hpp) at\n");
    std::fprintf(f, "// the base roughness (dielectric_anisotropic_base_alpha), plus the lift (%g entering, %g exiting; not on\n",
                 s.lift[0], s.lift[1]);
    std::fprintf(f, "// the isotropic rows up to alpha 1), written with 4 significant digits.\n\n");
    std::fprintf(f, "#include <shade/bsdf/dielectric_anisotropic_albedo_table.hpp>\n\n");
    std::fprintf(f, "namespace shade::detail {\n\n");
    std::fprintf(f, "/// Delta_s(w) of shade::rough_dielectric<ggx> with alpha_x != alpha_y.\n");
    std::fprintf(f, "/// Node standard error <= %.1e; |Delta| <= %.3f.", t.max_error, t.max_delta);
    if (t.checks > 0)
        std::fprintf(f,
                     "\n/// An upper envelope of E where z < %g or alpha_rms > %g: %zu nodes raised (by at most %.1e) so\n"
                     "/// that no fresh %zu-sample estimate (+ %g) at the %zu check points there with mu >= 0.05 (cell\n"
                     "/// centres and edge middles) is above the table by more than %.1e.",
                     std::min(s.envelope_below_z, 1.0), s.envelope_rough_above, t.raised, t.max_raise, s.envelope * s.envelope,
                     s.envelope_margin, t.envelope_checks, std::max(t.envelope_left, 0.0));
    std::fprintf(f, "\n/// The table read minus a fresh estimate at %zu random points with mu >= 0.1 (interpolation\n"
                    "/// and both estimates' noise): entering side %.1e to %.1e, exiting side %.1e to %.1e.\n",
                 t.points, t.side_lowest[0], t.side_highest[0], t.side_lowest[1], t.side_highest[1]);
    std::fprintf(f, "inline constexpr float ggx_dielectric_anisotropic_delta[dielectric_anisotropic_size] = {\n");
    for (std::size_t row = 0; row < d::dielectric_anisotropic_rows; row += tg::nu) {
        ex::write_float_literals(f, t.delta.data() + row * tg::nx, tg::nx * tg::nu, 4);
        std::fprintf(f, ",\n");
    }
    std::fprintf(f, "};\n\n");
    std::fprintf(f, "/// The cosine averages of the rows of ggx_dielectric_anisotropic_delta\n");
    std::fprintf(f, "/// (dielectric_anisotropic_row_average), the %zu azimuth rows of one node per line.\n", tg::nu);
    std::fprintf(f, "inline constexpr float ggx_dielectric_anisotropic_delta_average[dielectric_anisotropic_rows] = {\n");
    for (std::size_t n = 0; n < d::dielectric_anisotropic_rows / tg::nu; ++n) {
        ex::write_float_literals(f, t.average.data() + n * tg::nu, tg::nu);
        std::fprintf(f, ",\n");
    }
    std::fprintf(f, "};\n\n");
    std::fprintf(f, "} // namespace shade::detail\n");
}

} // namespace

int main(int argc, char** argv) {
    return ex::run_cli("dielectric_albedo_tables", [&] {
        settings s;
        bool strata_given = false, nodes_given = false;
        std::size_t mu_nodes = 0, alpha_nodes = 0, eta_nodes = 0; // 0: the grid's own
        ex::command_line args(argc, argv);
        while (args.next()) {
            if (args.flag("--help") || args.flag("-h")) {
                std::fputs(usage.data(), stdout);
                return 0;
            }
            if (args.option("--out")) s.out = args.path();
            else if (args.option("--mu-nodes")) {
                mu_nodes = args.integer<std::size_t>(4, 128);
                nodes_given = true;
            } else if (args.option("--alpha-nodes")) {
                alpha_nodes = args.integer<std::size_t>(4, 128);
                nodes_given = true;
            } else if (args.option("--eta-nodes")) {
                eta_nodes = args.integer<std::size_t>(2, 64);
                nodes_given = true;
            }
            else if (args.option("--strata")) {
                s.strata = args.integer<std::size_t>(16, 2048);
                strata_given = true;
            }
            else if (args.option("--threads")) s.threads = args.integer<unsigned>(1, 64);
            else if (args.flag("--quiet")) s.quiet = true;
            else if (args.flag("--anisotropic")) s.anisotropic = true;
            else if (args.flag("--beckmann")) s.beckmann = true;
            else if (args.flag("--reflection")) s.reflection = true;
            else if (args.flag("--beyond")) s.beyond = true;
            else if (args.flag("--verbose")) s.verbose = true;
            else if (args.option("--points")) s.points = args.integer<std::size_t>(0, 1000000);
            else if (args.option("--envelope")) s.envelope = args.integer<std::size_t>(16, 2048);
            else if (args.option("--envelope-margin")) s.envelope_margin = args.real(0, 0.01);
            else if (args.option("--envelope-view-steps")) s.envelope_view_steps = args.integer<std::size_t>(2, 8);
            else if (args.option("--cache")) s.cache = args.path();
            else if (args.option("--views")) s.views = args.path();
            else if (args.option("--lift")) {
                const std::string text(args.text());
                const std::size_t comma = text.find(',');
                s.lift[0] = ex::parse_real("--lift", text.substr(0, comma), 0, 0.01);
                s.lift[1] = comma == std::string::npos ? s.lift[0] : ex::parse_real("--lift", text.substr(comma + 1), 0, 0.01);
            }
            else if (args.option("--envelope-below-z")) s.envelope_below_z = args.real(0, 1, ex::lower_limit::exclusive);
            else if (args.option("--envelope-rough-above")) s.envelope_rough_above = args.real(0, 2);
            else if (args.option("--envelope-random")) s.envelope_random = args.integer<std::size_t>(1, 10000000);
            else if (args.option("--envelope-sigma")) s.envelope_sigma = args.real(0, 4);
            else args.unknown();
        }
        (void)ex::output_format("--out", s.out, {".hpp", ".h"});
        if (s.anisotropic && s.beckmann)
            throw ex::usage_error("--beckmann does not apply to --anisotropic (the correction is tabulated for GGX)");
        if (s.beckmann && s.out == "dielectric_albedo_data.hpp") s.out = "beckmann_dielectric_albedo_data.hpp";
        if (s.reflection && s.beckmann)
            throw ex::usage_error("--reflection does not apply to --beckmann (it is tabulated for GGX)");
        if (s.envelope > 0 && s.reflection && !s.anisotropic)
            throw ex::usage_error("--envelope applies to the total-albedo tables and to --anisotropic --reflection only");
        if (s.envelope_view_steps != 2 && (s.envelope == 0 || s.anisotropic))
            throw ex::usage_error("--envelope-view-steps needs --envelope on a total-albedo table");
        const bool envelope_scope = s.envelope_below_z < 2 || s.envelope_rough_above < 2;
        if ((!s.cache.empty() || !s.views.empty() || s.lift[0] > 0 || s.lift[1] > 0 || envelope_scope) &&
            (!s.anisotropic || s.reflection))
            throw ex::usage_error(
                "--cache, --views, --lift, --envelope-below-z and --envelope-rough-above apply to --anisotropic (total albedo) only");
        if (envelope_scope && s.envelope == 0)
            throw ex::usage_error("--envelope-below-z and --envelope-rough-above need --envelope");
        if (s.envelope_margin > 0 && s.envelope == 0)
            throw ex::usage_error("--envelope-margin needs --envelope on a total-albedo table or on --anisotropic --reflection");
        if (s.envelope_random > 0 && (s.envelope == 0 || !s.anisotropic || !s.reflection))
            throw ex::usage_error("--envelope-random needs --anisotropic --reflection --envelope S");
        if (s.envelope_sigma > 0 && (s.envelope == 0 || !s.anisotropic || !s.reflection))
            throw ex::usage_error("--envelope-sigma needs --anisotropic --reflection --envelope S");
        if (s.reflection && !s.anisotropic) {
            if (s.out == "dielectric_albedo_data.hpp") s.out = "dielectric_reflection_albedo_data.hpp";
            s.grid = d::dielectric_reflection_albedo_grid;
        }
        if (s.beckmann) s.grid = d::dielectric_beckmann_albedo_grid;
        if (s.beyond) {
            if (s.reflection || s.anisotropic)
                throw ex::usage_error("--beyond applies to the total-albedo tables (GGX, or --beckmann) only");
            s.grid = s.beckmann ? d::dielectric_beckmann_albedo_beyond_grid : d::dielectric_albedo_beyond_grid;
            if (s.out == "dielectric_albedo_data.hpp") s.out = "dielectric_albedo_beyond_data.hpp";
            if (s.out == "beckmann_dielectric_albedo_data.hpp") s.out = "beckmann_dielectric_albedo_beyond_data.hpp";
        }
        if (mu_nodes != 0) s.grid.mu_nodes = mu_nodes;
        if (alpha_nodes != 0) s.grid.alpha_nodes = alpha_nodes;
        if (eta_nodes != 0) s.grid.eta_nodes = eta_nodes;
        if (s.anisotropic && nodes_given)
            throw ex::usage_error("--mu-nodes, --alpha-nodes and --eta-nodes do not apply to --anisotropic (its grid is fixed)");
        if (s.anisotropic && s.reflection) {
            if (s.out == "dielectric_albedo_data.hpp") s.out = "dielectric_anisotropic_reflection_albedo_data.hpp";
            if (!strata_given) s.strata = 128;
            ex::output_file header(s.out);
            std::vector<reflection_check> checks = s.envelope > 0 ? reflection_checks() : std::vector<reflection_check>{};
            const std::size_t fixed_checks = checks.size();
            for (const reflection_check& c : reflection_random_checks(s.envelope_random)) checks.push_back(c);
            std::optional<ex::progress> bar(std::in_place, "dielectric_albedo_tables",
                                            d::reflection_anisotropic_size + checks.size() + s.points, !s.quiet);
            reflection_table t = compute_reflection(s, *bar, checks);
            t.random_checks = checks.size() - fixed_checks;
            bar.reset();
            std::fprintf(stderr,
                         "dielectric_albedo_tables: anisotropic reflection: largest node standard error %.2e, |Delta_R| <= %.3f; "
                         "envelope: %zu check points, %zu nodes raised by at most %.2e in %d passes, %.2e left; table - fresh "
                         "estimate at %zu points with mu >= 0.1: entering %.2e to %.2e, exiting %.2e to %.2e\n",
                         t.max_error, t.max_delta, t.checks, t.raised, t.max_raise, t.passes, t.envelope_left, t.points,
                         t.side_lowest[0], t.side_highest[0], t.side_lowest[1], t.side_highest[1]);
            header.write_stream([&](std::FILE* f) {
                write_reflection(f, t, s);
            });
            std::fprintf(stderr, "dielectric_albedo_tables: wrote %s\n", s.out.string().c_str());
            return 0;
        }
        if (s.anisotropic) {
            if (s.out == "dielectric_albedo_data.hpp") s.out = "dielectric_anisotropic_albedo_data.hpp";
            if (!strata_given) s.strata = 128;
            ex::output_file header(s.out);
            const std::vector<reflection_check> checks = s.envelope > 0 ? total_checks() : std::vector<reflection_check>{};
            std::optional<ex::progress> bar(std::in_place, "dielectric_albedo_tables",
                                            d::dielectric_anisotropic_size + checks.size() + s.points, !s.quiet);
            const anisotropic_table t = compute_anisotropic(s, *bar, checks);
            bar.reset();
            std::fprintf(stderr,
                         "dielectric_albedo_tables: anisotropic: largest node standard error %.2e, |Delta| <= %.3f; "
                         "envelope: %zu check points, %zu nodes raised by at most %.2e in %d passes, %.2e left; table - fresh "
                         "estimate at %zu points with mu >= 0.1: entering %.2e to %.2e, exiting %.2e to %.2e\n",
                         t.max_error, t.max_delta, t.checks, t.raised, t.max_raise, t.passes, t.envelope_left, t.points,
                         t.side_lowest[0], t.side_highest[0], t.side_lowest[1], t.side_highest[1]);
            if (!s.views.empty()) report_views(t, s.views, s.threads);
            header.write_stream([&](std::FILE* f) {
                write_anisotropic(f, t, s);
            });
            std::fprintf(stderr, "dielectric_albedo_tables: wrote %s\n", s.out.string().c_str());
            return 0;
        }
        ex::output_file header(s.out);
        const d::dielectric_albedo_grid& g = s.grid;
        const std::size_t cells = 2 * (g.eta_nodes - 1) * (g.alpha_nodes - 1) * (g.mu_nodes - 1);
        const std::size_t checks = s.envelope > 0 ? envelope_points(g, s.envelope_view_steps).size() : 0;
        std::optional<ex::progress> bar(std::in_place, "dielectric_albedo_tables", g.size() + cells + checks, !s.quiet);
        std::vector<table> tables;
        if (s.reflection)
            tables.push_back(compute("ggx_rough_dielectric_reflection_albedo",
                                     "shade::rough_dielectric<ggx> (isotropic alpha), reflected part",
                                     estimate_reflection, s, *bar));
        else if (s.beckmann)
            tables.push_back(compute(s.beyond ? "beckmann_rough_dielectric_albedo_beyond" : "beckmann_rough_dielectric_albedo",
                                     s.beyond ? "shade::rough_dielectric<beckmann> (isotropic m, read as alpha), eta_hat 3 to 1000"
                                              : "shade::rough_dielectric<beckmann> (isotropic m, read as alpha)",
                                     estimate<shade::beckmann<T>>, s, *bar));
        else
            tables.push_back(compute(s.beyond ? "ggx_rough_dielectric_albedo_beyond" : "ggx_rough_dielectric_albedo",
                                     s.beyond ? "shade::rough_dielectric<ggx> (isotropic alpha), eta_hat 3 to 1000"
                                              : "shade::rough_dielectric<ggx> (isotropic alpha)",
                                     estimate<shade::ggx<T>>, s, *bar));
        bar.reset();
        for (const auto& t : tables)
            std::fprintf(stderr,
                         "dielectric_albedo_tables: %s: largest node standard error %.2e, largest interpolation "
                         "difference %.2e (%.2e where mu >= 0.05: %.2e entering, %.2e exiting; the largest at %s); "
                         "table - estimate where mu >= 0.05 from %.2e to %.2e; envelope: %zu check points, %zu nodes "
                         "raised by at most %.2e in %d passes\n",
                         t.name.c_str(), t.max_error, t.max_interpolation, t.max_domain, t.max_side[0], t.max_side[1],
                         t.worst.c_str(), t.lowest, t.highest, t.checks, t.raised, t.max_raise, t.passes);
        header.write_stream([&](std::FILE* f) {
            write(f, tables, s);
        });
        std::fprintf(stderr, "dielectric_albedo_tables: wrote %s\n", s.out.string().c_str());
        return 0;
    });
}
