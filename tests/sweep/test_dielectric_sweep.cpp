// The property kit over every shipped rough dielectric (issue 31, item 4): rough_dielectric
// with GGX and with Beckmann, compensated_rough_dielectric, each at alpha 0.05, 0.3, 1 and
// anisotropic 0.1 x 0.4, with eta 1.33, 1.5 and 2.4, seen from outside at 0, 30, 60 and 85
// degrees and from inside at the mirror images of those views, in float and double:
//   - chi-square of sample against pdf over the whole sphere, with the zoomed grid around the
//     reflection and refraction lobes where they are sharp (shade/check/sampling.hpp), every
//     test of this file sharing a family-wise level of 1e-3 (Šidák);
//   - ∫pdf over the sphere <= 1 + 1e-3 (on the zoomed grid where a lobe is sharp);
//   - sample_consistency from both sides in both transport modes with eta_inside = eta, and
//     pdf_coverage over the sphere;
//   - energy: reflected + transmitted albedo (importance mode) must not exceed 1 + 0.01 at
//     any view on either side (bsdf_energy_conservation; inconclusive allowed where the
//     compensated model reaches 1 within the estimate's error).
// And issue #31's band for compensated_rough_dielectric over Beckmann (whose albedo table is
// an upper envelope checked on a lattice of points): R + T in [0.99, 1.001] at the issue's
// lattice of views and between its nodes, and at 600 random views between the table's nodes
// (tests/bsdf/test_compensated_rough_dielectric.cpp runs 40 in script/test).
// tests/bsdf/test_rough_dielectric.cpp runs a slice of the chi-square matrix in every
// script/test; this file runs it all, in script/test --all only (tests/sweep/CMakeLists.txt).
// Each test case prints what it measured (smallest p-value, largest ∫pdf, how many tests
// ran on the zoomed grid), which docs/properties.md records.
#include <algorithm>
#include <cstddef>
#include <cstdio>
#include <string>

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/brdf/microfacet/beckmann.hpp>
#include <shade/brdf/microfacet/ggx.hpp>
#include <shade/bsdf/compensated_rough_dielectric.hpp>
#include <shade/bsdf/rough_dielectric.hpp>
#include <shade/check/bsdf_energy.hpp>
#include <shade/check/doctest.hpp>
#include <shade/check/sampling.hpp>

#include "bsdf/compensated_energy.hpp"
#include "check/model_point.hpp"

namespace {

constexpr double etas[] = {1.33, 1.5, 2.4};
constexpr double views[] = {0, 30, 60, 85, 180, 150, 120, 95}; // outside, then inside
// Distributions: alpha 0.05, 0.3, 1 and 0.1 x 0.4.
constexpr double alphas[][2] = {{0.05, 0.05}, {0.3, 0.3}, {1, 1}, {0.1, 0.4}};

// Chi-square tests in this file: 3 model families x 4 distributions x 3 etas x 8 views x 2
// scalar types. Each call that runs the zoomed grid splits its share in two (Šidák).
constexpr std::size_t chi2_family = 3 * 4 * 3 * 8 * 2;

/// What one test case measured.
struct tally {
    std::size_t tests = 0;
    std::size_t zoomed = 0;
    double min_p = 1;
    double max_integral = 0;
    double worst_consistency = 0;
    double max_total_albedo = 0;
    std::string max_albedo_message;
    std::size_t energy_passed = 0;
    std::size_t energy_inconclusive = 0;
};

std::string number(double x) {
    std::string s = std::to_string(x);
    while (s.size() > 1 && s.back() == '0') s.pop_back();
    if (!s.empty() && s.back() == '.') s.pop_back();
    return s;
}

template <class B>
void sweep(const B& model, const std::string& name, double eta, tally& out) {
    using T = shade::scalar_of<B>;
    namespace check = shade::check;
    INFO(name);
    const auto at = check_test::model_point<T>();
    for (const double deg : views) {
        CAPTURE(deg);
        const double theta = deg * shade::pi<double> / 180;
        const shade::vec3<T> v =
            glm::normalize(at.shading.to_world(shade::spherical_direction(T(theta), T(0.4))));
        check::chi2_options chi2{.samples = 40000, .alpha = 1e-3, .tests = chi2_family};
        chi2.model = name;
        const auto r = check::chi2_goodness_of_fit(model, v, at, chi2);
        check::doctest_expect(r);
        ++out.tests;
        if (r.zoomed) ++out.zoomed;
        out.min_p = std::min(out.min_p, r.p_value);
        const auto integral = check::pdf_normalization(model, v, at, chi2);
        check::doctest_expect(integral);
        out.max_integral = std::max(out.max_integral, integral.worst);
    }
    check::sample_options consistency{.views = 100, .samples_per_view = 20};
    consistency.model = name;
    consistency.eta_inside = eta;
    const auto c = check::sample_consistency(model, at, consistency);
    check::doctest_expect(c);
    out.worst_consistency = std::max(out.worst_consistency, c.worst);
    check::pair_options coverage{.pairs = 2000};
    coverage.model = name;
    check::doctest_expect(check::pdf_coverage(model, at, coverage));
    check::albedo_options albedo{.strata = 64, .view_angles = 6, .azimuths = 2};
    albedo.model = name;
    const auto e = check::bsdf_energy_conservation(model, at, albedo);
    CHECK_MESSAGE(e.outcome != check::verdict::fail, e.message);
    if (e.outcome == check::verdict::pass) ++out.energy_passed;
    if (e.outcome == check::verdict::inconclusive) ++out.energy_inconclusive;
    if (e.worst > out.max_total_albedo) {
        out.max_total_albedo = e.worst;
        out.max_albedo_message = e.message;
    }
}

void report(const std::string& what, const tally& t) {
    char text[512];
    std::snprintf(text, sizeof text,
                  "%s: %zu chi-square tests (%zu on the zoomed grid), smallest p %.3g (level %.3g, %.3g on the zoomed "
                  "grid), largest integral of pdf %.6f, worst sample consistency %.2g, energy %zu pass, %zu "
                  "inconclusive; the largest total albedo: ",
                  what.c_str(), t.tests, t.zoomed, t.min_p, shade::check::sidak_significance(1e-3, chi2_family),
                  shade::check::sidak_significance(1e-3, 2 * chi2_family), t.max_integral, t.worst_consistency,
                  t.energy_passed, t.energy_inconclusive);
    const std::string line = std::string(text) + t.max_albedo_message;
    MESSAGE(line);
}

} // namespace

