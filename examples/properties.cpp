// properties: runs every shade reflection model through the property checks of
// shade/check (positivity, reciprocity, energy conservation, and the sampling checks), and
// every BSDF through the checks over the whole sphere (adjoint reciprocity, reflected and
// transmitted albedo, sampling), and reports the outcome as Markdown tables (stdout), plus a white-furnace plot (directional
// albedo against viewing angle) as a PNG; and the white furnace of the models compensated
// for multiple scattering against single scattering (a table, and a plot of albedo against
// roughness).
//
//   properties [--out white_furnace.png] [--roughness-out albedo_roughness.png] [--strata N] [--samples N] [--quiet]
//
// The tables in docs/properties.md are this program's output.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <shade/brdf/anisotropic_multiple_scattering.hpp>
#include <shade/brdf/eon.hpp>
#include <shade/brdf/f82_tint.hpp>
#include <shade/brdf/kulla_conty_lobe.hpp>
#include <shade/brdf/microfacet_reflection.hpp>
#include <shade/brdf/sheen.hpp>
#include <shade/brdf/thin_film.hpp>
#include <shade/bsdf/compensated_rough_dielectric.hpp>
#include <shade/bsdf/layer.hpp>
#include <shade/bsdf/mix.hpp>
#include <shade/check/bsdf_energy.hpp>
#include <shade/check/bsdf_reciprocity.hpp>
#include <shade/check/properties.hpp>
#include <shade/core/random.hpp>
#include <shade/material/openpbr_presets.hpp>
#include <shade/material/openpbr_surface.hpp>
#include <shade/shade.hpp>

#include "support/canvas.hpp"
#include "support/cli.hpp"
#include "support/progress.hpp"

namespace {

namespace ex = shade::examples;
namespace check = shade::check;
using T = double;
using shade::rgb;
using shade::vec3;

constexpr std::string_view usage = R"(usage: properties [--out FILE.png] [--roughness-out FILE.png] [--strata N] [--samples N] [--quiet]

Runs every shade model through the positivity, reciprocity and energy checks and the
sampling checks (chi-square of sample() against pdf(), sample consistency, pdf
normalization and coverage), every BSDF through adjoint reciprocity, reflected and
transmitted albedo and the sampling checks over the whole sphere, and prints Markdown
tables on stdout. Plots are written only
when asked for.

  --out FILE.png  the white-furnace plot (albedo against the view angle, every model)
  --roughness-out FILE.png
                  the plot of albedo against roughness, compensated for multiple
                  scattering and not
  --strata N      N^2 samples per albedo estimate, 16 to 4096 (default 128); below 16^2
                  samples per view the energy check cannot give a verdict
  --samples N     directions per chi-square test, 1000 to 10000000 (default 100000)
  --quiet         no progress bar (it is drawn on stderr only when stderr is a terminal
                  and the run takes more than a second)
)";

// Views of the sampling checks: from the normal to grazing, azimuth 0.4 rad off the
// tangent (so anisotropic lobes are seen neither along nor across their axes).
constexpr double sampling_views_deg[] = {0, 45, 75, 89};
constexpr std::size_t curve_points = 30;
// The chi-square tests of the whole table share alpha = 0.01 (Šidák); an upper bound on
// their number.
constexpr std::size_t chi2_family = 40 * std::size(sampling_views_deg);

struct settings {
    std::optional<std::filesystem::path> out;           ///< the white-furnace plot, if asked for
    std::optional<std::filesystem::path> roughness_out; ///< the roughness plot, if asked for
    bool quiet = false;
    std::size_t strata = 128;
    std::size_t samples = 100000;
};

struct row {
    std::string name;
    bool positive = false;
    bool reciprocal = false;
    check::verdict energy = check::verdict::inconclusive;
    double max_albedo = 0;
    double albedo_error = 0;
    bool own_sampler = false;
    double min_p = 1;                  // smallest chi-square p-value over the views
    check::verdict chi2 = check::verdict::pass;
    double max_pdf_integral = 0;       // largest ∫pdf over the views
    double pdf_integral_error = 0;     // its quadrature error
    check::verdict normalization = check::verdict::pass;
    bool consistent = false;           // sample_consistency and pdf_coverage both pass
    double weight_spread = 0;          // largest sd(weight) / mean(weight) over the curve's views
    std::vector<double> curve;         // albedo (max channel) against theta_v, azimuth 0
    rgb<float> colour;
};

const char* word(check::verdict v) {
    switch (v) {
    case check::verdict::pass: return "pass";
    case check::verdict::fail: return "**fail**";
    case check::verdict::inconclusive: return "*inconclusive*";
    }
    return "?";
}

/// The worse of two verdicts (fail > inconclusive > pass).
check::verdict worse(check::verdict a, check::verdict b) {
    const auto rank = [](check::verdict v) { return v == check::verdict::fail ? 2 : v == check::verdict::inconclusive ? 1 : 0; };
    return rank(a) >= rank(b) ? a : b;
}

template <class B>
row evaluate(const std::string& name, const B& model, const settings& s, rgb<float> colour) {
    shade::surface_point<T> at;
    at.shading = shade::frame<T>::from_normal_tangent({0, 0, 1}, {1, 0, 0});
    check::pair_options pairs{.pairs = 20000};
    pairs.model = name;
    check::albedo_options albedo{.strata = s.strata, .view_angles = 16, .azimuths = 4};
    albedo.model = name;
    row r;
    r.name = name;
    r.colour = colour;
    r.positive = check::positivity(model, at, pairs).passed;
    r.reciprocal = check::reciprocity(model, at, pairs).passed;
    const auto energy = check::energy_conservation(model, at, albedo);
    r.energy = energy.outcome;
    r.max_albedo = energy.worst;
    r.albedo_error = energy.error;
    auto curve_options = albedo;
    curve_options.view_angles = curve_points;
    curve_options.azimuths = 1;
    for (const auto& p : check::white_furnace(model, at, curve_options)) {
        const double a = std::max({p.albedo.x, p.albedo.y, p.albedo.z});
        r.curve.push_back(a);
        r.own_sampler = p.own_sampler;
        for (int c = 0; c < 3; ++c)
            if (p.albedo[c] > 1e-6) r.weight_spread = std::max(r.weight_spread, p.sample_deviation[c] / p.albedo[c]);
    }
    static_assert(shade::sampled_brdf<B>, "every shipped model has a sampler");
    check::chi2_options chi2{.samples = s.samples, .tests = chi2_family};
    chi2.model = name;
    for (const double theta_deg : sampling_views_deg) {
        const double theta = theta_deg * shade::pi<double> / 180;
        const vec3<T> v = at.shading.to_world(shade::spherical_direction(theta, 0.4));
        const auto c = check::chi2_goodness_of_fit(model, v, at, chi2);
        r.min_p = std::min(r.min_p, c.p_value);
        r.chi2 = worse(r.chi2, c.outcome);
        const auto n = check::pdf_normalization(model, v, at, chi2);
        if (n.worst > r.max_pdf_integral) {
            r.max_pdf_integral = n.worst;
            r.pdf_integral_error = n.error;
        }
        r.normalization = worse(r.normalization, n.outcome);
    }
    check::sample_options consistency;
    consistency.model = name;
    r.consistent = check::sample_consistency(model, at, consistency).passed &&
                   check::pdf_coverage(model, at, pairs).passed;
    return r;
}

