// Every shipped reflection model with a sampler through the sampling checks of
// shade/check/sampling.hpp (chi-square of sample against pdf, sample consistency, pdf
// normalization and coverage) at several parameter sets and views down to grazing, in
// float and double; and the energy check with the models' own samplers on the sharp lobes
// that the cosine/lobe mixture cannot resolve.
//
// The sample counts keep this file to seconds: 40000 draws per chi-square test detect a
// pdf off by 5 % in one ring (tests/check/test_sampling.cpp shows the checks catching
// broken samplers).
#include <optional>
#include <string>
#include <vector>

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/brdf/aliases.hpp>
#include <shade/brdf/ashikhmin_shirley.hpp>
#include <shade/brdf/blinn_phong.hpp>
#include <shade/brdf/cook_torrance.hpp>
#include <shade/brdf/coupled_plastic.hpp>
#include <shade/brdf/eon.hpp>
#include <shade/brdf/lambert.hpp>
#include <shade/brdf/microfacet_reflection.hpp>
#include <shade/brdf/oren_nayar.hpp>
#include <shade/brdf/phong.hpp>
#include <shade/check/doctest.hpp>
#include <shade/check/properties.hpp>
#include <shade/shading/checker.hpp>
#include <shade/shading/gradient.hpp>

#include "model_point.hpp"

