// dielectric_albedo_tables: computes the albedo tables of the rough dielectric
// (shade/bsdf/dielectric_albedo_table.hpp) with the model's own importance sampling and
// writes them as a header of constants.
//
//   dielectric_albedo_tables --out include/shade/bsdf/detail/dielectric_albedo_data.hpp
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

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <thread>
#include <utility>
#include <vector>

#include <shade/brdf/microfacet/ggx.hpp>
#include <shade/bsdf/dielectric_albedo_table.hpp>
#include <shade/bsdf/rough_dielectric.hpp>
#include <shade/check/energy.hpp>

#include "support/cli.hpp"
#include "support/float_literals.hpp"
#include "support/progress.hpp"

namespace ex = shade::examples;
namespace d = shade::detail;

namespace {

using T = double;

constexpr std::string_view usage =
    R"(usage: dielectric_albedo_tables [--out FILE.hpp] [--mu-nodes N] [--alpha-nodes N] [--eta-nodes N]
                                [--strata S] [--threads K] [--quiet]

Computes E(mu, alpha, eta_s) = R + T (importance mode) of
shade::rough_dielectric over GGX, for light entering (eta_s in
[1.05, 3]) and leaving (eta_s in [1/3, 1/1.05]) the denser medium, on the grid of
dielectric_albedo_table.hpp, each node from S^2 samples of the model's own sampler, and
writes the header of constants.

  --out FILE.hpp    output, a C++ header (.hpp or .h; default dielectric_albedo_data.hpp)
  --mu-nodes N      nodes along the view coordinate, 4 to 128 (default 25)
  --alpha-nodes N   nodes along sqrt(alpha), 4 to 128 (default 16)
  --eta-nodes N     nodes along log(eta - 1), 2 to 64 (default 12)
  --strata S        S^2 samples per node, 16 to 2048 (default 384)
  --threads K       worker threads, 1 to 64 (default 2)
  --quiet           no progress bar
)";