/// One job per model of the tables: each evaluates its model when called.
std::vector<std::function<row()>> model_jobs(const settings& s) {
    using namespace shade;
    const rgb<T> one(1), half(0.5), zero(0);
    std::vector<std::function<row()>> jobs;
    const auto add = [&](std::string name, const auto& model, rgb<float> colour) {
        jobs.emplace_back([name = std::move(name), model, colour, &s] { return evaluate(name, model, s, colour); });
    };
    // Colours of the plot's curves (linear RGB).
    const auto c = [](float r, float g, float b) { return rgb<float>(r, g, b); };
    using ggx_smith = cook_torrance<ggx<T>, schlick<T>, smith_ggx<T>>;
    using beckmann_smith = cook_torrance<beckmann<T>, schlick<T>, smith_beckmann<T>>;
    add("Lambert (k_d = 1)", lambert<T>(one), c(0.1f, 0.1f, 0.1f));
    add("Phong classic, / n.l (k_s = 1, s = 10)", classic_phong<T>(zero, one, 10), c(0.8f, 0.1f, 0.1f));
    add("Phong modified, unnormalized (k_s = 1, s = 2)", modified_phong<T>(zero, one, 2), c(0.9f, 0.5f, 0.0f));
    add("Phong normalized (k_d = k_s = 0.5, s = 20)", normalized_phong<T>(half, half, 20), c(0.1f, 0.5f, 0.1f));
    add("Phong normalized (k_s = 1, s = 10000)", normalized_phong<T>(zero, one, 10000), c(0.3f, 0.7f, 0.3f));
    add("Blinn-Phong classic, / n.l (k_s = 1, s = 20)",
                            blinn_phong<T, blinn_phong_form::classic>(zero, one, 20), c(0.6f, 0.1f, 0.6f));
    add("Blinn-Phong normalized (k_d = k_s = 0.5, s = 50)", blinn_phong<T>(half, half, 50), c(0.1f, 0.3f, 0.8f));
    add("Blinn-Phong normalized (k_s = 1, s = 10000)", blinn_phong<T>(zero, one, 10000), c(0.4f, 0.5f, 0.9f));
    add("Cook-Torrance Walter, Beckmann/Smith, m = 0.3, F = 1",
                            beckmann_smith(beckmann<T>(0.3), schlick<T>(one)), c(0.0f, 0.6f, 0.6f));
    add("Cook-Torrance Walter, Beckmann/Smith, m = 0.01, F = 1",
                            beckmann_smith(beckmann<T>(0.01), schlick<T>(one)), c(0.0f, 0.4f, 0.4f));
    add("Cook-Torrance Walter, GGX/Smith, alpha = 0.3, F = 1",
                            ggx_smith(ggx<T>(0.3), schlick<T>(one)), c(0.3f, 0.3f, 0.9f));
    add("Cook-Torrance Walter, GGX/Smith, alpha = 0.01, F = 1",
                            ggx_smith(ggx<T>(0.01), schlick<T>(one)), c(0.2f, 0.2f, 0.6f));
    add("Cook-Torrance Walter, GGX/Smith, alpha = 1, F = 1",
                            ggx_smith(ggx<T>(1), schlick<T>(one)), c(0.5f, 0.5f, 1.0f));
    add("Cook-Torrance Walter, GGX/Smith, alpha = 0.05 x 0.5, F = 1",
                            ggx_smith(ggx<T>(0.05, 0.5), schlick<T>(one)), c(0.6f, 0.3f, 0.9f));
    add("Cook-Torrance Walter, GGX/height-correlated Smith, alpha = 0.3, F = 1",
                            cook_torrance<ggx<T>, schlick<T>, smith_height_correlated<T>>(ggx<T>(0.3), schlick<T>(one)),
                            c(0.2f, 0.6f, 0.9f));
    add("Microfacet reflection (the lobe alone), GGX/height-correlated Smith, alpha = 0.5, gold",
        microfacet_reflection<ggx<T>, schlick<T>, smith_height_correlated<T>>(ggx<T>(0.5),
                                                                             schlick<T>(rgb<T>(1.0, 0.71, 0.29))),
        c(0.7f, 0.5f, 0.1f));
    using ggx_ms = compensated_ggx_conductor<T>;
    using beckmann_ms = compensated_beckmann_conductor<T>;
    add("Cook-Torrance Walter, GGX/height-correlated Smith + Kulla-Conty, alpha = 1, F = 1",
                            ggx_ms(ggx<T>(1), schlick<T>(one)), c(0.0f, 0.0f, 0.0f));
    add("Cook-Torrance Walter, GGX/height-correlated Smith + Kulla-Conty, alpha = 0.05 x 0.5, gold",
                            ggx_ms(ggx<T>(0.05, 0.5), schlick<T>(rgb<T>(1.0, 0.71, 0.29))), c(0.8f, 0.6f, 0.1f));
    add("Cook-Torrance Walter, Beckmann/height-correlated Smith + Kulla-Conty, m = 0.5, F = 1",
                            beckmann_ms(beckmann<T>(0.5), schlick<T>(one)), c(0.0f, 0.3f, 0.3f));
    add("Coupled plastic (GGX alpha = 0.5, k_d = 1)", coupled_plastic<T>(ggx<T>(0.5), one),
                            c(0.9f, 0.4f, 0.6f));
    add("Cook-Torrance Walter, Beckmann/V-groove, m = 0.3, F = 1",
                            cook_torrance<beckmann<T>, schlick<T>, v_groove<T>>(beckmann<T>(0.3), schlick<T>(one)),
                            c(0.5f, 0.5f, 0.2f));
    add("Cook-Torrance course slides (4/pi), Beckmann/V-groove, m = 0.3, F = 1",
                            cook_torrance<beckmann<T>, schlick<T>, v_groove<T>, cook_torrance_form::course>(
                                beckmann<T>(0.3), schlick<T>(one)),
                            c(0.9f, 0.2f, 0.5f));
    add("Cook-Torrance 1982 paper (x4), Beckmann/V-groove, m = 0.3, F = 1",
                            cook_torrance<beckmann<T>, schlick<T>, v_groove<T>, cook_torrance_form::paper_1982>(
                                beckmann<T>(0.3), schlick<T>(one)),
                            c(0.5f, 0.2f, 0.0f));
    add("Oren-Nayar (rho = 0.8, sigma = 0.3)", oren_nayar<T>(rgb<T>(0.8), 0.3), c(0.6f, 0.4f, 0.2f));
    add("Oren-Nayar (rho = 1, sigma = 0.5)", oren_nayar<T>(one, 0.5), c(0.8f, 0.6f, 0.3f));
    add("Zeltner sheen (F = 1, roughness = 0.3)", zeltner_sheen<T>(one, 0.3), c(0.9f, 0.9f, 0.5f));
    add("Zeltner sheen (F = 1, roughness = 1)", zeltner_sheen<T>(one, 1), c(0.7f, 0.7f, 0.3f));
    add("Zeltner sheen reciprocal (F = 1, roughness = 0.3)", zeltner_sheen_reciprocal<T>(one, 0.3),
                            c(0.9f, 0.7f, 0.7f));
    add("EON (rho = 1, roughness = 1)", eon<T>(one, 1.0), c(0.4f, 0.2f, 0.1f));
    add("EON (rho = 0.8, roughness = 0.5)", eon<T>(rgb<T>(0.8), 0.5), c(0.7f, 0.5f, 0.4f));
    add("EON, fitted albedo (rho = 1, roughness = 1)", eon<T, eon_albedo::approximate>(one, 1.0), c(0.5f, 0.3f, 0.0f));
    add("Fujii Oren-Nayar, single scattering (rho = 1, roughness = 1)", fujii_oren_nayar<T>(one, 1.0),
        c(0.9f, 0.7f, 0.5f));
    // The lobes of openpbr_surface not above (shade/material/openpbr_surface.hpp): its metal
    // (F82-tint Fresnel, Kulla-Conty compensation at every azimuth), its coat (one-sided
    // reflection with the exact dielectric Fresnel) and its thin film.
    using f82_metal = microfacet_reflection<ggx<T>, f82_tint<T>, smith_height_correlated<T>, cook_torrance_form::walter,
                                            kulla_conty_anisotropic>;
    add("F82-tint metal lobe + kulla_conty_anisotropic, GGX alpha = 0.3 x 0.1, F0 = 1, tint = 1",
        f82_metal(ggx<T>(0.3, 0.1), f82_tint<T>(one, one)), c(0.3f, 0.3f, 0.3f));
    add("F82-tint metal lobe + kulla_conty_anisotropic, GGX alpha = 0.25, gold-like F0 (0.95, 0.7, 0.3), tint (0.9, 0.8, 0.6)",
        f82_metal(ggx<T>(0.25), f82_tint<T>(rgb<T>(0.95, 0.7, 0.3), rgb<T>(0.9, 0.8, 0.6))), c(0.9f, 0.6f, 0.2f));
    add("Coat lobe: microfacet reflection, GGX alpha = 0.2 x 0.05, dielectric Fresnel eta 1.6",
        microfacet_reflection<ggx<T>, dielectric_fresnel<T>, smith_height_correlated<T>>(ggx<T>(0.2, 0.05),
                                                                                         dielectric_fresnel<T>(1.6)),
        c(0.4f, 0.7f, 0.9f));
    add("Thin-film lobe: microfacet reflection, GGX alpha = 0.2, film 400 nm of eta 1.4 over eta 1.5",
        microfacet_reflection<ggx<T>, thin_film_fresnel<T>, smith_height_correlated<T>>(
            ggx<T>(0.2), thin_film_fresnel<T>::over_dielectric(1.5, 1.4, 400)),
        c(0.6f, 0.2f, 0.8f));
    add("Ashikhmin-Shirley (R_d = 0.8, R_s = 0.2, p = 10, 200)",
                            ashikhmin_shirley<T>(rgb<T>(0.8), rgb<T>(0.2), 10, 200), c(0.2f, 0.7f, 0.3f));
    return jobs;
}

