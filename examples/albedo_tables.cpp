// albedo_tables: computes the microfacet albedo tables of shade/brdf/microfacet/albedo_table.hpp
// with the models' own importance sampling and writes them as a header of constants.
//
//   albedo_tables --out include/shade/brdf/microfacet/detail/albedo_data.hpp
//
// Each node's E(mu, alpha) is shade::check::sampled_albedo of the single-scattering lobe
// (cook_torrance with k_s = 1, k_d = 0, height-correlated Smith, the walter form): the mean
// of the sampler's weight f (n·l) / pdf over strata^2 jittered visible-normal samples,
// with its standard error. E_avg is the exact average of the interpolated row
// (detail::albedo_row_average). Besides the nodes, the program evaluates E the same way
// at the centres of a sub-grid of cells and compares the interpolated table there: the
// largest difference, and the largest standard error, are written into the header as the
// table's stated accuracy.
//
//   albedo_tables --anisotropic --out include/shade/brdf/microfacet/detail/anisotropic_albedo_data.hpp
//
// writes instead the anisotropic corrections of shade/brdf/microfacet/anisotropic_albedo_table.hpp:
// at each node, Delta = E(w) - E_iso(mu, sqrt(alpha_x alpha_y)), E(w) estimated the same
// way for the anisotropic lobe and E_iso read from the committed isotropic table, and per
// (r, y) node the exact cosine-weighted average of the slice's interpolant.
//
//   albedo_tables --anisotropic-strong --out include/shade/brdf/microfacet/detail/anisotropic_strong_albedo_data.hpp
//
// writes the strong-anisotropy corrections of the same header (anisotropy beyond its
// ratio_max, to a 1-D rough surface): Delta_strong = E(w) - E_iso(mu, alpha_base) on that
// grid, the same estimates, plus its lift (strong_anisotropy_lift), and the rows' cosine
// averages.
//
//   albedo_tables --cosine-weights --strata 384 --out include/shade/brdf/microfacet/detail/cosine_weight_data.hpp
//
// writes instead the weights of the c nodes of shade/brdf/microfacet/cosine_weights.hpp
// (detail::ggx_cosine_weights at each node, a deterministic quadrature) and, as their stated
// accuracy, the largest difference at the cell centres with mu >= 0.1 between the table's
// sum for a few Fresnel factors (F = 1, dielectrics, thin films) and the quadrature itself.
//
//   albedo_tables --film-margin --strata 96 --out include/shade/brdf/microfacet/detail/thin_film_margin_data.hpp
//
// writes instead the margin of openpbr_surface's thin-film share: per film index and node of
// the cosine weights' grid, the largest shortfall of their read of a film's integral
// (run_film_margin).

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <thread>
#include <utility>
#include <vector>

#include <shade/brdf/microfacet/albedo_table.hpp>
#include <shade/brdf/microfacet/anisotropic_albedo_table.hpp>
#include <shade/brdf/microfacet/cosine_weights.hpp>
#include <shade/brdf/thin_film.hpp>
#include <shade/brdf/microfacet/detail/albedo_data.hpp>
#include <shade/check/energy.hpp>
#include <shade/shade.hpp>

#include "support/cli.hpp"
#include "support/float_literals.hpp"
#include "support/progress.hpp"

namespace ex = shade::examples;

namespace {

using T = double;

constexpr std::string_view usage = R"(usage: albedo_tables [--out FILE.hpp] [--nodes N] [--strata S] [--threads K] [--quiet]
       albedo_tables --anisotropic [--out FILE.hpp] [--strata S] [--threads K] [--quiet]
       albedo_tables --anisotropic-strong [--out FILE.hpp] [--strata S] [--threads K] [--quiet]
       albedo_tables --cosine-weights [--out FILE.hpp] [--strata S] [--threads K] [--quiet]
       albedo_tables --film-margin [--out FILE.hpp] [--strata S] [--sub Q] [--fine G] [--coarse-films] [--threads K] [--quiet]

Computes E(mu, alpha) and E_avg(alpha) of the single-scattering GGX and Beckmann lobes
with F = 1 and of the GGX lobe with the dielectric Fresnel of eta = 1.5, on an N x N grid
uniform in (c, sqrt(alpha)) (see albedo_table.hpp), each node from S^2 samples of the model's own
sampler, and writes the header of constants.

With --anisotropic, computes instead the corrections Delta = E(w) - E_iso(mu, sqrt(alpha_x
alpha_y)) of the anisotropic GGX and Beckmann lobes with F = 1 on the fixed grid of
anisotropic_albedo_table.hpp (S^2 samples per node) and their averages. With
--anisotropic-strong, the corrections Delta_strong = E(w) - E_iso(mu, alpha_base) of that
header's strong-anisotropy grid (alpha_max / alpha_min from its ratio_max to infinity).

With --cosine-weights, computes instead the weights w_k(mu, alpha) of the c nodes of the
GGX reflection lobe (cosine_weights.hpp) on its fixed grid, by the midpoint rule on S^2
cells of the visible-normal square, and their stated accuracy.

With --film-margin, computes instead the margin of openpbr_surface's thin-film share
(thin_film_margin_data.hpp): per film index and node of the cosine weights' grid, the
largest shortfall of the weights' read of the film's integral over the films' thickness
and base index (S^2 cells per point of a sub-grid of Q - 1 points inside each cell, the
measure deposited on G cosines).

  --cosine-weights write the cosine weights (default output cosine_weight_data.hpp)
  --film-margin   write the thin film's margin (default output thin_film_margin_data.hpp)
  --sub Q         with --film-margin: sub-grid points per cell and axis, 1 to 8 (default 2)
  --fine G        with --film-margin: fine cosines, 65 to 16385 (default 1025)
  --coarse-films  with --film-margin: a small set of films (a quick run, not for the header)
  --anisotropic   write the anisotropic corrections (default output anisotropic_albedo_data.hpp)
  --anisotropic-strong
                  write the strong-anisotropy corrections (default output
                  anisotropic_strong_albedo_data.hpp)
  --out FILE.hpp  output, a C++ header (.hpp or .h; default albedo_data.hpp)
  --nodes N       nodes per axis, 4 to 512 (default 128)
  --strata S      S^2 samples per node, 16 to 2048 (default 256)
  --threads K     worker threads, 1 to 64 (default 2)
  --quiet         no progress bar (it is drawn on stderr only when stderr is a terminal
                  and the run takes more than a second)
)";

struct settings {
    std::filesystem::path out = "albedo_data.hpp";
    std::size_t nodes = shade::detail::albedo_grid_nodes;
    std::size_t strata = 256;
    unsigned threads = 2;
    bool quiet = false;
    bool anisotropic = false;
    bool strong = false; // with anisotropic: the strong-anisotropy grid
    bool cosine_weights = false;
    bool film_margin = false;
};

// E(mu, alpha) estimated for one model family: make(alpha) builds the lobe.
using albedo_function = std::function<shade::check::albedo_sample<T>(double mu, double alpha, std::uint64_t seed)>;