TEST_CASE_TEMPLATE("rough_dielectric with GGX and Beckmann: alpha 0.05, 0.3, 1 and 0.1 x 0.4, eta 1.33, 1.5, 2.4", T, float,
                   double) {
    tally t;
    for (const double eta : etas) {
        for (const auto& a : alphas) {
            const std::string p = number(a[0]) + (a[0] == a[1] ? "" : " x " + number(a[1])) + ", eta " + number(eta);
            sweep(shade::rough_dielectric<shade::ggx<T>>(shade::ggx<T>(T(a[0]), T(a[1])), T(eta)),
                  "rough dielectric ggx " + p, eta, t);
            sweep(shade::rough_dielectric<shade::beckmann<T>>(shade::beckmann<T>(T(a[0]), T(a[1])), T(eta)),
                  "rough dielectric beckmann " + p, eta, t);
        }
    }
    CHECK(t.zoomed > 0);
    CHECK(t.energy_passed > 0);
    report("rough_dielectric", t);
}

TEST_CASE_TEMPLATE("compensated_rough_dielectric: alpha 0.05, 0.3, 1 and 0.1 x 0.4, eta 1.33, 1.5, 2.4", T, float, double) {
    tally t;
    for (const double eta : etas) {
        for (const auto& a : alphas) {
            const std::string p = number(a[0]) + (a[0] == a[1] ? "" : " x " + number(a[1])) + ", eta " + number(eta);
            sweep(shade::compensated_rough_dielectric<T>(shade::ggx<T>(T(a[0]), T(a[1])), T(eta)),
                  "compensated rough dielectric ggx " + p, eta, t);
        }
    }
    CHECK(t.zoomed > 0);
    report("compensated_rough_dielectric", t);
}

TEST_CASE("compensated_rough_dielectric over Beckmann: R + T in [0.99, 1.001] for m <= 1, mu >= 0.05, eta in [1.05, 3], "
          "both sides") {
    // The Beckmann table is an upper envelope of E (its generated header: every node raised
    // until the interpolated table is at least a fresh estimate + 3e-4 at the middle of every
    // cell edge, face and interior and at the quarters of every cell along the view
    // coordinate, with mu >= 0.05), so R + T = 1 + E_true - E_table stays at or below 1 up to
    // the estimates' noise; the point-value table it replaced gave up to 1.0020 over these
    // views and 1.0040 between its nodes.
    const auto make = [](double m, double eta) {
        return shade::compensated_rough_dielectric<double, shade::beckmann<double>>{shade::beckmann<double>(m), eta};
    };
    bsdf_test::expect_energy_conserved(make, "Beckmann", 1.001);
    // Between the table's nodes in eta, m and mu, seen from inside (where interpolation
    // erred low before the envelope). The largest R + T was at eta 1.05, m 0.05, mu 0.2, below
    // the critical angle (mu_c = 0.30) of so weak an interface, where E falls steeply along m
    // (0.9997 at m 0.04, 0.9874 at m 0.06): 1.0011 +- 1e-4 on a grid with 16 nodes along
    // sqrt(m), 0.9981 on the 21 of dielectric_beckmann_albedo_grid (a probe, 256^2 samples).
    bsdf_test::view_set between;
    between.etas = {1.05, 1.1, 1.35, 1.8, 2.7};
    between.alphas = {0.05, 0.2, 0.45, 0.8};
    between.mus = {0.1, 0.2, 0.35, 0.7};
    between.sides = {true};
    bsdf_test::expect_energy_conserved(make, "Beckmann, between nodes, inside", 1.001, between);
}

TEST_CASE("compensated_rough_dielectric over Beckmann: R + T in [0.99, 1.001] at 600 random views between the nodes") {
    const auto make = [](double m, double eta) {
        return shade::compensated_rough_dielectric<double, shade::beckmann<double>>{shade::beckmann<double>(m), eta};
    };
    bsdf_test::expect_energy_conserved_at(make, "Beckmann, random views", 1.001, bsdf_test::random_views(3131, 600));
}