void print_tables(const std::vector<row>& rows, const settings& s) {
    std::printf("### Reciprocity, positivity, energy\n\n");
    std::printf("| model | positive | reciprocal | max albedo ± SE | energy conserving |\n");
    std::printf("|---|---|---|---|---|\n");
    for (const auto& r : rows)
        std::printf("| %s | %s | %s | %.4f ± %.1e | %s |\n", r.name.c_str(), r.positive ? "yes" : "**no**",
                    r.reciprocal ? "yes" : "**no**", r.max_albedo, r.albedo_error, word(r.energy));
    std::printf("\nPositivity and reciprocity: 20000 direction pairs each (hard cases first). Max albedo: the "
                "deciding view (see `energy_conservation`) over 16 viewing angles (0 to 89 degrees) x 4 azimuths, "
                "%zu^2 samples per view from each model's own sampler, with its standard error; energy conserving: "
                "pass when albedo + 4 SE <= 1.01 at every view, fail when albedo - 4 SE > 1.01 at some view, "
                "inconclusive otherwise.\n\n",
                s.strata);
    std::printf("### Sampling\n\n");
    std::printf("| model | chi-square min p | sampling matches pdf | max ∫pdf ± error | ∫pdf <= 1 | sample = f, pdf; pdf covers f | weight sd / mean |\n");
    std::printf("|---|---|---|---|---|---|---|\n");
    for (const auto& r : rows)
        std::printf("| %s | %.3g | %s | %.6f ± %.0e | %s | %s | %.3g |\n", r.name.c_str(), r.min_p, word(r.chi2),
                    r.max_pdf_integral, r.pdf_integral_error, word(r.normalization), r.consistent ? "yes" : "**no**",
                    r.weight_spread);
    std::printf("\nChi-square: %zu directions per view at 4 views (theta_v = 0, 45, 75, 89 degrees), binned in 10 "
                "rings around the mirror direction (quantiles of a pilot sample) x 20 sectors plus a bin for "
                "draws that return nothing, bins expecting < 5 pooled; each test rejects at the Šidák level "
                "1 - 0.99^(1/%zu) = %.2g, so the whole table has at most a 1 %% chance of a false rejection. "
                "∫pdf: adaptive quadrature over the same bins, largest over the views, with the quadrature's "
                "error estimate (< 1 where the lobe loses mass below the horizon). Sample consistency: 500 views x "
                "40 draws; coverage: 20000 pairs. Weight sd / mean: the largest relative standard deviation "
                "of one sample's weight f |n.l| / pdf over 30 viewing angles (how noisy one sample is in a "
                "renderer; 0 for a sampler proportional to f |n.l|).\n",
                s.samples, chi2_family, check::sidak_significance(0.01, chi2_family));
}

// The white furnace of the compensated models against single scattering.
constexpr double compensation_alphas[] = {0.05, 0.25, 0.5, 0.75, 1.0};
constexpr double compensation_cosines[] = {1.0, 0.75, 0.5, 0.25, 0.1, 0.05};

template <class B>
check::albedo_sample<T> furnace_sample(const B& model, double mu, std::size_t strata) {
    shade::surface_point<T> at;
    at.shading = shade::frame<T>::from_normal_tangent({0, 0, 1}, {1, 0, 0});
    const vec3<T> v(std::sqrt((1 - mu) * (1 + mu)), 0, mu);
    return check::sampled_albedo(model, v, at, strata, 7);
}

template <class B>
double furnace_albedo(const B& model, double mu, std::size_t strata) {
    return furnace_sample(model, mu, strata).albedo.x;
}

// 2 integral_0^1 g(mu) mu dmu, midpoint rule on 20000 cells.
template <class G>
double cosine_average(const G& g) {
    double sum = 0;
    for (int i = 0; i < 20000; ++i) {
        const double mu = (i + 0.5) / 20000;
        sum += 2 * g(mu) * mu / 20000;
    }
    return sum;
}

// The albedo of a compensated lobe's f_ms part (k_s = 1) at view cosine mu, exact by
// quadrature of the model's table reads: F_ms (1 - E(mu)) (1 - 2 integral E mu) / (1 - E_avg).
template <class Compensated>
double multiple_scattering_albedo(const Compensated& model, double f_ms, double mu) {
    const double e_avg = model.average_single_scattering_albedo();
    const double average = cosine_average([&](double x) { return double(model.single_scattering_albedo(T(x))); });
    return f_ms * (1 - double(model.single_scattering_albedo(T(mu)))) * (1 - average) / (1 - e_avg);
}