template <class Make>
albedo_function family(Make make, std::size_t strata) {
    return [make, strata](double mu, double alpha, std::uint64_t seed) {
        shade::surface_point<T> at;
        at.shading = shade::frame<T>::from_normal_tangent({0, 0, 1}, {1, 0, 0});
        const auto model = make(alpha);
        // mu from the warp's inverse can round just above 1.
        const double c = std::min(mu, 1.0);
        const shade::vec3<T> v(std::sqrt((1 - c) * (1 + c)), 0, c);
        return shade::check::sampled_albedo(model, v, at, strata, seed);
    };
}

struct table {
    std::string name;      // C++ name prefix
    std::string what;      // one line for the comment
    std::vector<float> e;  // n x n, row j = alpha_j
    std::vector<float> average;
    double max_error = 0;  // largest standard error of a node
    double max_interpolation = 0; // largest |interpolated - estimated| at the check points
    double max_average = 0; // largest |interpolated E_avg - average of the interpolated E| between rows
    std::size_t worst_i = 0, worst_j = 0; // the cell of the largest interpolation difference
};

// Runs job(k) for k in [0, count) on `threads` threads.
void parallel_for(std::size_t count, unsigned threads, const std::function<void(std::size_t)>& job) {
    std::atomic<std::size_t> next{0};
    std::vector<std::thread> pool;
    for (unsigned t = 0; t < threads; ++t)
        pool.emplace_back([&] {
            for (std::size_t k = next++; k < count; k = next++) job(k);
        });
    for (auto& th : pool) th.join();
}

// The cells whose centres check the interpolation: every 4th cell along each axis, as
// (i, j) = (column along c, row along sqrt(alpha)).
std::vector<std::pair<std::size_t, std::size_t>> check_cells(std::size_t n) {
    std::vector<std::pair<std::size_t, std::size_t>> cells;
    for (std::size_t j = 0; j + 1 < n; j += 4)
        for (std::size_t i = 0; i + 1 < n; i += 4) cells.emplace_back(i, j);
    return cells;
}

// One table: n^2 node estimates and the interpolation check, one progress step each.
table compute(const std::string& name, const std::string& what, const albedo_function& albedo, const settings& s,
              ex::progress& bar) {
    namespace d = shade::detail;
    const std::size_t n = s.nodes;
    table out{name, what, std::vector<float>(n * n), std::vector<float>(n), 0, 0, 0, 0, 0};
    std::vector<double> errors(n * n);
    parallel_for(n * n, s.threads, [&](std::size_t k) {
        const std::size_t j = k / n, i = k % n;
        const double alpha = d::albedo_grid_alpha(j, n);
        const double mu = std::max(d::albedo_grid_mu(double(i) / double(n - 1), alpha), d::albedo_grid_mu_min);
        const auto a = albedo(mu, alpha, 1 + k);
        out.e[k] = float(std::min(a.albedo.x, 1.0));
        errors[k] = a.standard_error.x;
        bar.advance();
    });
    out.max_error = *std::max_element(errors.begin(), errors.end());
    for (std::size_t j = 0; j < n; ++j) out.average[j] = float(d::albedo_row_average(out.e.data() + j * n, n, d::albedo_grid_alpha(j, n)));
    // Interpolation check: the centre of every 4th cell along each axis (c and sqrt(alpha)
    // halfway between nodes), estimated afresh and compared.
    const auto cells = check_cells(n);
    std::vector<double> differences(cells.size());
    parallel_for(cells.size(), s.threads, [&](std::size_t k) {
        const auto [i, j] = cells[k];
        const double y = (double(j) + 0.5) / double(n - 1);
        const double alpha = std::max(y * y, d::albedo_grid_alpha_min);
        const double mu = std::max(d::albedo_grid_mu((double(i) + 0.5) / double(n - 1), alpha), d::albedo_grid_mu_min);
        const auto a = albedo(mu, alpha, 1000003 + k);
        differences[k] = std::abs(d::albedo_lookup(out.e.data(), n, mu, alpha) - a.albedo.x);
        bar.advance();
    });
    const auto worst = std::max_element(differences.begin(), differences.end());
    out.max_interpolation = *worst;
    const auto [wi, wj] = cells[std::size_t(worst - differences.begin())];
    // Consistency of E_avg between rows: at the middle of each row interval the table's
    // interpolant is the mean of the two rows, as a function of s at that alpha; its exact
    // average against the interpolated E_avg.
    std::vector<float> blend(n);
    for (std::size_t j = 0; j + 1 < n; ++j) {
        const double y = (double(j) + 0.5) / double(n - 1);
        const double alpha = std::max(y * y, d::albedo_grid_alpha_min);
        for (std::size_t i = 0; i < n; ++i) blend[i] = 0.5f * (out.e[j * n + i] + out.e[(j + 1) * n + i]);
        const double exact = d::albedo_row_average(blend.data(), n, alpha);
        out.max_average = std::max(out.max_average, std::abs(exact - d::albedo_average_lookup(out.average.data(), n, alpha)));
    }
    out.worst_i = wi;
    out.worst_j = wj;
    return out;
}

// x rounded to `digits` significant digits, as ex::write_float_literals writes it and the compiler
// reads it back: the averages are then computed from the values the header holds.
float as_written(double x, int digits) {
    char text[32];
    std::snprintf(text, sizeof text, "%.*g", digits, double(float(x)));
    return std::strtof(text, nullptr);
}

void write(std::FILE* f, const std::vector<table>& tables, const settings& s) {
    const std::size_t n = s.nodes;
    std::fprintf(f, "#pragma once\n");
    std::fprintf(f, "// Generated by examples/albedo_tables.cpp (--nodes %zu --strata %zu); do not edit by hand.\n", n,
                 s.strata);
    std::fprintf(f, "// The albedo tables of shade/brdf/microfacet/albedo_table.hpp (grid, interpolation, meaning):\n");
    std::fprintf(f, "// %zu x %zu nodes uniform in (c, sqrt(alpha)), row j = alpha_j, one row per line;\n", n, n);
    std::fprintf(f, "// each node the mean weight of %zu jittered samples of the lobe's own sampler.\n",
                 s.strata * s.strata);
    std::fprintf(f, "// Accuracy (measured by the generator, per table below): the largest standard error of a\n");
    std::fprintf(f, "// node, and the largest difference between the interpolated table and a fresh estimate at\n");
    std::fprintf(f, "// the centres of every 4th cell along each axis (interpolation plus both estimates' noise), and\n");
    std::fprintf(f, "// the largest difference between the interpolated E_avg and the exact average of the\n");
    std::fprintf(f, "// interpolated E halfway between rows.\n\n");
    std::fprintf(f, "namespace shade::detail {\n");
    for (const auto& t : tables) {
        std::fprintf(f, "\n/// E(mu, alpha) of %s.\n", t.what.c_str());
        std::fprintf(f, "/// Node standard error <= %.1e; interpolated vs estimated at cell centres <= %.1e;\n", t.max_error,
                     t.max_interpolation);
        std::fprintf(f, "/// E_avg consistency <= %.1e.\n", t.max_average);
        std::fprintf(f, "inline constexpr float %s[%zu * %zu] = {\n", t.name.c_str(), n, n);
        for (std::size_t j = 0; j < n; ++j) {
            ex::write_float_literals(f, t.e.data() + j * n, n);
            std::fprintf(f, ",\n");
        }
        std::fprintf(f, "};\n\n/// E_avg(alpha) of %s.\n", t.what.c_str());
        std::fprintf(f, "inline constexpr float %s_average[%zu] = {\n", t.name.c_str(), n);
        ex::write_float_literals(f, t.average.data(), n);
        std::fprintf(f, "};\n");
    }
    std::fprintf(f, "\n} // namespace shade::detail\n");
}

