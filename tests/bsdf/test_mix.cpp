// shade::mix: known values (two Lamberts, a weight of 0, a delta lobe's albedo), the
// samples against f and pdf, the chi-square test over the whole sphere, the pdf integral,
// energy, adjoint reciprocity and bad weights.
#include <cmath>
#include <optional>

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/brdf/cook_torrance.hpp>
#include <shade/brdf/fresnel.hpp>
#include <shade/brdf/lambert.hpp>
#include <shade/brdf/microfacet.hpp>
#include <shade/bsdf/mix.hpp>
#include <shade/bsdf/rough_dielectric.hpp>
#include <shade/bsdf/smooth_conductor.hpp>
#include <shade/check/bsdf_energy.hpp>
#include <shade/check/bsdf_reciprocity.hpp>
#include <shade/check/doctest.hpp>

#include "bsdf/support_combine.hpp"

using namespace combine_test;
using shade::transport_mode;

static_assert(shade::bsdf_sampler<shade::mix<shade::lambert<float>, shade::smooth_conductor<float>>>);
static_assert(shade::bsdf_sampler<
              shade::mix<shade::mix<shade::lambert<double>, shade::lambert<double>>, shade::lambert<double>>>);

namespace {

template <class T>
shade::rough_dielectric<shade::ggx<T>> rough_glass() {
    return {shade::ggx<T>(T(0.3)), T(1.5)};
}

template <class T>
using ggx_metal = shade::cook_torrance<shade::ggx<T>, shade::schlick<T>, shade::smith_height_correlated<T>>;

template <class T>
ggx_metal<T> gold_like() {
    return {shade::ggx<T>(T(0.2)), shade::schlick<T>(rgb<T>(T(1), T(0.8), T(0.3)))};
}

} // namespace

TEST_CASE_TEMPLATE("mix: two Lamberts are the Lambert of the weighted albedo, and every sample weighs that albedo", T,
                   float, double) {
    // f = w_1 k_1 / pi + w_2 k_2 / pi = (w_1 k_1 + w_2 k_2) / pi (Lambert 1760, the constant
    // BRDF k / pi). Both lobes draw the cosine density n·l / pi, so the mixture density is
    // p cos / pi + (1 - p) cos / pi = cos / pi whatever p, and weight = f cos / pdf =
    // w_1 k_1 + w_2 k_2 = (0.5 0.8 + 0.25 0.2, 0.5 0.4 + 0.25 0.6, 0.5 0.1 + 0.25 1)
    // = (0.45, 0.35, 0.30) for every sample.
    const auto at = brdf_test::tilted<T>();
    const shade::lambert<T> one(rgb<T>(T(0.8), T(0.4), T(0.1)));
    const shade::lambert<T> two(rgb<T>(T(0.2), T(0.6), T(1)));
    const shade::mix m(one, rgb<T>(T(0.5)), two, rgb<T>(T(0.25)));
    const rgb<T> albedo(T(0.45), T(0.35), T(0.30));
    CHECK(m.probability_a() == doctest::Approx(0.5 / 0.75));
    const vec3<T> v = bsdf_test::view_deg(at, 35);
    shade::rng random(3);
    for (int i = 0; i < 200; ++i) {
        const auto s = m.sample(v, random.uniform<T>(), vec2<T>(random.uniform<T>(), random.uniform<T>()), at);
        if (!s) continue;
        const rgb<T> f = m.f(s->l, v, at);
        for (int c = 0; c < 3; ++c) {
            CHECK(f[c] == doctest::Approx(double(albedo[c]) / shade::pi<double>).epsilon(1e-6));
            CHECK(s->weight[c] == doctest::Approx(double(albedo[c])).epsilon(1e-5));
        }
        CHECK(m.pdf(s->l, v, at) ==
              doctest::Approx(double(glm::dot(at.n(), s->l)) / shade::pi<double>).epsilon(1e-5));
    }
}

TEST_CASE_TEMPLATE("mix: weights (1, 0) give A exactly: the same f, pdf and samples, bit for bit", T, float, double) {
    const auto at = brdf_test::tilted<T>();
    const auto glass = rough_glass<T>();
    const shade::mix m(glass, rgb<T>(1), shade::lambert<T>(rgb<T>(T(0.5))), rgb<T>(0));
    CHECK(m.probability_a() == T(1));
    shade::rng random(11);
    for (const double deg : {0.0, 50.0, 85.0, 130.0, 175.0}) {
        const vec3<T> v = bsdf_test::view_deg(at, deg);
        for (const auto mode : {transport_mode::radiance, transport_mode::importance}) {
            for (int i = 0; i < 100; ++i) {
                const T uc = random.uniform<T>();
                const vec2<T> u(random.uniform<T>(), random.uniform<T>());
                const auto s = m.sample(v, uc, u, at, mode);
                const auto expected = glass.sample(v, uc, u, at, mode);
                REQUIRE(s.has_value() == expected.has_value());
                if (!s) continue;
                CHECK(s->l == expected->l);
                CHECK(s->f == expected->f);
                CHECK(s->pdf == expected->pdf);
                CHECK(s->weight == expected->weight);
                CHECK(s->flags == expected->flags);
                CHECK(s->eta == expected->eta);
                CHECK(m.f(s->l, v, at) == glass.f(s->l, v, at));
                CHECK(m.pdf(s->l, v, at) == glass.pdf(s->l, v, at));
            }
        }
    }
}