namespace {

using shade::rgb;

template <class T>
shade::surface_point<T> point() {
    return check_test::model_point<T>();
}

// Views from the normal to 89 degrees; azimuth 0.4 rad from the tangent (between t and b,
// so an anisotropic lobe is seen neither along nor across its axes).
constexpr double view_angles[] = {0, 45, 75, 89};

// Upper bound on the chi-square tests of this file; the family's alpha is 0.01 (Šidák).
constexpr std::size_t chi2_family = 400;

template <class T>
shade::vec3<T> view(const shade::surface_point<T>& at, double theta_deg) {
    const double theta = theta_deg * shade::pi<double> / 180;
    return glm::normalize(at.shading.to_world(shade::spherical_direction(T(theta), T(0.4))));
}

/// Runs every sampling check on `model` (which must have a sampler).
template <class B>
void expect_sampling(const B& model, const std::string& name) {
    static_assert(shade::sampled_brdf<B>);
    using T = shade::scalar_of<B>;
    const auto at = point<T>();
    for (const double theta : view_angles) {
        CAPTURE(theta);
        shade::check::chi2_options chi2{.samples = 40000, .tests = chi2_family};
        chi2.model = name;
        const auto v = view(at, theta);
        shade::check::doctest_expect(shade::check::chi2_goodness_of_fit(model, v, at, chi2));
        shade::check::doctest_expect(shade::check::pdf_normalization(model, v, at, chi2));
    }
    shade::check::sample_options consistency{.views = 200, .samples_per_view = 20};
    consistency.model = name;
    shade::check::doctest_expect(shade::check::sample_consistency(model, at, consistency));
    shade::check::pair_options coverage{.pairs = 4000};
    coverage.model = name;
    shade::check::doctest_expect(shade::check::pdf_coverage(model, at, coverage));
}

/// The energy check with the model's own sampler at 96^2 samples per view.
template <class B>
void expect_energy_with_sampler(const B& model, const std::string& name) {
    static_assert(shade::sampled_brdf<B>);
    shade::check::albedo_options albedo{.strata = 96, .view_angles = 10, .azimuths = 3,
                                        .estimator = shade::check::albedo_estimator::own_sampler};
    albedo.model = name;
    shade::check::doctest_expect(shade::check::energy_conservation(model, point<shade::scalar_of<B>>(), albedo));
}

/// A shipped model whose pdf (in pdf() and in its samples, with the weight to match)
/// is `factor` times the true density: its samples agree with its f and pdf, but the
/// distribution is wrong.
template <class B>
struct pdf_scaled {
    using scalar_type = shade::scalar_of<B>;
    using T = scalar_type;
    B inner;
    T factor;
    [[nodiscard]] shade::rgb<T> f(const shade::vec3<T>& l, const shade::vec3<T>& v, const shade::surface_point<T>& at) const {
        return inner.f(l, v, at);
    }
    [[nodiscard]] T pdf(const shade::vec3<T>& l, const shade::vec3<T>& v, const shade::surface_point<T>& at) const {
        return factor * inner.pdf(l, v, at);
    }
    [[nodiscard]] std::optional<shade::brdf_sample<T>> sample(const shade::vec3<T>& v, T uc, const shade::vec2<T>& u,
                                                              const shade::surface_point<T>& at) const {
        const auto s = inner.sample(v, uc, u, at);
        if (!s) return s;
        return shade::detail::make_brdf_sample(s->l, s->f, factor * s->pdf, glm::dot(s->l, at.n()));
    }
};

/// A shipped model that draws its lobe as if seen from the normal (its axis in the wrong
/// place for any other view) but reports f and pdf for the true view.
template <class B>
struct sampled_from_normal {
    using scalar_type = shade::scalar_of<B>;
    using T = scalar_type;
    B inner;
    [[nodiscard]] shade::rgb<T> f(const shade::vec3<T>& l, const shade::vec3<T>& v, const shade::surface_point<T>& at) const {
        return inner.f(l, v, at);
    }
    [[nodiscard]] T pdf(const shade::vec3<T>& l, const shade::vec3<T>& v, const shade::surface_point<T>& at) const {
        return inner.pdf(l, v, at);
    }
    [[nodiscard]] std::optional<shade::brdf_sample<T>> sample(const shade::vec3<T>& v, T uc, const shade::vec2<T>& u,
                                                              const shade::surface_point<T>& at) const {
        if (glm::dot(v, at.n()) <= 0) return std::nullopt;
        const auto s = inner.sample(at.n(), uc, u, at);
        if (!s) return s;
        return shade::detail::make_brdf_sample(s->l, f(s->l, v, at), pdf(s->l, v, at), glm::dot(s->l, at.n()));
    }
};

/// The sampling checks catch `model` made wrong both ways, at a 45-degree view.
template <class B>
void expect_broken_caught(const B& model, const std::string& name) {
    using T = shade::scalar_of<B>;
    const auto at = point<T>();
    const auto v = view(at, 45);
    shade::check::chi2_options chi2{.samples = 40000};
    chi2.model = name + ", pdf x 1.05";
    const pdf_scaled<B> scaled{model, T(1.05)};
    shade::check::doctest_expect_failure(shade::check::chi2_goodness_of_fit(scaled, v, at, chi2));
    // The normalization check sees the excess only where it lifts ∫pdf above 1 (a lobe
    // that loses mass below the horizon can hide 5 %); its integral scales exactly.
    const auto true_integral = shade::check::pdf_normalization(model, v, at, chi2);
    const auto scaled_integral = shade::check::pdf_normalization(scaled, v, at, chi2);
    CHECK(scaled_integral.worst == doctest::Approx(1.05 * true_integral.worst).epsilon(1e-4));
    if (1.05 * true_integral.worst > 1.002) shade::check::doctest_expect_failure(scaled_integral);
    shade::check::doctest_expect(shade::check::sample_consistency(scaled, at, {.views = 50, .samples_per_view = 20}));
    chi2.model = name + ", drawn as if seen from n";
    shade::check::doctest_expect_failure(
        shade::check::chi2_goodness_of_fit(sampled_from_normal<B>{model}, v, at, chi2));
}

} // namespace