// The BSDFs over the whole sphere: v and l on either side of the surface.

// Views of the BSDF sampling checks: as for the BRDFs, from outside and from inside.
constexpr double bsdf_views_deg[] = {0, 45, 75, 89};
// The BSDF table's chi-square tests share alpha = 0.01 (Šidák); an upper bound on their
// number (models with a density x views x 2 sides).
constexpr std::size_t bsdf_chi2_family = 30 * std::size(bsdf_views_deg) * 2;

struct bsdf_row {
    std::string name;
    check::verdict reciprocal = check::verdict::inconclusive;
    double reciprocity_worst = 0;
    double max_reflected = 0;          // largest reflected albedo (max channel) over the views
    double max_transmitted = 0;        // largest transmitted albedo
    double max_total = 0;              // the deciding view's total (bsdf_energy_conservation)
    double total_error = 0;
    check::verdict energy = check::verdict::inconclusive;
    bool has_density = false;          // false for delta lobes only: no chi-square, no ∫pdf
    double min_p = 1;
    check::verdict chi2 = check::verdict::pass;
    double max_pdf_integral = 0;
    double pdf_integral_error = 0;
    check::verdict normalization = check::verdict::pass;
};

template <class B, class D>
bsdf_row evaluate_bsdf(const std::string& name, const B& model, const D& density, double eta_inside,
                       bool has_density, const settings& s, bool opaque) {
    shade::surface_point<T> at;
    at.shading = shade::frame<T>::from_normal_tangent({0, 0, 1}, {1, 0, 0});
    bsdf_row r;
    r.name = name;
    r.has_density = has_density;
    check::pair_options pairs{.pairs = 20000};
    pairs.model = name;
    const auto reciprocity = check::adjoint_reciprocity(model, at, eta_inside, pairs);
    r.reciprocal = reciprocity.outcome;
    r.reciprocity_worst = reciprocity.worst;
    check::albedo_options albedo{.strata = s.strata, .view_angles = 16, .azimuths = 4};
    albedo.model = name;
    for (const auto& p : check::bsdf_white_furnace(model, at, albedo)) {
        r.max_reflected = std::max({r.max_reflected, p.reflected.x, p.reflected.y, p.reflected.z});
        r.max_transmitted = std::max({r.max_transmitted, p.transmitted.x, p.transmitted.y, p.transmitted.z});
    }
    const auto energy = check::bsdf_energy_conservation(model, at, albedo);
    r.energy = energy.outcome;
    r.max_total = energy.worst;
    r.total_error = energy.error;
    if (!has_density) return r;
    check::chi2_options chi2{.samples = s.samples, .tests = bsdf_chi2_family};
    chi2.model = name;
    for (const double side : {1.0, -1.0}) {
        if (opaque && side < 0) continue; // an opaque model draws nothing from inside: no density to test
        for (const double theta_deg : bsdf_views_deg) {
            const double theta = theta_deg * shade::pi<double> / 180;
            vec3<T> local = shade::spherical_direction(theta, 0.4);
            local.z *= side;
            const vec3<T> v = at.shading.to_world(local);
            const auto c = check::chi2_goodness_of_fit(density, v, at, chi2);
            r.min_p = std::min(r.min_p, c.p_value);
            r.chi2 = worse(r.chi2, c.outcome);
            const auto n = check::pdf_normalization(density, v, at, chi2);
            if (n.worst > r.max_pdf_integral) {
                r.max_pdf_integral = n.worst;
                r.pdf_integral_error = n.error;
            }
            r.normalization = worse(r.normalization, n.outcome);
        }
    }
    return r;
}

template <class B>
bsdf_row evaluate_bsdf(const std::string& name, const B& model, double eta_inside, bool has_density,
                       const settings& s, bool opaque = false) {
    return evaluate_bsdf(name, model, model, eta_inside, has_density, s, opaque);
}

// The points of openpbr_surface in the BSDF table and in its white furnace: the name, the
// parameters, the layering, and whether some lobe is a delta lobe (roughness 0).
struct openpbr_point {
    std::string name;
    shade::openpbr_parameters<T> p;
    shade::layering form = shade::layering::albedo_scaling;
    bool delta = false;
    // eta_inside for adjoint reciprocity: specular_ior for a solid that transmits, else 1.
    [[nodiscard]] double eta_inside() const {
        return !p.geometry_thin_walled && p.transmission_weight > 0 ? double(p.specular_ior) : 1.0;
    }
    // An opaque solid draws nothing for a view from inside: no density to test there.
    [[nodiscard]] bool opaque() const { return !p.geometry_thin_walled && p.transmission_weight == 0; }
};

std::vector<openpbr_point> openpbr_points() {
    using namespace shade;
    std::vector<openpbr_point> out;
    out.push_back({"default", openpbr::default_material<T>()});
    // The gold preset's colours at roughness 0.3: at its own roughness 0.02 (GGX alpha 4e-4)
    // the chi-square grid and the pdf quadrature do not resolve the lobe.
    openpbr_parameters<T> gold = openpbr::gold<T>();
    gold.specular_roughness = 0.3;
    out.push_back({"metal: F82 gold (preset colours, roughness 0.3)", gold});
    out.push_back({"coated plastic (preset: coat of roughness 0.1, eta 1.5)", openpbr::coated_plastic<T>(),
                   layering::albedo_scaling, true});
    out.push_back({"velvet (preset: fuzz 0.5 over a rough base)", openpbr::velvet<T>()});
    openpbr_parameters<T> p;
    p.transmission_weight = 1;
    p.specular_roughness = 0.3;
    out.push_back({"rough glass (roughness 0.3)", p});
    p.geometry_thin_walled = true;
    out.push_back({"thin-walled rough glass (roughness 0.3)", p});
    p = {};
    p.subsurface_weight = 1;
    p.subsurface_color = rgb<T>(0.9, 0.8, 0.6);
    out.push_back({"subsurface (weight 1, colour (0.9, 0.8, 0.6))", p});
    p = {};
    p.thin_film_weight = 1;
    p.thin_film_thickness = 0.4;
    p.specular_roughness = 0.2;
    out.push_back({"thin film (400 nm of eta 1.4, roughness 0.2)", p});
    p = {};
    p.base_metalness = 0.3;
    p.transmission_weight = 0.4;
    p.subsurface_weight = 0.5;
    p.coat_weight = 0.6;
    p.coat_roughness = 0.3;
    p.fuzz_weight = 0.5;
    p.thin_film_weight = 0.5;
    out.push_back({"everything at once (metal 0.3, transmission 0.4, subsurface 0.5, coat 0.6, fuzz 0.5, film 0.5)", p});
    p = openpbr::coated_plastic<T>();
    p.fuzz_weight = 0.5;
    out.push_back({"coated plastic + fuzz 0.5, layering::reciprocal", p, layering::reciprocal, true});
    return out;
}