// The anisotropic correction of one distribution family: make(alpha_x, alpha_y) builds the
// single-scattering lobe, iso is the committed isotropic table it is corrected from.
struct anisotropic_table {
    std::string name;
    std::string what;
    std::vector<float> delta;   // anisotropic_albedo_size values
    std::vector<float> average; // ratio_nodes x roughness_nodes
    double max_error = 0;       // largest standard error of a node
    double max_delta = 0;       // largest |Delta|
};

using anisotropic_albedo =
    std::function<shade::check::albedo_sample<T>(const shade::vec3<T>& v, double alpha_x, double alpha_y, std::uint64_t seed)>;

template <class Make>
anisotropic_albedo anisotropic_family(Make make, std::size_t strata) {
    return [make, strata](const shade::vec3<T>& v, double alpha_x, double alpha_y, std::uint64_t seed) {
        shade::surface_point<T> at;
        at.shading = shade::frame<T>::from_normal_tangent({0, 0, 1}, {1, 0, 0});
        return shade::check::sampled_albedo(make(alpha_x, alpha_y), v, at, strata, seed);
    };
}

anisotropic_table compute_anisotropic(const std::string& name, const std::string& what, const float* iso,
                                      const anisotropic_albedo& albedo, const settings& s, ex::progress& bar) {
    namespace d = shade::detail;
    constexpr std::size_t nx = d::anisotropic_albedo_mu_nodes, ns = d::anisotropic_albedo_azimuth_nodes;
    constexpr std::size_t ny = d::anisotropic_albedo_roughness_nodes, nr = d::anisotropic_albedo_ratio_nodes;
    anisotropic_table out{name, what, std::vector<float>(d::anisotropic_albedo_size, 0.0f), std::vector<float>(d::anisotropic_albedo_rows, 0.0f), 0, 0};
    std::vector<double> errors(d::anisotropic_albedo_size, 0.0);
    parallel_for(d::anisotropic_albedo_size, s.threads, [&](std::size_t index) {
        const std::size_t i = index % nx, si = (index / nx) % ns, j = (index / d::anisotropic_albedo_slice) % ny,
                          k = index / (d::anisotropic_albedo_slice * ny);
        // r = 0 (isotropic) and y = 0 (a mirror) hold 0 by definition.
        if (k > 0 && j > 0) {
            const double y = double(j) / double(ny - 1);
            const double alpha = y * y;
            const double ratio = std::pow(d::anisotropic_albedo_ratio_max, double(k) / double(nr - 1));
            const double x = double(i) / double(nx - 1);
            const double mu = std::min(std::max(x * x, d::albedo_grid_mu_min), 1.0);
            // s = sin^2(phi) of the node's u: u = ln(1 + (q^2 - 1) s) / ln(q^2).
            const double u = double(si) / double(ns - 1);
            const double sin2 = std::min(std::expm1(u * 2 * std::log(ratio)) / ((ratio - 1) * (ratio + 1)), 1.0);
            const double sin_theta = std::sqrt((1 - mu) * (1 + mu));
            const shade::vec3<T> v(sin_theta * std::sqrt(1 - sin2), sin_theta * std::sqrt(sin2), mu);
            // The seed depends on (k, j, i) only: the pole column (mu = 1) is then the same
            // estimate for every s, as Delta there is.
            const auto a = albedo(v, alpha / std::sqrt(ratio), alpha * std::sqrt(ratio), 1 + (k * ny + j) * nx + i);
            const double e = std::min(a.albedo.x, 1.0);
            out.delta[index] = as_written(e - d::albedo_lookup(iso, d::albedo_grid_nodes, mu, alpha), 5);
            errors[index] = a.standard_error.x;
        }
        bar.advance();
    });
    out.max_error = *std::max_element(errors.begin(), errors.end());
    for (const float x : out.delta) out.max_delta = std::max(out.max_delta, double(std::abs(x)));
    for (std::size_t n = 0; n < d::anisotropic_albedo_rows; ++n)
        out.average[n] = float(d::anisotropic_albedo_row_average(out.delta.data() + n * nx));
    return out;
}

// The strong-anisotropy correction of one distribution family (anisotropic_albedo_table.hpp's
// second grid): Delta_strong = E(w) - E_iso(mu, alpha_base) at every node, the lobe's smoother
// axis along t (alpha_x = alpha_min) and w's azimuth from it.
anisotropic_table compute_strong(const std::string& name, const std::string& what, const float* iso,
                                 const anisotropic_albedo& albedo, const settings& s, ex::progress& bar) {
    namespace d = shade::detail;
    constexpr std::size_t nx = d::strong_anisotropy_mu_nodes, nu = d::strong_anisotropy_azimuth_nodes;
    constexpr std::size_t ny = d::strong_anisotropy_roughness_nodes;
    anisotropic_table out{name, what, std::vector<float>(d::strong_anisotropy_size, 0.0f),
                          std::vector<float>(d::strong_anisotropy_rows, 0.0f), 0, 0};
    std::vector<double> errors(d::strong_anisotropy_size, 0.0);
    parallel_for(d::strong_anisotropy_size, s.threads, [&](std::size_t index) {
        const std::size_t i = index % nx, iu = (index / nx) % nu, j = (index / d::strong_anisotropy_slice) % ny,
                          k = index / (d::strong_anisotropy_slice * ny);
        // y = 0 (a mirror) holds 0.
        if (j > 0) {
            const double y = double(j) / double(ny - 1), z = double(k) / double(d::strong_anisotropy_ratio_nodes - 1);
            const double alpha_max = y * y * d::strong_anisotropy_alpha_top;
            // z = 0 is a 1-D rough surface; its lobe is estimated at alpha_min = 1e-7 alpha_max.
            const double alpha_min = alpha_max * std::max(z * z / d::anisotropic_albedo_ratio_max, 1e-7);
            const double x = double(i) / double(nx - 1);
            const double mu = std::min(std::max(x * x, d::albedo_grid_mu_min), 1.0);
            const double phi = d::strong_anisotropy_phi(double(iu) / double(nu - 1));
            const double sin_theta = std::sqrt((1 - mu) * (1 + mu));
            const shade::vec3<T> v(sin_theta * std::cos(phi), sin_theta * std::sin(phi), mu);
            // The seed depends on (k, j, i) only: the pole column (mu = 1) is then the same
            // estimate for every u, as Delta there is.
            const auto a = albedo(v, alpha_min, alpha_max, 1 + (k * ny + j) * nx + i);
            const double e = std::min(a.albedo.x, 1.0);
            const double base = d::anisotropic_albedo_base_alpha(alpha_min, alpha_max);
            const double lift = d::strong_anisotropy_lift * (1 - e);
            out.delta[index] = as_written(e - d::albedo_lookup(iso, d::albedo_grid_nodes, mu, base) + lift, 5);
            errors[index] = a.standard_error.x;
        }
        bar.advance();
    });
    out.max_error = *std::max_element(errors.begin(), errors.end());
    for (const float x : out.delta) out.max_delta = std::max(out.max_delta, double(std::abs(x)));
    for (std::size_t n = 0; n < d::strong_anisotropy_rows; ++n)
        out.average[n] = float(d::anisotropic_albedo_row_average(out.delta.data() + n * nx));
    return out;
}