TEST_CASE_TEMPLATE("mix: a delta lobe's samples have pdf its probability, and the albedo is w_a F + w_b k_d", T, float,
                   double) {
    // Lobe a, a smooth conductor, is chosen with p_a = 0.3 / (0.3 + 0.7) = 0.3: its sample has
    // pdf 0.3 x 1 and weight w_a F / p_a = F (pbrt-v4's rule, shade/bsdf/bsdf.hpp). Lobe b,
    // Lambert k_d = 0.6, has the density sample f = w_b k_d / pi (the delta lobe adds
    // nothing at l), pdf (1 - p_a) cos / pi, weight w_b k_d / (1 - p_a) = 0.6. The expected
    // weight in importance mode is p_a F + (1 - p_a) 0.6 = w_a F + w_b k_d = 0.3 F + 0.42,
    // with F = F_conductor(n·v) of the metal (Born, Wolf 1999, sec. 14.2).
    const auto at = brdf_test::tilted<T>();
    const rgb<T> eta(T(0.2), T(0.9), T(1.1));
    const rgb<T> kappa(T(3.9), T(2.4), T(2.2));
    const shade::smooth_conductor<T> metal(eta, kappa);
    const shade::mix m(metal, rgb<T>(T(0.3)), shade::lambert<T>(rgb<T>(T(0.6))), rgb<T>(T(0.7)));
    for (const double deg : {0.0, 45.0, 80.0}) {
        CAPTURE(deg);
        const vec3<T> v = bsdf_test::view_deg(at, deg);
        const rgb<T> F = metal.fresnel().F(glm::dot(at.n(), v));
        const auto s = m.sample(v, T(0.1), vec2<T>(T(0.5)), at);
        REQUIRE(s.has_value());
        CHECK(shade::is_specular(s->flags));
        CHECK(s->pdf == doctest::Approx(0.3));
        for (int c = 0; c < 3; ++c) CHECK(s->weight[c] == doctest::Approx(double(F[c])).epsilon(1e-5));
        const auto a = shade::check::bsdf_albedo(m, v, at, 64);
        for (int c = 0; c < 3; ++c) {
            const double expected = 0.3 * double(F[c]) + 0.42;
            CHECK(std::abs(a.total[c] - expected) <= 4 * a.total_error[c] + 1e-5);
        }
    }
    CHECK(expect_consistent_samples(m, at, {0.0, 60.0, 88.0}) > 0);
}

TEST_CASE_TEMPLATE("mix: sample draws l with the density pdf over the whole sphere, and agrees with f and pdf", T,
                   float, double) {
    // Rough glass with a Lambertian layer (v on both sides: from inside only the glass
    // draws, and the Lambert lobe's share is lost), and a mix nested in a mix: 2 models x 4
    // views x 2 scalar types = 16 chi-square tests at a family-wise level of 1e-3.
    const auto at = brdf_test::tilted<T>();
    const shade::mix glass_and_paint(rough_glass<T>(), rgb<T>(T(0.6)), shade::lambert<T>(rgb<T>(T(0.8), T(0.5), T(0.2))),
                                     rgb<T>(T(0.4), T(0.3), T(0.2)));
    const shade::mix nested(shade::mix(gold_like<T>(), rgb<T>(T(0.5)), shade::lambert<T>(rgb<T>(T(0.7))), rgb<T>(T(0.5))),
                            rgb<T>(T(0.8)), rough_glass<T>(), rgb<T>(T(0.2)));
    expect_sampling(glass_and_paint, "glass + paint", at, {0.0, 45.0, 80.0, 150.0}, 16);
    expect_sampling(nested, "(gold + paint) + glass", at, {0.0, 45.0, 80.0, 150.0}, 16);
    CHECK(expect_consistent_samples(glass_and_paint, at, {0.0, 45.0, 85.0, 120.0, 170.0}) > 1000);
    CHECK(expect_consistent_samples(nested, at, {10.0, 70.0, 160.0}) > 1000);
}

TEST_CASE_TEMPLATE("mix: energy conservation on both sides and adjoint reciprocity with the glass's eta", T, float,
                   double) {
    // Weights summing to 1 of two models that conserve energy conserve it (albedo
    // w_a E_a + w_b E_b <= 1); a linear blend of reciprocal lobes is reciprocal, with the
    // glass's eta 1.5 for its refractions (the Lambert lobe has no transmission).
    const auto at = brdf_test::tilted<T>();
    const shade::mix m(rough_glass<T>(), rgb<T>(T(0.5)), shade::lambert<T>(rgb<T>(1)), rgb<T>(T(0.5)));
    shade::check::albedo_options options{.strata = 64, .view_angles = 6, .azimuths = 2};
    options.model = "glass + white paint";
    shade::check::doctest_expect(shade::check::bsdf_energy_conservation(m, at, options));
    shade::check::pair_options pairs{.pairs = 4000};
    pairs.model = "glass + white paint";
    shade::check::doctest_expect(shade::check::adjoint_reciprocity(m, at, 1.5, pairs));
}

TEST_CASE("mix: bad weights are refused by name") {
    const shade::lambert<double> white(rgb<double>(1));
    CHECK_THROWS_WITH_AS(shade::mix(white, rgb<double>(-0.1, 0, 0), white, rgb<double>(1)), doctest::Contains("w_a"),
                         shade::invalid_parameter);
    CHECK_THROWS_WITH_AS(shade::mix(white, rgb<double>(1), white, rgb<double>(std::nan(""))),
                         doctest::Contains("w_b"), shade::invalid_parameter);
}