/// One job per BSDF of the table: each evaluates its model when called.
std::vector<std::function<bsdf_row()>> bsdf_jobs(const settings& s) {
    using namespace shade;
    std::vector<std::function<bsdf_row()>> jobs;
    const auto add = [&](std::string name, const auto& model, double eta_inside, bool has_density,
                         bool opaque = false) {
        jobs.emplace_back([name = std::move(name), model, eta_inside, has_density, opaque, &s] {
            return evaluate_bsdf(name, model, eta_inside, has_density, s, opaque);
        });
    };
    add("Smooth dielectric (eta = 1.5)", smooth_dielectric<T>(1.5), 1.5, false);
    add("Smooth dielectric (eta = 1/1.33, air bubble in water)", smooth_dielectric<T>(1 / 1.33), 1 / 1.33, false);
    add("Thin dielectric (eta = 1.5; air on both sides)", thin_dielectric<T>(1.5), 1, false);
    add("Smooth conductor (gold)", smooth_conductor<T>(metals::gold<T>()), 1, false);
    add("Rough dielectric, GGX alpha = 0.3, eta = 1.5", rough_dielectric<ggx<T>>(ggx<T>(0.3), 1.5), 1.5, true);
    add("Rough dielectric, GGX alpha = 1, eta = 1.5", rough_dielectric<ggx<T>>(ggx<T>(1), 1.5), 1.5, true);
    add("Rough dielectric, GGX alpha = 0.1 x 0.4, eta = 1.5", rough_dielectric<ggx<T>>(ggx<T>(0.1, 0.4), 1.5), 1.5,
        true);
    add("Rough dielectric, Beckmann alpha = 0.3, eta = 1.5", rough_dielectric<beckmann<T>>(beckmann<T>(0.3), 1.5),
        1.5, true);
    add("Rough dielectric, GGX alpha = 0.3, eta = 1/1.33", rough_dielectric<ggx<T>>(ggx<T>(0.3), 1 / 1.33), 1 / 1.33,
        true);
    // The combinators (shade/bsdf/mix.hpp, shade/bsdf/layer.hpp): glass half covered by paint,
    // and a GGX varnish of eta 1.5 over paint in both layerings (opaque: views from outside).
    using varnish = cook_torrance<ggx<T>, dielectric_fresnel<T>, smith_height_correlated<T>>;
    add("Mix: 0.5 rough dielectric (GGX 0.3, eta 1.5) + 0.5 Lambert 0.8",
        mix(rough_dielectric<ggx<T>>(ggx<T>(0.3), 1.5), rgb<T>(0.5), lambert<T>(rgb<T>(0.8)), rgb<T>(0.5)), 1.5, true);
    add("Layer: GGX 0.2 varnish (eta 1.5) over Lambert 0.8, reciprocal",
        layer(varnish(ggx<T>(0.2), dielectric_fresnel<T>(1.5)), lambert<T>(rgb<T>(0.8))), 1, true, true);
    add("Layer: GGX 0.2 varnish (eta 1.5) over Lambert 0.8, albedo scaling (OpenPBR)",
        layer(varnish(ggx<T>(0.2), dielectric_fresnel<T>(1.5)), lambert<T>(rgb<T>(0.8)), T(1), layering::albedo_scaling),
        1, true, true);
    // A microfacet reflection that opts in to reflecting below too (a varnish seen from
    // either side; from inside, eta 1/1.5 and total internal reflection), and the
    // multiple-scattering compensation as a lobe mixed with the single-scattering one (the
    // kulla_conty policy's f; opaque).
    add("Microfacet reflection, both sides: GGX 0.3, eta 1.5 (reflection_sides::both)",
        microfacet_reflection<ggx<T>, dielectric_fresnel<T>, smith_height_correlated<T>, cook_torrance_form::walter,
                              single_scattering, reflection_sides::both>(ggx<T>(0.3), dielectric_fresnel<T>(1.5)),
        1.5, true);
    add("Mix: GGX 0.5 Schlick gold lobe + kulla_conty_lobe (the kulla_conty policy's f)",
        mix(microfacet_reflection<ggx<T>, schlick<T>, smith_height_correlated<T>>(ggx<T>(0.5), schlick<T>(rgb<T>(1, 0.71, 0.29))),
            rgb<T>(1), kulla_conty_lobe<ggx<T>, schlick<T>>(ggx<T>(0.5), schlick<T>(rgb<T>(1, 0.71, 0.29))), rgb<T>(1)),
        1, true, true);
    // The lobe openpbr_surface refracts with (docs/conventions.md).
    add("Compensated rough dielectric, GGX alpha = 0.3, eta = 1.5",
        compensated_rough_dielectric<T>(ggx<T>(0.3), 1.5), 1.5, true);
    // openpbr_surface (shade/material/openpbr_surface.hpp) at its points; a point with a
    // delta lobe is tested for its density part.
    for (const auto& point : openpbr_points()) {
        std::string name = "OpenPBR Surface: " + point.name;
        jobs.emplace_back([name = std::move(name), point, &s] {
            const openpbr_surface<T> m(point.p, point.form);
            if (point.delta)
                return evaluate_bsdf(name, m, check::density_part{m}, point.eta_inside(), true, s,
                                     point.opaque());
            return evaluate_bsdf(name, m, m, point.eta_inside(), true, s, point.opaque());
        });
    }
    return jobs;
}

void print_bsdf_table(const std::vector<bsdf_row>& rows, const settings& s) {
    std::printf("\n### BSDFs over the whole sphere\n\n");
    std::printf("| model | adjoint reciprocal (worst) | max reflected | max transmitted | max total ± SE | energy "
                "conserving | chi-square min p | sampling matches pdf | max ∫pdf ± error | ∫pdf <= 1 |\n");
    std::printf("|---|---|---|---|---|---|---|---|---|---|\n");
    for (const auto& r : rows) {
        std::printf("| %s | %s (%.1e) | %.4f | %.4f | %.4f ± %.1e | %s |", r.name.c_str(),
                    r.reciprocal == check::verdict::pass ? "yes" : "**no**", r.reciprocity_worst, r.max_reflected,
                    r.max_transmitted, r.max_total, r.total_error, word(r.energy));
        if (r.has_density)
            std::printf(" %.3g | %s | %.6f ± %.0e | %s |\n", r.min_p, word(r.chi2), r.max_pdf_integral,
                        r.pdf_integral_error, word(r.normalization));
        else
            std::printf(" – | – | – | – |\n");
    }
    std::printf("\nAdjoint reciprocity (radiance mode; Veach 1997, eq. 5.14): f(l, v) eta_l^2 = f(v, l) eta_v^2 "
                "on 20000 direction pairs over the sphere (the hard cases of the BRDF table on the four "
                "combinations of sides), eta 1 outside and the model's eta inside (1 for the thin pane, air on "
                "both sides, and the opaque conductor), relative tolerance 1e-7 (worst relative difference in "
                "brackets; delta lobes have f = 0 and pass trivially). Albedo (importance mode: the fraction of "
                "the energy arriving along v that leaves on v's side, reflected, or on the other, transmitted): "
                "16 viewing angles (0 to 89 degrees) x 4 azimuths from outside and the same from inside, %zu^2 "
                "samples per view from each model's own sampler; max reflected and max transmitted are the "
                "largest over the views, max total the deciding view's reflected + transmitted (see "
                "`bsdf_energy_conservation`) with its standard error; energy conserving as for the BRDFs "
                "(total + 4 SE <= 1.01 at every view). Chi-square and ∫pdf as for the BRDFs, %zu directions per "
                "view at theta_v = 0, 45, 75, 89 degrees from outside and from inside, the table's tests sharing "
                "alpha = 0.01 (Šidák level 1 - 0.99^(1/%zu) = %.2g) (the layers, the compensated mix and the opaque OpenPBR points, from outside only: from "
                "inside they draw nothing); delta lobes have no density to test (–), and an OpenPBR point with a "
                "delta lobe is tested for its density part (its delta draws counted as draws that return "
                "nothing, whose bin then expects the delta lobes' share). The albedo-scaling layer and "
                "openpbr_surface in its default layering are not reciprocal by construction (the base's factor "
                "1 - E(n·v) depends on v only; shade/bsdf/layer.hpp), so their importance-mode albedo, which "
                "integrates the adjoint f(v, l), may exceed 1 (**fail** above) while the radiance-mode white "
                "furnace the OpenPBR specification promises holds: see the next table.\n",
                s.strata, s.samples, bsdf_chi2_family, check::sidak_significance(0.01, bsdf_chi2_family));
}