// The header of --anisotropic (strong false: the first grid of anisotropic_albedo_table.hpp)
// or --anisotropic-strong (its strong-anisotropy grid).
void write_anisotropic(std::FILE* f, const std::vector<anisotropic_table>& tables, const settings& s) {
    namespace d = shade::detail;
    const bool strong = s.strong;
    const std::size_t nx = strong ? d::strong_anisotropy_mu_nodes : d::anisotropic_albedo_mu_nodes;
    const std::size_t nu = strong ? d::strong_anisotropy_azimuth_nodes : d::anisotropic_albedo_azimuth_nodes;
    const std::size_t rows = strong ? d::strong_anisotropy_rows : d::anisotropic_albedo_rows;
    std::fprintf(f, "#pragma once\n");
    std::fprintf(f, "// Generated by examples/albedo_tables.cpp (%s --strata %zu); do not edit by hand.\n",
                 strong ? "--anisotropic-strong" : "--anisotropic", s.strata);
    std::fprintf(f, "// The %s of shade/brdf/microfacet/anisotropic_albedo_table.hpp (grid,\n",
                 strong ? "strong-anisotropy corrections" : "anisotropic corrections");
    std::fprintf(f, "// interpolation, meaning): %zu (%s) x %zu (y) slices of %zu (%s) x %zu (x) nodes, one %s row per\n",
                 strong ? d::strong_anisotropy_ratio_nodes : d::anisotropic_albedo_ratio_nodes, strong ? "z" : "r",
                 strong ? d::strong_anisotropy_roughness_nodes : d::anisotropic_albedo_roughness_nodes, nu,
                 strong ? "u" : "s", nx, strong ? "u" : "s");
    std::fprintf(f, "// line; each node E(w), the mean weight of %zu jittered samples of the lobe's own sampler,\n",
                 s.strata * s.strata);
    if (strong) {
        std::fprintf(f, "// minus the isotropic table (albedo_data.hpp) at the base roughness alpha_base, plus the lift\n");
        std::fprintf(f, "// strong_anisotropy_lift (1 - E), strong_anisotropy_lift = %g, written with 5 significant digits\n",
                     d::strong_anisotropy_lift);
        std::fprintf(f, "// (|Delta| < 1, so within 1e-5, far below the node noise).\n\n");
    } else {
        std::fprintf(f, "// minus the isotropic table (albedo_data.hpp) at the geometric-mean roughness, written with 5\n");
        std::fprintf(f, "// significant digits (|Delta| < 1, so within 1e-5, far below the node noise).\n\n");
    }
    std::fprintf(f, "#include <shade/brdf/microfacet/anisotropic_albedo_table.hpp>\n\n");
    std::fprintf(f, "namespace shade::detail {\n");
    for (const auto& t : tables) {
        std::fprintf(f, "\n/// %s of %s.\n", strong ? "Delta_strong(w)" : "Delta(w)", t.what.c_str());
        std::fprintf(f, "/// Node standard error <= %.1e; |%s| <= %.3f.\n", t.max_error, strong ? "Delta_strong" : "Delta",
                     t.max_delta);
        std::fprintf(f, "inline constexpr float %s[%s] = {\n", t.name.c_str(),
                     strong ? "strong_anisotropy_size" : "anisotropic_albedo_size");
        for (std::size_t row = 0; row < t.delta.size() / nx; ++row) {
            ex::write_float_literals(f, t.delta.data() + row * nx, nx, 5);
            std::fprintf(f, ",\n");
        }
        std::fprintf(f, "};\n\n/// The cosine averages of the rows of %s (anisotropic_albedo_row_average), one slice per line.\n",
                     t.name.c_str());
        std::fprintf(f, "inline constexpr float %s_average[%s] = {\n", t.name.c_str(),
                     strong ? "strong_anisotropy_rows" : "anisotropic_albedo_rows");
        for (std::size_t k = 0; k < rows / nu; ++k) {
            ex::write_float_literals(f, t.average.data() + k * nu, nu);
            std::fprintf(f, ",\n");
        }
        std::fprintf(f, "};\n");
    }
    std::fprintf(f, "\n} // namespace shade::detail\n");
}

// --cosine-weights: the GGX reflection lobe's weights of the c nodes
// (shade/brdf/microfacet/cosine_weights.hpp), written to `header`. The stated accuracy: at
// the centre of every cell with mu >= 0.1 (halfway in x = mu^(2/3) and in sqrt(alpha)), the
// row built from the new table (sum of the weights interpolated bilinearly times F at the
// nodes) against the same quadrature with F read at every sample's own cosine, for the
// Fresnel factors of check_fresnels (F = 1, a dielectric, and thin films less the
// dielectric of their base, the difference openpbr_surface sums); the range of the difference
// per factor.
struct check_fresnel {
    std::string what;
    std::vector<double> fine; // F on 4097 cosines uniform in [0, 1], interpolated linearly
    [[nodiscard]] double operator()(double c) const {
        const double x = std::clamp(c, 0.0, 1.0) * double(fine.size() - 1);
        const std::size_t k = std::min(std::size_t(x), fine.size() - 2);
        const double t = x - double(k);
        return (1 - t) * fine[k] + t * fine[k + 1];
    }
};

std::vector<check_fresnel> check_fresnels() {
    using namespace shade;
    std::vector<check_fresnel> out;
    const auto add = [&](std::string what, const std::function<double(double)>& F) {
        check_fresnel f{std::move(what), std::vector<double>(4097)};
        for (std::size_t k = 0; k < f.fine.size(); ++k) f.fine[k] = F(double(k) / double(f.fine.size() - 1));
        out.push_back(std::move(f));
    };
    add("F = 1", [](double) { return 1.0; });
    add("dielectric eta 1.5", [](double c) { return F_dielectric(c, 1.5); });
    for (const auto& [film_ior, thickness] : {std::pair{1.1, 300.0}, {1.4, 500.0}, {2.0, 800.0}, {3.0, 1000.0}}) {
        const auto film = thin_film_fresnel<double>::over_dielectric(1.5, film_ior, thickness);
        char what[96];
        std::snprintf(what, sizeof what, "film %.1f, %.0f nm over 1.5 minus dielectric 1.5 (green)", film_ior, thickness);
        add(what, [film](double c) { return film.F(c).y - F_dielectric(c, 1.5); });
    }
    return out;
}