struct settings {
    std::filesystem::path out = "dielectric_albedo_data.hpp";
    d::dielectric_albedo_grid grid{};
    std::size_t strata = 384;
    unsigned threads = 2;
    bool quiet = false;
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
    // with which sample() chooses them at the visible normal it draws from u.
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

using estimator = std::function<shade::check::albedo_sample<T>(double, double, double, std::size_t, std::uint64_t)>;

struct table {
    std::string name;            // C++ name prefix
    std::string what;            // one line for the comment
    std::vector<float> e;        // grid.size()
    double max_error = 0;        // largest standard error of a node
    double max_interpolation = 0; // largest |interpolated - estimated| at the cell centres
    double max_domain = 0;       // the same over the cell centres with mu >= 0.05
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

table compute(const std::string& name, const std::string& what, const estimator& albedo, const settings& s,
              ex::progress& bar) {
    const d::dielectric_albedo_grid& g = s.grid;
    table out{name, what, std::vector<float>(g.size()), 0, 0, 0};
    std::vector<double> errors(g.size());
    parallel_for(g.size(), s.threads, [&](std::size_t index) {
        const std::size_t i = index % g.mu_nodes;
        const std::size_t j = index / g.mu_nodes % g.alpha_nodes;
        const std::size_t k = index / (g.mu_nodes * g.alpha_nodes) % g.eta_nodes;
        const std::size_t side = index / (g.mu_nodes * g.alpha_nodes * g.eta_nodes);
        const double alpha = d::albedo_grid_alpha(j, g.alpha_nodes);
        const double eta_hat = d::dielectric_albedo_eta(k, g.eta_nodes);
        const double mu = d::dielectric_albedo_view_mu(double(i) / double(g.mu_nodes - 1), alpha, eta_hat, side);
        const auto a = albedo(mu, alpha, eta_of_side(side, eta_hat), s.strata, 1 + index);
        out.e[index] = float(std::min(a.albedo.x, 1.0));
        errors[index] = a.standard_error.x;
        bar.advance();
    });
    out.max_error = *std::max_element(errors.begin(), errors.end());
    // Every cell centre, estimated afresh and compared with the interpolated table.
    const std::size_t cells = 2 * (g.eta_nodes - 1) * (g.alpha_nodes - 1) * (g.mu_nodes - 1);
    std::vector<double> differences(cells);
    std::vector<char> in_domain(cells);
    parallel_for(cells, s.threads, [&](std::size_t index) {
        const std::size_t i = index % (g.mu_nodes - 1);
        const std::size_t j = index / (g.mu_nodes - 1) % (g.alpha_nodes - 1);
        const std::size_t k = index / ((g.mu_nodes - 1) * (g.alpha_nodes - 1)) % (g.eta_nodes - 1);
        const std::size_t side = index / ((g.mu_nodes - 1) * (g.alpha_nodes - 1) * (g.eta_nodes - 1));
        const double y = (double(j) + 0.5) / double(g.alpha_nodes - 1);
        const double alpha = std::max(y * y, d::albedo_grid_alpha_min);
        const double eta_hat = 1 + std::sqrt((d::dielectric_albedo_eta(k, g.eta_nodes) - 1) * (d::dielectric_albedo_eta(k + 1, g.eta_nodes) - 1));
        const double mu = d::dielectric_albedo_view_mu((double(i) + 0.5) / double(g.mu_nodes - 1), alpha, eta_hat, side);
        const double eta_s = eta_of_side(side, eta_hat);
        const auto a = albedo(mu, alpha, eta_s, s.strata, 1000003 + index);
        const auto cell = d::dielectric_albedo_locate(g, alpha, eta_s);
        differences[index] = std::abs(d::dielectric_albedo_lookup(out.e.data(), g, cell, mu) - a.albedo.x);
        in_domain[index] = mu >= 0.05;
        bar.advance();
    });
    out.max_interpolation = *std::max_element(differences.begin(), differences.end());
    for (std::size_t index = 0; index < cells; ++index)
        if (in_domain[index]) out.max_domain = std::max(out.max_domain, differences[index]);
    return out;
}

void write(std::FILE* f, const std::vector<table>& tables, const settings& s) {
    const d::dielectric_albedo_grid& g = s.grid;
    std::fprintf(f, "#pragma once\n");
    std::fprintf(f,
                 "// Generated by examples/dielectric_albedo_tables.cpp (--mu-nodes %zu --alpha-nodes %zu --eta-nodes %zu "
                 "--strata %zu);\n// do not edit by hand.\n",
                 g.mu_nodes, g.alpha_nodes, g.eta_nodes, s.strata);
    std::fprintf(f, "// The albedo tables of shade/bsdf/dielectric_albedo_table.hpp (grid, interpolation, meaning):\n");
    std::fprintf(f, "// 2 sides x %zu eta x %zu alpha x %zu mu nodes, one (side, eta) block of rows per line group;\n",
                 g.eta_nodes, g.alpha_nodes, g.mu_nodes);
    std::fprintf(f, "// each node the mean importance-mode weight of %zu jittered samples of the model's own sampler.\n",
                 s.strata * s.strata);
    std::fprintf(f, "// Accuracy (measured by the generator, per table below): the largest standard error of a\n");
    std::fprintf(f, "// node; the largest difference between the interpolated table and a fresh estimate at the\n");
    std::fprintf(f, "// centre of every cell (interpolation plus both estimates' noise), and the same over the\n");
    std::fprintf(f, "// cells whose centre has mu >= 0.05.\n\n");
    std::fprintf(f, "namespace shade::detail {\n");
    for (const auto& t : tables) {
        std::fprintf(f, "\n/// E(mu, alpha, eta_s) of %s.\n", t.what.c_str());
        std::fprintf(f, "/// Node standard error <= %.1e; interpolated vs estimated at cell centres <= %.1e;\n", t.max_error,
                     t.max_interpolation);
        std::fprintf(f, "/// at the cell centres with mu >= 0.05 <= %.1e.\n", t.max_domain);
        std::fprintf(f, "inline constexpr float %s[%zu] = {\n", t.name.c_str(), g.size());
        for (std::size_t r = 0; r < g.size() / g.mu_nodes; ++r) {
            ex::write_float_literals(f, t.e.data() + r * g.mu_nodes, g.mu_nodes);
            std::fprintf(f, ",\n");
        }
        std::fprintf(f, "};\n");
    }
    std::fprintf(f, "\n} // namespace shade::detail\n");
}

} // namespace

int main(int argc, char** argv) {
    return ex::run_cli("dielectric_albedo_tables", [&] {
        settings s;
        ex::command_line args(argc, argv);
        while (args.next()) {
            if (args.flag("--help") || args.flag("-h")) {
                std::fputs(usage.data(), stdout);
                return 0;
            }
            if (args.option("--out")) s.out = args.path();
            else if (args.option("--mu-nodes")) s.grid.mu_nodes = args.integer<std::size_t>(4, 128);
            else if (args.option("--alpha-nodes")) s.grid.alpha_nodes = args.integer<std::size_t>(4, 128);
            else if (args.option("--eta-nodes")) s.grid.eta_nodes = args.integer<std::size_t>(2, 64);
            else if (args.option("--strata")) s.strata = args.integer<std::size_t>(16, 2048);
            else if (args.option("--threads")) s.threads = args.integer<unsigned>(1, 64);
            else if (args.flag("--quiet")) s.quiet = true;
            else args.unknown();
        }
        (void)ex::output_format("--out", s.out, {".hpp", ".h"});
        ex::output_file header(s.out);
        const d::dielectric_albedo_grid& g = s.grid;
        const std::size_t cells = 2 * (g.eta_nodes - 1) * (g.alpha_nodes - 1) * (g.mu_nodes - 1);
        std::optional<ex::progress> bar(std::in_place, "dielectric_albedo_tables", g.size() + cells, !s.quiet);
        std::vector<table> tables;
        tables.push_back(compute("ggx_rough_dielectric_albedo", "shade::rough_dielectric<ggx> (isotropic alpha)",
                                 estimate<shade::ggx<T>>, s, *bar));
        bar.reset();
        for (const auto& t : tables)
            std::fprintf(stderr,
                         "dielectric_albedo_tables: %s: largest node standard error %.2e, largest interpolation "
                         "difference %.2e (%.2e where mu >= 0.05)\n",
                         t.name.c_str(), t.max_error, t.max_interpolation, t.max_domain);
        std::FILE* f = std::fopen(header.temporary().c_str(), "w");
        if (!f) throw std::runtime_error("cannot write " + header.temporary().string());
        write(f, tables, s);
        if (std::fclose(f) != 0) throw std::runtime_error("cannot write " + header.temporary().string());
        header.commit();
        std::fprintf(stderr, "dielectric_albedo_tables: wrote %s\n", s.out.string().c_str());
        return 0;
    });
}