// A table cell: a value and its standard error (none when 0).
std::string cell(double a, double se) {
    char text[48];
    if (se > 0) std::snprintf(text, sizeof text, "%.4f ± %.0e", a, se);
    else std::snprintf(text, sizeof text, "%.4f", a);
    return text;
}

// openpbr_surface's white furnace as the specification states it (section "White furnace
// testing"): what a camera looking along v sees in a uniform environment of radiance 1.

// The reading at view cosine mu (azimuth 0.4 rad off the tangent): the mean over strata^2
// stratified draws of weight * eta^2 in radiance mode (inside a solid of index eta a
// uniform environment of radiance 1 has radiance eta^2; Veach 1997, sec. 5.2), or of the
// plain weight in importance mode (the fraction of the energy arriving along v that
// leaves); uc stratified too, its strata dealt to those of u in a random order (Latin
// hypercube sampling). As tests/material/test_openpbr_surface.cpp's furnace(). Returns the
// largest channel's mean and its standard error (that of independent draws; the
// stratification makes the true error smaller).
std::pair<double, double> openpbr_reading(const shade::openpbr_surface<T>& m, double mu, shade::transport_mode mode, int strata) {
    shade::surface_point<T> at;
    at.shading = shade::frame<T>::from_normal_tangent({0, 0, 1}, {1, 0, 0});
    const vec3<T> v = at.shading.to_world(shade::spherical_direction(std::acos(mu), 0.4));
    shade::rng random(11);
    const int n = strata * strata;
    std::vector<int> order(std::size_t(n), 0);
    for (int i = 0; i < n; ++i) order[std::size_t(i)] = i;
    for (int i = n - 1; i > 0; --i) std::swap(order[std::size_t(i)], order[random.next_u32() % std::uint32_t(i + 1)]);
    vec3<T> sum(0), sum2(0);
    for (int i = 0; i < n; ++i) {
        const shade::vec2<T> u((i % strata + random.uniform<double>()) / strata,
                               (i / strata + random.uniform<double>()) / strata);
        const T uc = (order[std::size_t(i)] + random.uniform<double>()) / n;
        const auto s = m.sample(v, uc < 1 ? uc : 0, u, at, mode);
        if (!s) continue;
        const double scale = mode == shade::transport_mode::radiance ? double(s->eta) * double(s->eta) : 1.0;
        const vec3<T> w = s->weight * T(scale);
        sum += w;
        sum2 += w * w;
    }
    const int c = sum.x >= sum.y && sum.x >= sum.z ? 0 : sum.y >= sum.z ? 1 : 2;
    const double mean = sum[c] / n;
    return {mean, std::sqrt(std::max(sum2[c] / n - mean * mean, 0.0) / (n - 1))};
}

// The same parameters with every colour white (base, specular, coat, fuzz, subsurface,
// transmission): the specification's furnace configurations.
shade::openpbr_parameters<T> whitened(shade::openpbr_parameters<T> p) {
    const rgb<T> one(1);
    p.base_weight = 1;
    p.base_color = p.specular_color = p.coat_color = p.fuzz_color = p.subsurface_color = p.transmission_color = one;
    p.specular_weight = std::min(p.specular_weight, T(1));
    return p;
}

constexpr double openpbr_furnace_cosines[] = {1.0, 0.5, 0.2, 0.1};

struct openpbr_furnace_row {
    std::string name;
    std::vector<std::pair<double, double>> radiance; // mean and SE at openpbr_furnace_cosines
    std::vector<std::pair<double, double>> importance;
};

std::vector<openpbr_furnace_row> evaluate_openpbr_furnace(const settings& s) {
    std::vector<openpbr_furnace_row> rows;
    const int strata = int(s.strata);
    for (const auto& point : openpbr_points()) {
        for (const bool white : {false, true}) {
            openpbr_furnace_row r;
            r.name = point.name + (white ? ", every colour white" : "");
            const shade::openpbr_surface<T> m(white ? whitened(point.p) : point.p, point.form);
            for (const double mu : openpbr_furnace_cosines) {
                r.radiance.push_back(openpbr_reading(m, mu, shade::transport_mode::radiance, strata));
                r.importance.push_back(openpbr_reading(m, mu, shade::transport_mode::importance, strata));
            }
            rows.push_back(std::move(r));
        }
    }
    return rows;
}

void print_openpbr_furnace(const std::vector<openpbr_furnace_row>& rows, const settings& s) {
    std::printf("\n### OpenPBR Surface white furnace\n\n");
    std::printf("| point | radiance mode: mu = 1 | 0.5 | 0.2 | 0.1 | importance mode: mu = 1 | 0.5 | 0.2 | 0.1 |\n");
    std::printf("|---|---|---|---|---|---|---|---|---|\n");
    for (const auto& r : rows) {
        std::printf("| %s |", r.name.c_str());
        for (const auto& [a, se] : r.radiance) std::printf(" %s |", cell(a, se).c_str());
        for (const auto& [a, se] : r.importance) std::printf(" %s |", cell(a, se).c_str());
        std::printf("\n");
    }
    std::printf("\nThe points of the BSDF table as given and with every colour white (base, specular, coat, fuzz, "
                "subsurface and transmission colours 1, specular_weight at most 1), seen from outside at view "
                "cosine mu (azimuth 0.4 rad): the largest channel of the mean weight of %zu^2 stratified draws "
                "of the material's own sampler, with the standard error of independent draws (an upper bound: "
                "the draws are stratified). Radiance mode: weight * eta^2, what a camera along v sees in a "
                "uniform white environment (the specification's white furnace, which its albedo scaling makes 1 "
                "for white colours up to the albedo tables, the thin film's included). Importance mode: the "
                "plain weight, which integrates the adjoint f(v, l) over l (shade/bsdf/bsdf.hpp), i.e. "
                "integral f(l', v) |n.l'| over the views l' that scatter into v -- the BSDF table's energy column; "
                "the two differ because albedo scaling weighs the base by 1 - E(v), a function of the view "
                "alone, so f is not reciprocal (the reciprocal form reads the same in both modes).\n",
                s.strata);
}

struct compensation_row {
    std::string name;
    double alpha = 0;
    std::vector<std::string> cells; // at compensation_cosines
};