int run_cosine_weights(const settings& s, ex::output_file& header) {
    namespace d = shade::detail;
    constexpr std::size_t n = d::cosine_weight_nodes, m = d::cosine_weight_alpha_nodes;
    std::vector<double> table(m * n * n);
    const std::vector<check_fresnel> fresnels = check_fresnels();
    std::vector<std::pair<std::size_t, std::size_t>> cells; // (mu cell i, alpha cell j)
    for (std::size_t j = 0; j + 1 < m; ++j)
        for (std::size_t i = 0; i + 1 < n; ++i) {
            const double x = (double(i) + 0.5) / double(n - 1);
            if (x * std::sqrt(x) >= 0.1) cells.emplace_back(i, j);
        }
    std::optional<ex::progress> bar(std::in_place, "albedo_tables", m * n + cells.size(), !s.quiet);
    parallel_for(m * n, s.threads, [&](std::size_t k) {
        const std::size_t j = k / n, i = k % n;
        d::ggx_cosine_weights(d::cosine_weight_node(i), d::cosine_weight_alpha(j), s.strata, table.data() + k * n);
        bar->advance();
    });
    std::vector<std::vector<double>> differences(cells.size(), std::vector<double>(fresnels.size()));
    parallel_for(cells.size(), s.threads, [&](std::size_t q) {
        const auto [i, j] = cells[q];
        const double x = (double(i) + 0.5) / double(n - 1), r = (double(j) + 0.5) / double(m - 1);
        const double mu = x * std::sqrt(x), alpha = r * r;
        std::vector<double> fresh(fresnels.size(), 0.0);
        d::visit_ggx_cosine_measure(mu, alpha, s.strata, [&](double c, double w) {
            for (std::size_t f = 0; f < fresnels.size(); ++f) fresh[f] += w * fresnels[f](c);
        });
        for (std::size_t f = 0; f < fresnels.size(); ++f) {
            double row = 0;
            for (std::size_t a = 0; a < 2; ++a)
                for (std::size_t b = 0; b < 2; ++b)
                    for (std::size_t k = 0; k < n; ++k)
                        row += 0.25 * table[((j + a) * n + i + b) * n + k] * fresnels[f](d::cosine_weight_node(k));
            differences[q][f] = row - fresh[f];
        }
        bar->advance();
    });
    bar.reset();
    std::vector<double> lowest(fresnels.size(), 0.0), highest(fresnels.size(), 0.0);
    for (const auto& row : differences)
        for (std::size_t f = 0; f < fresnels.size(); ++f) {
            lowest[f] = std::min(lowest[f], row[f]);
            highest[f] = std::max(highest[f], row[f]);
        }
    std::vector<float> values(table.begin(), table.end());
    header.write_stream([&](std::FILE* f) {
        std::fprintf(f, "#pragma once\n");
        std::fprintf(f, "// Generated by examples/albedo_tables.cpp (--cosine-weights --strata %zu); do not edit by hand.\n", s.strata);
        std::fprintf(f, "// The weights of shade/brdf/microfacet/cosine_weights.hpp (grid, meaning: detail::ggx_cosine_weights,\n");
        std::fprintf(f, "// the midpoint rule on %zu^2 cells of the visible-normal square): %zu rows of alpha, each %zu\n", s.strata, m, n);
        std::fprintf(f, "// views mu_i, each %zu weights of the c nodes, one view per line.\n", n);
        std::fprintf(f, "// Accuracy (measured by the generator): at the centre of each cell with mu >= 0.1, the\n");
        std::fprintf(f, "// table's sum_k w_k F(c_k) (bilinear in x = mu^(2/3) and sqrt(alpha)) minus the same\n");
        std::fprintf(f, "// quadrature with F at each sample's own cosine, the range of the difference per Fresnel factor:\n");
        for (std::size_t k = 0; k < fresnels.size(); ++k)
            std::fprintf(f, "//   %-70s [%+.2e, %+.2e]\n", fresnels[k].what.c_str(), lowest[k], highest[k]);
        std::fprintf(f, "\n#include <cstddef>\n\nnamespace shade::detail {\n\n");
        std::fprintf(f, "inline constexpr std::size_t cosine_weight_nodes = %zu;       ///< nodes in c and in mu\n", n);
        std::fprintf(f, "inline constexpr std::size_t cosine_weight_alpha_nodes = %zu; ///< rows in sqrt(alpha)\n\n", m);
        std::fprintf(f, "/// w_k(mu_i, alpha_j) at [(j n + i) n + k], n = cosine_weight_nodes.\n");
        std::fprintf(f, "inline constexpr float cosine_weight_table[cosine_weight_alpha_nodes * cosine_weight_nodes * cosine_weight_nodes] = {\n");
        for (std::size_t row = 0; row < m * n; ++row) {
            ex::write_float_literals(f, values.data() + row * n, n, 6);
            std::fprintf(f, ",\n");
        }
        std::fprintf(f, "};\n\n} // namespace shade::detail\n");
    });
    for (std::size_t k = 0; k < fresnels.size(); ++k)
        std::fprintf(stderr, "albedo_tables: cosine weights, %s: [%+.2e, %+.2e]\n", fresnels[k].what.c_str(), lowest[k],
                     highest[k]);
    std::fprintf(stderr, "albedo_tables: wrote %s\n", s.out.string().c_str());
    return 0;
}

// --film-margin: the thin film's margin of openpbr_surface's film share (see
// detail/thin_film_margin_data.hpp), written to `header`. For each point of a sub-grid with
// q - 1 points inside each cell per axis (in x = mu^(2/3) and in sqrt(alpha)) the functional
// L(f) = (the table's read of f: sum_k w_k f(c_k), bilinear in x and sqrt(alpha)) minus
// (the integral of f against the lobe's measure of c = v·h: detail::visit_ggx_cosine_measure
// on S^2 cells, deposited linearly on a fine grid of G cosines uniform in [0, 1], f read
// at the grid points) is taken of each film's Delta = F_film - F (F the dielectric Fresnel of
// the film's base index, per RGB channel) and of the dielectric Fresnel F(eta) itself. Per
// film index f of the grid (film_iors), the under-read at the point is
//     u_f = max over films of index f (every thickness, base, channel) of -L(Delta)
//           [+ max over (base s, ratio e) of -(L(F_s) - L(F_e)) in table 1]
// (F_1 = 0: e = 1 stands for the rows that sum F_film alone, eta'_s <= 1), and the margin
// of a node is the largest u_f over the points of the (up to four) cells around it, plus
// `safety`: the bilinear read of the margins then exceeds u_f at every sub-grid point.
struct film_margin_settings {
    std::size_t fine = 1025; // G
    std::size_t q = 2;       // sub-grid points per cell and axis
    double safety = 1e-4;
    bool coarse = false;     // a quick subset of films (for the CLI test)
};

std::vector<double> film_thicknesses_um(bool coarse) {
    if (coarse) return {0.1, 0.5, 1, 2, 3};
    std::vector<double> out;
    for (int k = 1; k <= 120; ++k) out.push_back(0.025 * k); // 0.025 .. 3 um
    for (int k = 1; k <= 28; ++k) out.push_back(3 + 0.25 * k); // .. 10 um
    return out;
}
std::vector<double> film_iors(bool coarse) {
    if (coarse) return {1.0, 1.5, 3};
    return {1.0, 1.01, 1.02, 1.035, 1.05, 1.075, 1.1, 1.15, 1.2, 1.3, 1.45, 1.6, 1.8, 2.0, 2.3, 2.6, 3.0};
}
std::vector<double> film_bases(bool coarse) {
    if (coarse) return {1.5};
    return {1.0, 1.2, 1.33, 1.5, 1.75, 2.0, 2.5, 3.0};
}
std::vector<double> film_ratios() {
    return {1.0, 1.02, 1.05, 1.1, 1.15, 1.2, 1.3, 1.4, 1.5, 1.6, 1.8, 2.0, 2.25, 2.5, 3.0};
}