TEST_CASE_TEMPLATE("the sampling checks catch a shipped sampler made wrong", T, float, double) {
    using namespace shade;
    const auto run = [](const auto& model, const std::string& name) { expect_broken_caught(model, name); };
    const rgb<T> one(1), zero(0);
    // A 5 % excess of pdf is caught; so is a glossy lobe drawn around the wrong axis. (A
    // Lambert lobe does not depend on v, so only the pdf excess applies to it; it is
    // tested in tests/check/test_sampling.cpp.)
    run(normalized_phong<T>(zero, one, T(20)), "normalized phong s = 20");
    run(cook_torrance<ggx<T>, schlick<T>, smith_ggx<T>>(ggx<T>(T(0.3)), schlick<T>(one)), "ggx 0.3");
    run(cook_torrance<beckmann<T>, schlick<T>, smith_beckmann<T>>(beckmann<T>(T(0.01)), schlick<T>(one)),
                 "beckmann 0.01");
}

TEST_CASE_TEMPLATE("every sampled model passes the sampling checks", T, float, double) {
    using namespace shade;
    const auto run = [](const auto& model, const std::string& name) { expect_sampling(model, name); };
    const rgb<T> one(1), half(T(0.5)), zero(0);
    run(lambert<T>(rgb<T>(T(0.8))), "lambert");
    run(oren_nayar<T>(rgb<T>(T(0.8)), T(0.3)), "oren-nayar sigma 0.3");
    run(oren_nayar<T>(one, T(1)), "oren-nayar sigma 1");
    run(eon<T>(rgb<T>(T(0.8)), T(0.3)), "eon r 0.3");
    run(eon<T>(one, T(1)), "eon r 1");
    run(eon<T, eon_albedo::approximate>(one, T(1)), "eon (fitted albedo) r 1");
    run(fujii_oren_nayar<T>(one, T(1)), "fujii oren-nayar r 1");
    for (const T s : {T(1), T(20), T(10000)}) {
        const std::string e = std::to_string(int(s));
        run(normalized_phong<T>(half, half, s), "normalized phong, s = " + e);
        run(normalized_phong<T>(zero, one, s), "normalized phong, k_s = 1, s = " + e);
        run(blinn_phong<T>(half, half, s), "normalized blinn-phong, s = " + e);
    }
    run(classic_phong<T>(zero, one, T(10)), "classic phong");
    run(modified_phong<T>(zero, one, T(2)), "modified phong");
    run(ashikhmin_shirley<T>(rgb<T>(T(0.8)), rgb<T>(T(0.2)), T(10), T(200)), "ashikhmin-shirley 10 x 200");
    run(ashikhmin_shirley<T>(rgb<T>(T(0.3)), rgb<T>(T(0.7)), T(1000), T(1000)), "ashikhmin-shirley 1000");
    for (const T a : {T(0.01), T(0.3), T(1)}) {
        const std::string p = std::to_string(double(a)).substr(0, 4);
        run(cook_torrance<ggx<T>, schlick<T>, smith_ggx<T>>(ggx<T>(a), schlick<T>(one)),
                     "cook-torrance ggx/smith, alpha = " + p + ", F = 1");
        run(cook_torrance<beckmann<T>, schlick<T>, smith_beckmann<T>>(beckmann<T>(a), schlick<T>(one)),
                     "cook-torrance beckmann/smith, m = " + p + ", F = 1");
    }
    run(cook_torrance<ggx<T>, schlick<T>, smith_ggx<T>>(ggx<T>(T(0.05), T(0.5)), schlick<T>(one)),
        "cook-torrance ggx/smith, alpha 0.05 x 0.5");
    run(cook_torrance<beckmann<T>, schlick<T>, smith_beckmann<T>>(beckmann<T>(T(0.05), T(0.5)), schlick<T>(one)),
        "cook-torrance beckmann/smith, m 0.05 x 0.5");
    run(cook_torrance<ggx<T>, schlick<T>, smith_height_correlated<T>>(ggx<T>(T(0.05), T(0.5)), schlick<T>(one)),
        "cook-torrance ggx/height-correlated smith, alpha 0.05 x 0.5");
    run(cook_torrance<beckmann<T>, schlick<T>, smith_separable<T>>(beckmann<T>(T(0.3)), schlick<T>(one)),
        "cook-torrance beckmann/exact separable smith, m = 0.3");
    run(cook_torrance<ggx<T>, schlick<T>, smith_ggx<T>>(ggx<T>(T(0.3)), schlick<T>(rgb<T>(T(0.04))), half, half),
                 "cook-torrance ggx, k_s = k_d = 0.5");
    run(cook_torrance<beckmann<T>, dielectric_fresnel<T>, v_groove<T>>(beckmann<T>(T(0.3)),
                                                                               dielectric_fresnel<T>(T(1.5))),
                 "cook-torrance beckmann/v-groove, glass");
    run(compensated_ggx_conductor<T>(ggx<T>(T(1)), schlick<T>(one)), "compensated ggx (kulla-conty), alpha = 1, F = 1");
    run(compensated_ggx_conductor<T>(ggx<T>(T(0.05), T(0.5)), schlick<T>(rgb<T>(T(1), T(0.71), T(0.29)))),
        "compensated ggx (kulla-conty), alpha 0.05 x 0.5, gold");
    run(compensated_beckmann_conductor<T>(beckmann<T>(T(0.5)), schlick<T>(one)), "compensated beckmann, m = 0.5, F = 1");
    run(microfacet_reflection<ggx<T>, schlick<T>, smith_height_correlated<T>>(ggx<T>(T(0.5)),
                                                                             schlick<T>(rgb<T>(T(1), T(0.71), T(0.29)))),
        "microfacet reflection lobe, ggx 0.5, gold");
    run(microfacet_reflection<beckmann<T>, schlick<T>, smith_height_correlated<T>, cook_torrance_form::walter, kulla_conty>(
            beckmann<T>(T(0.3), T(0.1)), schlick<T>(one)),
        "microfacet reflection lobe, compensated beckmann 0.3 x 0.1");
    run(coupled_plastic<T>(ggx<T>(T(0.5)), one), "coupled plastic, alpha = 0.5, k_d = 1");
    run(checker<lambert<T>, normalized_phong<T>>(lambert<T>(one), normalized_phong<T>(zero, one, T(10)), T(1)),
                 "checker of lambert and phong");
    run(gradient<lambert<T>, blinn_phong<T>>(lambert<T>(one), blinn_phong<T>(zero, one, T(10)),
                                                      vec3<T>(0, 0, 1), T(3)),
                 "gradient of lambert and blinn-phong");
}