std::vector<compensation_row> evaluate_compensation(const settings& s, ex::progress& bar) {
    using namespace shade;
    const rgb<T> one(1);
    const std::size_t strata = 4 * s.strata;
    std::vector<compensation_row> rows;
    for (const double a : compensation_alphas) {
        const auto add_own = [&](const std::string& name, const auto& model, std::size_t n) {
            compensation_row r{name, a, {}};
            for (const double mu : compensation_cosines) {
                const auto e = furnace_sample(model, mu, n);
                r.cells.push_back(cell(e.albedo.x, e.standard_error.x));
            }
            rows.push_back(r);
        };
        // The split estimate: the single-scattering lobe by its own visible-normal sampler
        // (low variance), plus the parts exact by quadrature.
        const auto add_split = [&](const std::string& name, const auto& single, const auto& rest) {
            compensation_row r{name, a, {}};
            for (const double mu : compensation_cosines) {
                const auto e = furnace_sample(single, mu, strata);
                r.cells.push_back(cell(e.albedo.x + rest(mu), e.standard_error.x));
            }
            rows.push_back(r);
        };
        const ggx_conductor<T> ggx_single{ggx<T>(a), schlick<T>(one)};
        const compensated_ggx_conductor<T> ggx_ms{ggx<T>(a), schlick<T>(one)};
        const beckmann_conductor<T> beckmann_single{beckmann<T>(a), schlick<T>(one)};
        const compensated_beckmann_conductor<T> beckmann_ms{beckmann<T>(a), schlick<T>(one)};
        add_own("GGX, F = 1, single scattering", ggx_single, strata);
        add_split("GGX, F = 1, Kulla-Conty (split)", ggx_single,
                  [&](double mu) { return multiple_scattering_albedo(ggx_ms, 1.0, mu); });
        add_own("GGX, F = 1, Kulla-Conty (own sampler)", ggx_ms, strata);
        add_own("Beckmann, F = 1, single scattering", beckmann_single, s.strata);
        add_split("Beckmann, F = 1, Kulla-Conty (split)", beckmann_single,
                  [&](double mu) { return multiple_scattering_albedo(beckmann_ms, 1.0, mu); });
        add_own("Beckmann, F = 1, Kulla-Conty (own sampler)", beckmann_ms, 2 * s.strata);
        add_own("rough plastic k_d = 1, uncoupled", make_rough_plastic<T>(a, one), s.strata);
        const coupled_plastic<T> plastic{ggx<T>(a), one};
        const auto& coating = plastic.coating();
        const double f_ms =
            detail::multiple_scattering_fresnel(detail::fresnel_average<T>(dielectric_fresnel<T>(T(1.5))),
                                                coating.average_single_scattering_albedo())
                .x;
        const double e_s_avg =
            detail::albedo_average_lookup(detail::ggx_dielectric_albedo_average, detail::albedo_grid_nodes, a) +
            f_ms * (1 - coating.average_single_scattering_albedo());
        const double a_s = cosine_average([&](double x) { return double(plastic.coating_albedo(T(x))); });
        add_split("coupled plastic k_d = 1 (split)",
                  cook_torrance<ggx<T>, dielectric_fresnel<T>, smith_height_correlated<T>>(ggx<T>(a),
                                                                                           dielectric_fresnel<T>(T(1.5))),
                  [&](double mu) {
                      return multiple_scattering_albedo(coating, f_ms, mu) +
                             (1 - double(plastic.coating_albedo(T(mu)))) * (1 - a_s) / (1 - e_s_avg);
                  });
        add_own("coupled plastic k_d = 1 (own sampler)", plastic, strata);
        bar.advance();
    }
    return rows;
}

void print_compensation(const std::vector<compensation_row>& rows, const settings& s) {
    std::printf("\n### Multiple-scattering compensation\n\n");
    std::printf("| model | alpha |");
    for (const double mu : compensation_cosines) std::printf(" mu = %.2g |", mu);
    std::printf("\n|---|---|");
    for (std::size_t k = 0; k < std::size(compensation_cosines); ++k) std::printf("---|");
    std::printf("\n");
    for (const auto& r : rows) {
        std::printf("| %s | %.2g |", r.name.c_str(), r.alpha);
        for (const auto& c : r.cells) std::printf(" %s |", c.c_str());
        std::printf("\n");
    }
    std::printf("\nDirectional albedo (the white furnace) at view cosine mu = n.v, with its standard error. "
                "Own sampler: the mean weight of the model's sampler, %zu^2 samples (Beckmann, whose sampler is "
                "slower: %zu^2 for single scattering, %zu^2 compensated; uncoupled plastic %zu^2). Split: the "
                "single-scattering lobe estimated with its own visible-normal sampler (%zu^2 samples; its weight "
                "G2/G1 varies little, hence the small error), plus the compensation lobe and the coupled base, "
                "whose albedos are exact by quadrature of the tables the model reads; the own-sampler estimate "
                "agrees with it within its larger error (the mixture of lobes and the draws lost below the "
                "horizon make its weight vary). tests/brdf/test_multiple_scattering.cpp and "
                "test_coupled_plastic.cpp assert the split values in [0.99, 1.001] (conductors) and "
                "[0.97, 1.001] (plastic) and the agreement.\n",
                4 * s.strata, s.strata, 2 * s.strata, s.strata, 4 * s.strata);
}