struct margin_point {
    double sa = 0, x = 0;          // sqrt(alpha), mu^(2/3)
    std::array<double, shade::detail::cosine_weight_nodes> read{}; // the table's weights at the point
    std::size_t g0 = 0;            // first fine index of `fine`
    std::vector<double> fine;      // the measure deposited on the fine grid from g0
};

// L(f) at point p for f given at the nodes and on the fine grid.
double margin_functional(const margin_point& p, const double* nodes, const double* fine) {
    double read = 0, fresh = 0;
    for (std::size_t k = 0; k < p.read.size(); ++k) read += p.read[k] * nodes[k];
    for (std::size_t g = 0; g < p.fine.size(); ++g) fresh += p.fine[g] * fine[p.g0 + g];
    return read - fresh;
}

int run_film_margin(const settings& s, const film_margin_settings& fm, ex::output_file& header) {
    namespace d = shade::detail;
    using namespace shade;
    constexpr std::size_t n = d::cosine_weight_nodes, m = d::cosine_weight_alpha_nodes;
    const std::size_t G = fm.fine, q = fm.q;
    const std::size_t px = q * (n - 1) + 1, pa = q * (m - 1) + 1; // sub-grid points per axis
    std::vector<margin_point> points(px * pa);
    std::optional<ex::progress> bar(std::in_place, "albedo_tables", points.size(), !s.quiet);
    parallel_for(points.size(), s.threads, [&](std::size_t index) {
        margin_point& p = points[index];
        const std::size_t a = index / px, b = index % px;
        p.sa = double(a) / double(pa - 1);
        p.x = double(b) / double(px - 1);
        const double alpha = p.sa * p.sa, mu = p.x * std::sqrt(p.x);
        // The read: fresnel_albedo_row's interpolation in sqrt(alpha), then at()'s in x.
        const double ra = p.sa * double(m - 1);
        const std::size_t j = std::min(std::size_t(ra), m - 2);
        const double ta = ra - double(j);
        const double rx = p.x * double(n - 1);
        const std::size_t i = std::min(std::size_t(rx), n - 2);
        const double tx = rx - double(i);
        for (std::size_t k = 0; k < n; ++k) {
            const auto w = [&](std::size_t jj, std::size_t ii) { return double(d::cosine_weight_table[(jj * n + ii) * n + k]); };
            const double lower = (1 - ta) * w(j, i) + ta * w(j + 1, i);
            const double upper = (1 - ta) * w(j, i + 1) + ta * w(j + 1, i + 1);
            p.read[k] = (1 - tx) * lower + tx * upper;
        }
        std::vector<double> fine(G, 0.0);
        std::size_t lo = G, hi = 0;
        d::visit_ggx_cosine_measure(mu, alpha, s.strata, [&](double c, double weight) {
            const double y = std::clamp(c, 0.0, 1.0) * double(G - 1);
            const std::size_t g = std::min(std::size_t(y), G - 2);
            const double t = y - double(g);
            fine[g] += weight * (1 - t);
            fine[g + 1] += weight * t;
            lo = std::min(lo, g);
            hi = std::max(hi, g + 1);
        });
        if (lo > hi) lo = hi = 0;
        p.g0 = lo;
        p.fine.assign(fine.begin() + std::ptrdiff_t(lo), fine.begin() + std::ptrdiff_t(hi + 1));
        bar->advance();
    });
    // A function on the nodes and the fine grid.
    struct sampled {
        std::vector<double> nodes, fine;
    };
    const auto sample = [&](const std::function<double(double)>& f) {
        sampled out{std::vector<double>(n), std::vector<double>(G)};
        for (std::size_t k = 0; k < n; ++k) out.nodes[k] = f(d::cosine_weight_node(k));
        for (std::size_t g = 0; g < G; ++g) out.fine[g] = f(double(g) / double(G - 1));
        return out;
    };
    // Dielectric part: L(F_e) per point for every base and ratio.
    std::vector<double> indices = film_bases(fm.coarse);
    for (const double e : film_ratios()) indices.push_back(e);
    std::vector<std::vector<double>> dielectric(indices.size(), std::vector<double>(points.size()));
    parallel_for(indices.size(), s.threads, [&](std::size_t k) {
        const double e = indices[k];
        const sampled f = sample([e](double c) { return e == 1.0 ? 0.0 : F_dielectric(c, e); });
        for (std::size_t p = 0; p < points.size(); ++p)
            dielectric[k][p] = margin_functional(points[p], f.nodes.data(), f.fine.data());
    });
    const std::size_t bases = film_bases(fm.coarse).size();
    std::vector<double> under(points.size(), -1.0), over(points.size(), -1.0);
    for (std::size_t p = 0; p < points.size(); ++p)
        for (std::size_t a = 0; a < bases; ++a)
            for (std::size_t b = bases; b < indices.size(); ++b) {
                const double difference = dielectric[a][p] - dielectric[b][p];
                under[p] = std::max(under[p], -difference);
                over[p] = std::max(over[p], difference);
            }
    // Film part: max of -L(Delta) and of L(Delta) per film index and point over the films
    // of that index and the channels.
    struct film {
        std::size_t ior_index;
        double ior, thickness_um, base;
    };
    const std::vector<double> iors = film_iors(fm.coarse);
    const std::size_t fi = iors.size();
    std::vector<film> films;
    for (std::size_t f = 0; f < fi; ++f)
        for (const double base : film_bases(fm.coarse))
            for (const double t : film_thicknesses_um(fm.coarse)) films.push_back({f, iors[f], t, base});
    std::vector<std::vector<double>> film_under(fi, std::vector<double>(points.size(), 0.0)),
        film_over(fi, std::vector<double>(points.size(), 0.0));
    std::mutex merge;
    bar.emplace("albedo_tables", films.size(), !s.quiet);
    parallel_for(films.size(), s.threads, [&](std::size_t k) {
        const film fl = films[k];
        const auto F = thin_film_fresnel<double>::over_dielectric(fl.base, fl.ior, fl.thickness_um * 1000);
        std::array<sampled, 3> channels;
        {
            std::vector<rgb<double>> nodes(n), fine(G);
            for (std::size_t i = 0; i < n; ++i) nodes[i] = F.F(d::cosine_weight_node(i));
            for (std::size_t g = 0; g < G; ++g) fine[g] = F.F(double(g) / double(G - 1));
            for (int ch = 0; ch < 3; ++ch) {
                channels[std::size_t(ch)] = {std::vector<double>(n), std::vector<double>(G)};
                for (std::size_t i = 0; i < n; ++i)
                    channels[std::size_t(ch)].nodes[i] = nodes[i][ch] - F_dielectric(d::cosine_weight_node(i), fl.base);
                for (std::size_t g = 0; g < G; ++g)
                    channels[std::size_t(ch)].fine[g] = fine[g][ch] - F_dielectric(double(g) / double(G - 1), fl.base);
            }
        }
        std::vector<double> lo(points.size(), 0.0), hi(points.size(), 0.0);
        for (std::size_t p = 0; p < points.size(); ++p)
            for (int ch = 0; ch < 3; ++ch) {
                const double l = margin_functional(points[p], channels[std::size_t(ch)].nodes.data(), channels[std::size_t(ch)].fine.data());
                lo[p] = std::max(lo[p], -l);
                hi[p] = std::max(hi[p], l);
            }
        const std::lock_guard<std::mutex> lock(merge);
        for (std::size_t p = 0; p < points.size(); ++p) {
            film_under[fl.ior_index][p] = std::max(film_under[fl.ior_index][p], lo[p]);
            film_over[fl.ior_index][p] = std::max(film_over[fl.ior_index][p], hi[p]);
        }
        bar->advance();
    });
    bar.reset();
    // Node margins: the largest under-read over the points of the cells around the node;
    // table 0 for eta'_s equal to the film's base index (no dielectric pair), table 1 for
    // any; one pair of tables per film index.
    std::vector<float> margin(fi * 2 * m * n, 0.0f);
    const auto node_margin = [&](std::size_t f, int t, std::size_t j, std::size_t i) -> float& {
        return margin[((f * 2 + std::size_t(t)) * m + j) * n + i];
    };
    for (std::size_t f = 0; f < fi; ++f)
        for (int t = 0; t < 2; ++t)
            for (std::size_t j = 0; j < m; ++j)
                for (std::size_t i = 0; i < n; ++i) {
                    double worst = 0;
                    for (std::size_t a = (j == 0 ? 0 : q * j - q); a <= std::min(q * j + q, pa - 1); ++a)
                        for (std::size_t b = (i == 0 ? 0 : q * i - q); b <= std::min(q * i + q, px - 1); ++b) {
                            const std::size_t p = a * px + b;
                            worst = std::max(worst, film_under[f][p] + (t == 1 ? std::max(under[p], 0.0) : 0.0));
                        }
                    node_margin(f, t, j, i) = float(worst > 0 ? worst + fm.safety : 0.0);
                }
    // The resulting range of read - true at the sub-grid points (mu >= 0.1 and all), per
    // film index and table.
    std::vector<std::string> summary;
    for (std::size_t f = 0; f < fi; ++f)
        for (int t = 0; t < 2; ++t) {
            double lowest[2] = {1, 1}, highest[2] = {-1, -1}, before_low[2] = {1, 1}, before_high[2] = {-1, -1};
            for (std::size_t p = 0; p < points.size(); ++p) {
                const margin_point& pt = points[p];
                const double ra = pt.sa * double(m - 1), rx = pt.x * double(n - 1);
                const std::size_t j = std::min(std::size_t(ra), m - 2), i = std::min(std::size_t(rx), n - 2);
                const double ta = ra - double(j), tx = rx - double(i);
                const auto M = [&](std::size_t jj, std::size_t ii) { return double(node_margin(f, t, jj, ii)); };
                const double read = (1 - tx) * ((1 - ta) * M(j, i) + ta * M(j + 1, i)) +
                                    tx * ((1 - ta) * M(j, i + 1) + ta * M(j + 1, i + 1));
                const double u = film_under[f][p] + (t == 1 ? std::max(under[p], 0.0) : 0.0);
                const double o = film_over[f][p] + (t == 1 ? std::max(over[p], 0.0) : 0.0);
                for (int set = 0; set < 2; ++set) {
                    if (set == 0 && pt.x * std::sqrt(pt.x) < 0.1) continue;
                    before_low[set] = std::min(before_low[set], -u);
                    before_high[set] = std::max(before_high[set], o);
                    lowest[set] = std::min(lowest[set], read - u);
                    highest[set] = std::max(highest[set], read + o);
                }
            }
            char line[240];
            std::snprintf(line, sizeof line,
                          "film %.3f, table %d: without the margin [%+.2e, %+.2e] (mu >= 0.1), [%+.2e, %+.2e] (all mu); "
                          "with it [%+.2e, %+.2e], [%+.2e, %+.2e]",
                          iors[f], t, before_low[0], before_high[0], before_low[1], before_high[1], lowest[0],
                          highest[0], lowest[1], highest[1]);
            summary.emplace_back(line);
        }
    char counts[200];
    std::snprintf(counts, sizeof counts, "%zu films x 3 channels, %zu dielectric indices, %zu points, S = %zu, G = %zu",
                  films.size(), indices.size(), points.size(), s.strata, G);
    const std::vector<double> thicknesses = film_thicknesses_um(fm.coarse), base_list = film_bases(fm.coarse);
    header.write_stream([&](std::FILE* f) {
        std::fprintf(f, "#pragma once\n");
        std::fprintf(f, "// Generated by examples/albedo_tables.cpp (--film-margin --strata %zu --fine %zu --sub %zu%s); do not edit by hand.\n",
                     s.strata, G, q, fm.coarse ? " --coarse-films" : "");
        std::fprintf(f, "// The thin film's margin of openpbr_surface's film share (albedo_tables.cpp, run_film_margin):\n");
        std::fprintf(f, "// per film index n_f of the grid and node (alpha_j, mu_i) of cosine_weight_data.hpp, the\n");
        std::fprintf(f, "// largest amount by which the table's read of the integral of F_film - F(eta) against the\n");
        std::fprintf(f, "// lobe's measure of c = v.h falls short of the integral itself, over the films of index n_f\n");
        std::fprintf(f, "// (thickness %.3f-%.2f um in %zu steps, base index %.2f-%.2f in %zu, every RGB channel) and the\n",
                     thicknesses.front(), thicknesses.back(), thicknesses.size(), base_list.front(), base_list.back(),
                     base_list.size());
        std::fprintf(f, "// points of the cells around the node, plus %.1e. Table 0: eta = the film's base index;\n", fm.safety);
        std::fprintf(f, "// table 1: any eta in [1, %.1f] (1: the row sums F_film alone). Measured by the generator\n",
                     film_ratios().back());
        std::fprintf(f, "// (%s), E_R read - true at the sub-grid points:\n", counts);
        for (const auto& line : summary) std::fprintf(f, "//   %s\n", line.c_str());
        std::fprintf(f, "\n#include <cstddef>\n\nnamespace shade::detail {\n\n");
        std::fprintf(f, "/// The film indices of the margin's tables (ascending).\n");
        std::fprintf(f, "inline constexpr std::size_t thin_film_margin_iors = %zu;\n", fi);
        std::fprintf(f, "inline constexpr double thin_film_margin_ior[thin_film_margin_iors] = {");
        for (std::size_t k = 0; k < fi; ++k) std::fprintf(f, "%s%.3f", k ? ", " : "", iors[k]);
        std::fprintf(f, "};\n\n");
        std::fprintf(f, "/// The margins of film index f, table t, at [(f 2 + t) m n + j n + i], n = cosine_weight_nodes,\n");
        std::fprintf(f, "/// m = cosine_weight_alpha_nodes; one alpha row per line.\n");
        std::fprintf(f, "inline constexpr float thin_film_albedo_margin[thin_film_margin_iors * 2 * %zu] = {\n", m * n);
        for (std::size_t row = 0; row < fi * 2 * m; ++row) {
            ex::write_float_literals(f, margin.data() + row * n, n, 4);
            std::fprintf(f, ",\n");
        }
        std::fprintf(f, "};\n\n} // namespace shade::detail\n");
    });
    for (const auto& line : summary) std::fprintf(stderr, "albedo_tables: film margin, %s\n", line.c_str());
    std::fprintf(stderr, "albedo_tables: film margin, %s\nalbedo_tables: wrote %s\n", counts, s.out.string().c_str());
    return 0;
}

