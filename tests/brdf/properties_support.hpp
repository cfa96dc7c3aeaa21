#pragma once
// Every check of the property kit (shade/check) on one sampled BRDF, for the BRDF tests of
// models that must pass them all: positivity, reciprocity, pdf coverage, sample
// consistency, chi-square and pdf normalization at three views down to 87 degrees, and
// energy conservation with the model's own sampler.

#include <string>

#include <glm/geometric.hpp>

#include <shade/brdf/brdf.hpp>
#include <shade/check/doctest.hpp>
#include <shade/check/properties.hpp>
#include <shade/core/math.hpp>
#include <shade/core/sampling.hpp>

namespace brdf_test {

/// Runs every property check on `model` at a tilted point; `chi2_tests` is the number of
/// chi-square tests of the calling file (their Šidák family). A model documented as not
/// reciprocal (reciprocal = false) must fail the reciprocity check instead of passing it.
template <shade::sampled_brdf B>
void expect_every_property(const B& model, const std::string& name, std::size_t chi2_tests, bool reciprocal = true) {
    namespace check = shade::check;
    using T = shade::scalar_of<B>;
    shade::surface_point<T> at;
    at.shading = shade::frame<T>::from_normal_tangent(glm::normalize(shade::vec3<T>(T(0.2), T(0.3), T(1))), {1, 0, 0});
    check::pair_options pairs{.pairs = 4000};
    pairs.model = name;
    check::doctest_expect(check::positivity(model, at, pairs));
    if (reciprocal) {
        check::doctest_expect(check::reciprocity(model, at, pairs));
    } else {
        const auto r = check::reciprocity(model, at, pairs);
        MESSAGE(name << ": worst relative reciprocity difference " << r.worst);
        CHECK_FALSE(r.passed);
    }
    check::doctest_expect(check::pdf_coverage(model, at, pairs));
    check::sample_options consistency{.views = 100, .samples_per_view = 20};
    consistency.model = name;
    check::doctest_expect(check::sample_consistency(model, at, consistency));
    for (const double theta_deg : {0.0, 60.0, 87.0}) {
        const auto v = glm::normalize(
            at.shading.to_world(shade::spherical_direction(T(theta_deg * shade::pi<double> / 180), T(0.4))));
        check::chi2_options chi2{.samples = 40000, .tests = chi2_tests};
        chi2.model = name;
        check::doctest_expect(check::chi2_goodness_of_fit(model, v, at, chi2));
        check::doctest_expect(check::pdf_normalization(model, v, at, chi2));
    }
    // A mixture of lobes makes the sampler's weight vary (its standard deviation is ~0.4
    // for a compensated lobe at alpha = 0.7), so 320^2 samples per view keep 4 standard
    // errors under the check's 1 % margin.
    check::albedo_options albedo{.strata = 320, .view_angles = 3, .azimuths = 1,
                                 .estimator = check::albedo_estimator::own_sampler};
    albedo.model = name;
    check::doctest_expect(check::energy_conservation(model, at, albedo));
}

} // namespace brdf_test