// Albedo against roughness at two views, compensated and not.
void plot_roughness(const std::filesystem::path& path, const settings& s) {
    using namespace shade;
    const int width = 900, height = 560;
    const float left = 70, right = 560, top = 40, bottom = 500;
    ex::canvas c(width, height, rgb<float>(1));
    const float min_albedo = 0.2f, max_albedo = 1.1f;
    const auto x_of = [&](double alpha) { return left + float(alpha) * (right - left); };
    const auto y_of = [&](double a) {
        return bottom - float((std::clamp(a, double(min_albedo), double(max_albedo)) - min_albedo) / (max_albedo - min_albedo)) *
                            (bottom - top);
    };
    const rgb<float> grey(0.6f);
    for (int k = 2; k <= 11; ++k) {
        const double a = 0.1 * k;
        c.line(left, y_of(a), right, y_of(a), rgb<float>(0.85f), 1.0f);
        char label[16];
        std::snprintf(label, sizeof label, "%.1f", a);
        c.text(left - 40, y_of(a) - 6, label, grey);
    }
    for (int k = 0; k <= 10; k += 2) {
        const double a = 0.1 * k;
        c.line(x_of(a), top, x_of(a), bottom, rgb<float>(0.9f), 1.0f);
        char label[16];
        std::snprintf(label, sizeof label, "%.1f", a);
        c.text(x_of(a) - 10, bottom + 8, label, grey);
    }
    c.line(left, y_of(1.0), right, y_of(1.0), rgb<float>(0.2f), 2.0f);
    c.line(left, bottom, right, bottom, rgb<float>(0.2f), 1.5f);
    c.line(left, top, left, bottom, rgb<float>(0.2f), 1.5f);
    c.text(left, 12, "white furnace: directional albedo vs roughness alpha (F = 1)", rgb<float>(0.1f));
    struct curve {
        std::string name;
        rgb<float> colour;
        std::function<double(double alpha)> albedo;
    };
    const rgb<T> one(1);
    const std::size_t strata = std::max<std::size_t>(s.strata / 2, 32);
    std::vector<curve> curves;
    for (const double mu : {1.0, 0.25}) {
        const float shade_of = mu == 1.0 ? 1.0f : 0.55f;
        char view[32];
        std::snprintf(view, sizeof view, ", mu = %.2g", mu);
        curves.push_back({std::string("GGX single scattering") + view, rgb<float>(0.2f, 0.3f, 0.9f) * shade_of,
                          [=](double a) { return furnace_albedo(ggx_conductor<T>(ggx<T>(a), schlick<T>(one)), mu, strata); }});
        curves.push_back({std::string("GGX + Kulla-Conty") + view, rgb<float>(0.9f, 0.3f, 0.1f) * shade_of, [=](double a) {
                              return furnace_albedo(compensated_ggx_conductor<T>(ggx<T>(a), schlick<T>(one)), mu, strata);
                          }});
        curves.push_back({std::string("Beckmann single scattering") + view, rgb<float>(0.1f, 0.6f, 0.6f) * shade_of,
                          [=](double a) {
                              return furnace_albedo(beckmann_conductor<T>(beckmann<T>(a), schlick<T>(one)), mu, strata);
                          }});
        curves.push_back({std::string("Beckmann + Kulla-Conty") + view, rgb<float>(0.8f, 0.6f, 0.0f) * shade_of, [=](double a) {
                              return furnace_albedo(compensated_beckmann_conductor<T>(beckmann<T>(a), schlick<T>(one)), mu,
                                                    strata);
                          }});
    }
    float legend_y = top;
    for (const auto& cv : curves) {
        std::vector<shade::vec2<float>> pts;
        for (int k = 1; k <= 40; ++k) {
            const double a = 0.025 * k;
            pts.emplace_back(x_of(a), y_of(cv.albedo(a)));
        }
        c.polyline(pts, cv.colour, 2.0f);
        c.line(right + 15, legend_y + 5, right + 35, legend_y + 5, cv.colour, 3.0f);
        c.text(right + 40, legend_y, cv.name, rgb<float>(0.1f), 1.0f);
        legend_y += 16;
    }
    ex::save_png(path, c.to_image());
}

void plot(const std::vector<row>& rows, const std::filesystem::path& path) {
    const float left = 70, right = 560, top = 40, bottom = 500;
    // Tall enough for the legend: one 16-pixel line per model from the top.
    const int width = 900, height = std::max(560, int(top) + 16 * int(rows.size()) + 20);
    ex::canvas c(width, height, rgb<float>(1));
    // Albedo axis from 0 to 2.5 (the unnormalized offenders go above 1).
    const float max_albedo = 2.5f;
    const auto x_of = [&](double theta_deg) { return left + float(theta_deg / 90.0) * (right - left); };
    const auto y_of = [&](double a) { return bottom - float(std::min(a, double(max_albedo)) / max_albedo) * (bottom - top); };
    const rgb<float> grey(0.6f);
    for (int k = 0; k <= 5; ++k) {
        const float a = 0.5f * float(k);
        c.line(left, y_of(a), right, y_of(a), rgb<float>(0.85f), 1.0f);
        char label[16];
        std::snprintf(label, sizeof label, "%.1f", double(a));
        c.text(left - 40, y_of(a) - 6, label, grey);
    }
    for (int d = 0; d <= 90; d += 15) {
        c.line(x_of(d), top, x_of(d), bottom, rgb<float>(0.9f), 1.0f);
        c.text(x_of(d) - 8, bottom + 8, std::to_string(d), grey);
    }
    c.line(left, y_of(1.0), right, y_of(1.0), rgb<float>(0.2f), 2.0f); // albedo = 1
    c.line(left, bottom, right, bottom, rgb<float>(0.2f), 1.5f);
    c.line(left, top, left, bottom, rgb<float>(0.2f), 1.5f);
    c.text(left, 12, "white furnace: directional albedo vs viewing angle (deg)", rgb<float>(0.1f));
    float legend_y = top;
    for (const auto& r : rows) {
        std::vector<shade::vec2<float>> pts;
        for (std::size_t i = 0; i < r.curve.size(); ++i)
            pts.emplace_back(x_of(89.0 * double(i) / double(r.curve.size() - 1)), y_of(r.curve[i]));
        c.polyline(pts, r.colour, 2.0f);
        c.line(right + 15, legend_y + 5, right + 35, legend_y + 5, r.colour, 3.0f);
        std::string label = r.name;
        if (label.size() > 44) label = label.substr(0, 43) + "~";
        c.text(right + 40, legend_y, label, rgb<float>(0.1f), 1.0f);
        legend_y += 16;
    }
    ex::save_png(path, c.to_image());
}

} // namespace

int main(int argc, char** argv) {
    return ex::run_cli("properties", [&] {
        settings s;
        ex::command_line args(argc, argv);
        while (args.next()) {
            if (args.flag("--help") || args.flag("-h")) {
                std::fputs(usage.data(), stdout);
                return 0;
            }
            if (args.option("--out")) s.out = args.path();
            else if (args.option("--roughness-out")) s.roughness_out = args.path();
            else if (args.option("--strata")) s.strata = args.integer<std::size_t>(16, 4096);
            else if (args.option("--samples")) s.samples = args.integer<std::size_t>(1000, 10000000);
            else if (args.flag("--quiet")) s.quiet = true;
            else args.unknown();
        }
        // Formats and paths are checked (and the temporary files created) before the checks run.
        if (s.out) (void)ex::output_format("--out", *s.out, {".png"});
        if (s.roughness_out) (void)ex::output_format("--roughness-out", *s.roughness_out, {".png"});
        std::optional<ex::output_file> png, roughness_png;
        if (s.out) png.emplace(*s.out);
        if (s.roughness_out) roughness_png.emplace(*s.roughness_out);

        const auto jobs = model_jobs(s);
        const auto bsdf_model_jobs = bsdf_jobs(s);
        std::vector<row> rows;
        std::vector<bsdf_row> bsdf_rows;
        std::vector<compensation_row> compensation;
        std::vector<openpbr_furnace_row> openpbr_furnace;
        {
            // One step per model and BSDF, then one per roughness of the compensation table.
            ex::progress bar("properties", jobs.size() + bsdf_model_jobs.size() + std::size(compensation_alphas) + 1,
                             !s.quiet);
            for (const auto& job : jobs) {
                rows.push_back(job());
                bar.advance();
            }
            for (const auto& job : bsdf_model_jobs) {
                bsdf_rows.push_back(job());
                bar.advance();
            }
            compensation = evaluate_compensation(s, bar);
            openpbr_furnace = evaluate_openpbr_furnace(s);
            bar.advance();
        }
        print_tables(rows, s);
        print_bsdf_table(bsdf_rows, s);
        print_openpbr_furnace(openpbr_furnace, s);
        print_compensation(compensation, s);
        if (png) {
            plot(rows, png->temporary());
            png->commit();
            std::fprintf(stderr, "properties: wrote %s\n", s.out->string().c_str());
        }
        if (roughness_png) {
            plot_roughness(roughness_png->temporary(), s);
            roughness_png->commit();
            std::fprintf(stderr, "properties: wrote %s\n", s.roughness_out->string().c_str());
        }
        return 0;
    });
}