// --anisotropic: the GGX and Beckmann corrections, written to `header`.
int run_anisotropic(const settings& s, ex::output_file& header) {
    using namespace shade;
    const rgb<T> one(1);
    const std::size_t size = s.strong ? detail::strong_anisotropy_size : detail::anisotropic_albedo_size;
    std::optional<ex::progress> bar(std::in_place, "albedo_tables", 2 * size, !s.quiet);
    const auto compute_table = s.strong ? compute_strong : compute_anisotropic;
    const std::string prefix = s.strong ? "_anisotropic_strong_albedo_delta" : "_anisotropic_albedo_delta";
    std::vector<anisotropic_table> tables;
    tables.push_back(compute_table(
        "ggx" + prefix, "the anisotropic GGX lobe with F = 1 (cook_torrance<ggx, schlick(1), smith_height_correlated>)",
        detail::ggx_albedo, anisotropic_family([one](double ax, double ay) {
            return cook_torrance<ggx<T>, schlick<T>, smith_height_correlated<T>>(ggx<T>(unchecked, ax, ay), schlick<T>(one));
        }, s.strata), s, *bar));
    tables.push_back(compute_table(
        "beckmann" + prefix,
        "the anisotropic Beckmann lobe with F = 1 (cook_torrance<beckmann, schlick(1), smith_height_correlated>)",
        detail::beckmann_albedo, anisotropic_family([one](double mx, double my) {
            return cook_torrance<beckmann<T>, schlick<T>, smith_height_correlated<T>>(beckmann<T>(unchecked, mx, my), schlick<T>(one));
        }, s.strata), s, *bar));
    bar.reset();
    for (const auto& t : tables)
        std::fprintf(stderr, "albedo_tables: %s: largest node standard error %.2e, largest |Delta| %.4f\n", t.name.c_str(),
                     t.max_error, t.max_delta);
    header.write_stream([&](std::FILE* f) {
        write_anisotropic(f, tables, s);
    });
    std::fprintf(stderr, "albedo_tables: wrote %s\n", s.out.string().c_str());
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    return ex::run_cli("albedo_tables", [&] {
        settings s;
        film_margin_settings fm;
        bool nodes_given = false;
        ex::command_line args(argc, argv);
        while (args.next()) {
            if (args.flag("--help") || args.flag("-h")) {
                std::fputs(usage.data(), stdout);
                return 0;
            }
            if (args.option("--out")) s.out = args.path();
            else if (args.option("--nodes")) s.nodes = args.integer<std::size_t>(4, 512), nodes_given = true;
            else if (args.option("--strata")) s.strata = args.integer<std::size_t>(16, 2048);
            else if (args.option("--threads")) s.threads = args.integer<unsigned>(1, 64);
            else if (args.flag("--quiet")) s.quiet = true;
            else if (args.flag("--anisotropic")) s.anisotropic = true;
            else if (args.flag("--anisotropic-strong")) s.anisotropic = s.strong = true;
            else if (args.flag("--cosine-weights")) s.cosine_weights = true;
            else if (args.flag("--film-margin")) s.film_margin = true;
            else if (args.option("--fine")) fm.fine = args.integer<std::size_t>(65, 16385);
            else if (args.option("--sub")) fm.q = args.integer<std::size_t>(1, 8);
            else if (args.flag("--coarse-films")) fm.coarse = true;
            else args.unknown();
        }
        if (s.anisotropic && nodes_given)
            throw ex::usage_error("option --nodes does not apply with --anisotropic (its grid is fixed by anisotropic_albedo_table.hpp)");
        if (s.cosine_weights && (nodes_given || s.anisotropic))
            throw ex::usage_error("options --nodes and --anisotropic do not apply with --cosine-weights (its grid is fixed by cosine_weight_data.hpp)");
        if (s.film_margin && s.cosine_weights)
            throw ex::usage_error("options --cosine-weights and --film-margin exclude each other");
        if (s.film_margin && (nodes_given || s.anisotropic))
            throw ex::usage_error("options --nodes and --anisotropic do not apply with --film-margin (its grid is cosine_weight_data.hpp's)");
        if (s.anisotropic && s.out == "albedo_data.hpp")
            s.out = s.strong ? "anisotropic_strong_albedo_data.hpp" : "anisotropic_albedo_data.hpp";
        if (s.cosine_weights && s.out == "albedo_data.hpp") s.out = "cosine_weight_data.hpp";
        if (s.film_margin && s.out == "albedo_data.hpp") s.out = "thin_film_margin_data.hpp";
        (void)ex::output_format("--out", s.out, {".hpp", ".h"});
        ex::output_file header(s.out);
        if (s.anisotropic) return run_anisotropic(s, header);
        if (s.cosine_weights) return run_cosine_weights(s, header);
        if (s.film_margin) return run_film_margin(s, fm, header);
        constexpr std::size_t table_count = 3;
        std::optional<ex::progress> bar(std::in_place, "albedo_tables",
                                        table_count * (s.nodes * s.nodes + check_cells(s.nodes).size()), !s.quiet);
        using namespace shade;
        const rgb<T> one(1);
        std::vector<table> tables;
        tables.push_back(compute("ggx_albedo", "the GGX lobe with F = 1 (cook_torrance<ggx, schlick(1), smith_height_correlated>)",
                                 family([one](double a) {
                                     return cook_torrance<ggx<T>, schlick<T>, smith_height_correlated<T>>(ggx<T>(a), schlick<T>(one));
                                 }, s.strata), s, *bar));
        tables.push_back(compute("beckmann_albedo",
                                 "the Beckmann lobe with F = 1 (cook_torrance<beckmann, schlick(1), smith_height_correlated>)",
                                 family([one](double a) {
                                     return cook_torrance<beckmann<T>, schlick<T>, smith_height_correlated<T>>(beckmann<T>(a),
                                                                                                              schlick<T>(one));
                                 }, s.strata), s, *bar));
        tables.push_back(compute("ggx_dielectric_albedo",
                                 "the GGX lobe with the dielectric Fresnel of eta = 1.5 (cook_torrance<ggx, dielectric_fresnel(1.5), smith_height_correlated>)",
                                 family([](double a) {
                                     return cook_torrance<ggx<T>, dielectric_fresnel<T>, smith_height_correlated<T>>(
                                         ggx<T>(a), dielectric_fresnel<T>(1.5));
                                 }, s.strata), s, *bar));
        bar.reset(); // erases the bar before the messages
        for (const auto& t : tables)
            std::fprintf(stderr, "albedo_tables: %s: largest node standard error %.2e, largest interpolation difference "
                         "%.2e, E_avg consistency %.2e (worst interpolation in the cell of c_%zu, alpha_%zu)\n",
                         t.name.c_str(), t.max_error, t.max_interpolation, t.max_average, t.worst_i, t.worst_j);
        header.write_stream([&](std::FILE* f) {
            write(f, tables, s);
        });
        std::fprintf(stderr, "albedo_tables: wrote %s\n", s.out.string().c_str());
        return 0;
    });
}