TEST_CASE_TEMPLATE("sharp lobes conserve energy when their own sampler estimates the albedo", T, float, double) {
    using namespace shade;
    // The cosine/lobe mixture puts too few samples in these lobes to bound their albedo
    // (it estimated 1.03-1.04 for GGX alpha = 0.01 and Beckmann m = 0.01, whose true
    // albedo is <= 1); their samplers put every sample in the lobe.
    const auto run = [](const auto& model, const std::string& name) { expect_energy_with_sampler(model, name); };
    const rgb<T> one(1), zero(0);
    run(cook_torrance<ggx<T>, schlick<T>, smith_ggx<T>>(ggx<T>(T(0.01)), schlick<T>(one)),
                 "ggx alpha = 0.01, F = 1");
    run(cook_torrance<beckmann<T>, schlick<T>, smith_beckmann<T>>(beckmann<T>(T(0.01)), schlick<T>(one)),
                 "beckmann m = 0.01, F = 1");
    run(normalized_phong<T>(zero, one, T(10000)), "normalized phong s = 10000");
    run(blinn_phong<T>(zero, one, T(10000)), "normalized blinn-phong s = 10000");
    // With the mixture forced, the verdict is what its standard error supports: not a
    // (false) fail.
    using sharp_ggx = cook_torrance<ggx<T>, schlick<T>, smith_ggx<T>>;
    const auto mixture = check::energy_conservation(
        sharp_ggx(ggx<T>(T(0.01)), schlick<T>(one)), point<T>(),
        {.strata = 96, .view_angles = 10, .azimuths = 3, .estimator = check::albedo_estimator::mixture});
    CHECK(mixture.outcome != check::verdict::fail);
}
