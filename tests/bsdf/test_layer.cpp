// shade::layer: known values (a Lambertian coat, a coat of weight 0, a delta coat's
// albedo, the white furnace), the samples against f and pdf, the chi-square test, the pdf
// integral, energy, reciprocity of the reciprocal form and bad parameters.
#include <algorithm>
#include <cmath>
#include <optional>

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/brdf/cook_torrance.hpp>
#include <shade/brdf/coupled_plastic.hpp>
#include <shade/brdf/fresnel.hpp>
#include <shade/brdf/lambert.hpp>
#include <shade/brdf/microfacet.hpp>
#include <shade/bsdf/layer.hpp>
#include <shade/bsdf/rough_dielectric.hpp>
#include <shade/bsdf/smooth_conductor.hpp>
#include <shade/check/bsdf_energy.hpp>
#include <shade/check/bsdf_reciprocity.hpp>
#include <shade/check/energy.hpp>
#include <shade/check/doctest.hpp>

#include "bsdf/support_combine.hpp"

using namespace combine_test;
using shade::layering;
using shade::transport_mode;

static_assert(shade::bsdf_sampler<shade::layer<shade::lambert<float>, shade::lambert<float>>>);

namespace {

// A single-scattering GGX dielectric coating (k_s = 1, k_d = 0): a varnish of index 1.5.
template <class T>
using ggx_coat = shade::cook_torrance<shade::ggx<T>, shade::dielectric_fresnel<T>, shade::smith_height_correlated<T>>;

template <class T>
ggx_coat<T> varnish(T alpha) {
    return {shade::ggx<T>(alpha), shade::dielectric_fresnel<T>(T(1.5))};
}

template <class T>
using ggx_metal = shade::cook_torrance<shade::ggx<T>, shade::schlick<T>, shade::smith_height_correlated<T>>;

template <class T>
ggx_metal<T> rough_gold() {
    return {shade::ggx<T>(T(0.5)), shade::schlick<T>(rgb<T>(T(1), T(0.8), T(0.3)))};
}

} // namespace

TEST_CASE_TEMPLATE("layer: a Lambertian coat over a Lambertian base is the Lambert of rho_c + (1 - rho_c) rho_b", T,
                   float, double) {
    // A Lambertian coat of albedo rho_c = 0.3 reflects rho_c from every view (its cosine
    // samples all weigh exactly rho_c), so E_c = E_c,avg = 0.3 and, with w = 1,
    //   reciprocal:      rho_c / pi + (1 - rho_c)^2 / (1 - rho_c) rho_b / pi
    //   albedo scaling:  rho_c / pi + (1 - rho_c) rho_b / pi
    // both (rho_c + (1 - rho_c) rho_b) / pi = (0.3 + 0.7 (0.5, 0.2, 1)) / pi
    // = (0.65, 0.44, 1) / pi. Both lobes draw the cosine density, so every sample's weight
    // is that albedo.
    const auto at = brdf_test::tilted<T>();
    const shade::lambert<T> coat(rgb<T>(T(0.3)));
    const shade::lambert<T> base(rgb<T>(T(0.5), T(0.2), T(1)));
    const rgb<T> albedo(T(0.65), T(0.44), T(1));
    for (const auto form : {layering::reciprocal, layering::albedo_scaling}) {
        CAPTURE(int(form));
        const shade::layer m(coat, base, T(1), form);
        CHECK(m.coat_albedo(T(0.7)) == doctest::Approx(0.3).epsilon(1e-6));
        CHECK(m.coat_average_albedo() == doctest::Approx(0.3).epsilon(1e-6));
        shade::rng random(5);
        for (const double deg : {0.0, 40.0, 85.0}) {
            const vec3<T> v = bsdf_test::view_deg(at, deg);
            for (int i = 0; i < 100; ++i) {
                const auto s = m.sample(v, random.uniform<T>(), vec2<T>(random.uniform<T>(), random.uniform<T>()), at);
                if (!s) continue;
                const rgb<T> f = m.f(s->l, v, at);
                for (int c = 0; c < 3; ++c) {
                    CHECK(f[c] == doctest::Approx(double(albedo[c]) / shade::pi<double>).epsilon(1e-5));
                    CHECK(s->weight[c] == doctest::Approx(double(albedo[c])).epsilon(1e-5));
                }
            }
        }
    }
}

TEST_CASE_TEMPLATE("layer: a coat of weight 0 leaves the base exactly: the same f, pdf and samples", T, float, double) {
    // With w = 0 the base's factor is (1 - 0)(1 - 0) / (1 - 0) = 1 (or 1 - 0), the coat is
    // never chosen, and uc reaches the base unchanged ((uc - 0) / (1 - 0)).
    const auto at = brdf_test::tilted<T>();
    const auto base = rough_gold<T>();
    for (const auto form : {layering::reciprocal, layering::albedo_scaling}) {
        const shade::layer m(varnish<T>(T(0.1)), base, T(0), form);
        CHECK(m.coat_probability(T(0.5)) == T(0));
        shade::rng random(13);
        for (const double deg : {0.0, 50.0, 87.0}) {
            const vec3<T> v = bsdf_test::view_deg(at, deg);
            for (int i = 0; i < 100; ++i) {
                const T uc = random.uniform<T>();
                const vec2<T> u(random.uniform<T>(), random.uniform<T>());
                const auto s = m.sample(v, uc, u, at);
                const auto expected = shade::sample_bsdf(base, v, uc, u, at, transport_mode::radiance);
                REQUIRE(s.has_value() == expected.has_value());
                if (!s) continue;
                CHECK(s->l == expected->l);
                CHECK(s->f == expected->f);
                CHECK(s->pdf == expected->pdf);
                CHECK(s->weight == expected->weight);
                CHECK(m.f(s->l, v, at) == base.f(s->l, v, at));
                CHECK(m.pdf(s->l, v, at) == base.pdf(s->l, v, at));
            }
        }
    }
}

TEST_CASE_TEMPLATE("layer: a delta coat is estimated exactly at the nodes; its albedo in each transport mode", T,
                   float, double) {
    // A smooth conductor coat with kappa = 0 and eta = 1.5 (the dielectric Fresnel of
    // varnish, 0.04 head-on, 1 at grazing) reflects F(mu) with probability 1, so each node of
    // the estimated E_c is F at mu_k = ((k + 1/2) / 32)^2. With albedo_scaling, w = 0.5 and
    // a Lambertian base rho = 0.6, f(l, v) = (1 - w E_c(n·v)) rho / pi off the delta
    // direction, and the coat's delta sample has weight w F / p_c with probability p_c:
    //   radiance mode (albedo seen from v):   w F(n·v) + (1 - w E_c(n·v)) rho
    //   importance mode (energy arriving along v): w F(n·v) + rho (1 - w 2 ∫ E_c(mu) mu dmu)
    // the second because the adjoint f(v, l) carries the factor of l, 1 - w E_c(n·l),
    // which the cosine-weighted base integrates against.
    const auto at = brdf_test::tilted<T>();
    const shade::smooth_conductor<T> varnish_mirror(rgb<T>(T(1.5)), rgb<T>(T(0)));
    const shade::layer m(varnish_mirror, shade::lambert<T>(rgb<T>(T(0.6))), T(0.5), layering::albedo_scaling);
    for (const int k : {0, 7, 20, 31}) {
        const double x = (k + 0.5) / 32;
        const T mu = T(x * x);
        CHECK(m.coat_albedo(mu) == doctest::Approx(double(varnish_mirror.fresnel().F(mu).x)).epsilon(1e-5));
    }
    const double average = interpolated_average_albedo(m);
    for (const double deg : {0.0, 45.0, 80.0}) {
        CAPTURE(deg);
        const vec3<T> v = bsdf_test::view_deg(at, deg);
        const T n_dot_v = glm::dot(at.n(), v);
        const double F = double(varnish_mirror.fresnel().F(n_dot_v).x);
        const double e_c = double(m.coat_albedo(n_dot_v));
        const auto radiance = mean_weight(m, v, at, transport_mode::radiance);
        CHECK(std::abs(radiance.mean - (0.5 * F + (1 - 0.5 * e_c) * 0.6)) <= 4 * radiance.error + 1e-5);
        const auto importance = mean_weight(m, v, at, transport_mode::importance);
        CHECK(std::abs(importance.mean - (0.5 * F + 0.6 * (1 - 0.5 * average))) <= 4 * importance.error + 1e-5);
    }
    CHECK(expect_consistent_samples(m, at, {0.0, 60.0, 88.0}) > 0);
}

TEST_CASE_TEMPLATE("layer: a glossy varnish over a white base: the reciprocal form passes the white furnace both ways",
                   T, float, double) {
    // Reciprocal form over a Lambertian base of albedo 1: E_c(n·v) + (1 - E_c(n·v)) = 1 in
    // both modes (class comment of shade::layer), up to the error of the estimated E_c
    // (the coat's true albedo in the first term, the estimate in the second): total = 1
    // within the property kit's default tolerance 0.01 and 4 standard errors.
    // Albedo scaling: 1 seen from v (radiance mode), but for energy arriving along v
    // (importance mode) E_c(n·v) + 1 - 2 ∫ E_c(mu) mu dmu, above 1 at grazing incidence
    // where E_c(n·v) > E_c,avg (derivation in the delta-coat case above).
    const auto at = brdf_test::tilted<T>();
    const shade::layer reciprocal(varnish<T>(T(0.2)), shade::lambert<T>(rgb<T>(1)));
    const shade::layer scaled(varnish<T>(T(0.2)), shade::lambert<T>(rgb<T>(1)), T(1), layering::albedo_scaling);
    const double average = interpolated_average_albedo(scaled);
    for (const double deg : {0.0, 45.0, 75.0, 88.0}) {
        CAPTURE(deg);
        const vec3<T> v = bsdf_test::view_deg(at, deg);
        const auto a = shade::check::bsdf_albedo(reciprocal, v, at, 128);
        CHECK(std::abs(a.total.x - 1) <= 0.01 + 4 * a.total_error.x);
        const auto r = mean_weight(reciprocal, v, at, transport_mode::radiance);
        CHECK(std::abs(r.mean - 1) <= 0.01 + 4 * r.error);
        const auto s = mean_weight(scaled, v, at, transport_mode::radiance);
        CHECK(std::abs(s.mean - 1) <= 0.01 + 4 * s.error);
        const auto e = shade::check::bsdf_albedo(scaled, v, at, 128);
        const double e_c = double(scaled.coat_albedo(glm::dot(at.n(), v)));
        CHECK(std::abs(e.total.x - (e_c + 1 - average)) <= 0.01 + 4 * e.total_error.x);
        MESSAGE("view ", deg, " deg: reciprocal ", a.total.x, " (importance), ", r.mean,
                " (radiance); albedo scaling ", s.mean, " (radiance), ", e.total.x, " (importance)");
    }
}

TEST_CASE_TEMPLATE("layer: energy conservation, reciprocity of the reciprocal form, albedo scaling not reciprocal", T,
                   float, double) {
    const auto at = brdf_test::tilted<T>();
    shade::check::albedo_options options{.strata = 64, .view_angles = 6, .azimuths = 2};
    options.model = "varnished paint";
    const shade::layer paint(varnish<T>(T(0.2)), shade::lambert<T>(rgb<T>(T(0.9), T(0.5), T(0.1))));
    shade::check::doctest_expect(shade::check::bsdf_energy_conservation(paint, at, options));
    // Albedo scaling keeps the albedo seen from v at most 1 (radiance mode, the BRDF
    // kit's white furnace), not the energy sent back from light arriving along v (above).
    options.model = "varnished gold (albedo scaling)";
    const shade::layer gold(varnish<T>(T(0.05)), rough_gold<T>(), T(0.8), layering::albedo_scaling);
    shade::check::doctest_expect(shade::check::energy_conservation(gold, at, options));

    shade::check::pair_options pairs{.pairs = 4000};
    pairs.model = "varnished paint";
    shade::check::doctest_expect(shade::check::adjoint_reciprocity(paint, at, 1, pairs));
    // The albedo-scaling factor 1 - w E_c(n·v) is not symmetric: E_c goes from about 0.04
    // at normal incidence to 1 at grazing, so exchanging a grazing l with a steep v changes
    // the base's share by far more than the tolerance.
    pairs.model = "varnished paint (albedo scaling)";
    const shade::layer one_sided(varnish<T>(T(0.2)), shade::lambert<T>(rgb<T>(T(0.9))), T(1),
                                 layering::albedo_scaling);
    shade::check::doctest_expect_failure(shade::check::adjoint_reciprocity(one_sided, at, 1, pairs));
}

TEST_CASE_TEMPLATE("layer: sample draws l with the density pdf and agrees with f and pdf", T, float, double) {
    // 2 models x 3 views x 2 scalar types = 12 chi-square tests at a family-wise level of 1e-3.
    const auto at = brdf_test::tilted<T>();
    const shade::layer paint(varnish<T>(T(0.1)), shade::lambert<T>(rgb<T>(T(0.8), T(0.4), T(0.2))));
    const shade::layer gold(varnish<T>(T(0.3)), rough_gold<T>(), T(0.7), layering::albedo_scaling);
    expect_sampling(paint, "varnished paint", at, {0.0, 45.0, 80.0}, 12);
    expect_sampling(gold, "varnished gold", at, {0.0, 45.0, 80.0}, 12);
    CHECK(expect_consistent_samples(paint, at, {0.0, 45.0, 85.0}) > 1000);
    CHECK(expect_consistent_samples(gold, at, {10.0, 70.0}) > 500);
    // Nothing is drawn for a view from below.
    CHECK_FALSE(paint.sample(-at.n(), T(0.5), vec2<T>(T(0.5)), at).has_value());
}

TEST_CASE_TEMPLATE("layer: the estimated E_c of a rough dielectric coat matches its reflected albedo at the nodes", T,
                   float, double) {
    // A rough dielectric coat chooses reflection or refraction with uc and places the
    // microfacet normal with u, so its estimate needs uc independent of u. At the node
    // cosines mu_k = ((k + 1/2) / 32)^2 the layer reads its estimate without interpolation;
    // the reference is the coat's reflected albedo from the property kit (256^2 stratified
    // importance-mode samples; a reflection's weight is the same in both modes). They agree
    // within the kit's albedo tolerance 0.01 and 4 standard errors.
    const auto at = brdf_test::tilted<T>();
    for (const T alpha : {T(0.2), T(0.5)}) {
        const shade::rough_dielectric<shade::ggx<T>> coat(shade::ggx<T>(alpha), T(1.5));
        const shade::layer m(coat, shade::lambert<T>(rgb<T>(T(0.5))));
        for (const int k : {4, 10, 16, 31}) {
            CAPTURE(alpha);
            CAPTURE(k);
            const double x = (k + 0.5) / 32;
            const double mu = x * x;
            const vec3<T> v = brdf_test::direction(at, T(std::acos(mu)), T(0.4));
            const auto a = shade::check::bsdf_albedo(coat, v, at, 256);
            CHECK(std::abs(double(m.coat_albedo(T(mu))) - a.reflected.x) <= 0.01 + 4 * a.reflected_error.x);
        }
    }
}

TEST_CASE_TEMPLATE("layer: over coupled_plastic's coating, E_c agrees with the plastic's tabulated E_s", T, float,
                   double) {
    // layer<coating, lambert> with w = 1 and the reciprocal form has coupled_plastic's formula
    // (both headers); what differs is where the coating's albedo comes from: the plastic's
    // precomputed tables (E_F + F_ms (1 - E)), the layer's estimate from the coating's own
    // sampler. Both estimate the same directional albedo, so they agree within the property
    // kit's albedo tolerance, 0.01, at every cosine, and so do the averages.
    for (const T alpha : {T(0.05), T(0.3), T(0.7)}) {
        CAPTURE(alpha);
        const shade::coupled_plastic<T> plastic(shade::ggx<T>(alpha), rgb<T>(T(0.8), T(0.4), T(0.1)));
        const shade::layer m(plastic.coating(), shade::lambert<T>(plastic.k_d()));
        for (int i = 0; i <= 100; ++i) {
            const T mu = T(0.005) + T(0.995) * T(i) / T(100);
            CHECK(std::abs(double(m.coat_albedo(mu)) - double(plastic.coating_albedo(mu))) <= 0.01);
        }
    }
}

TEST_CASE("layer: a coat weight outside [0, 1] is refused by name") {
    const shade::lambert<double> white(rgb<double>(1));
    CHECK_THROWS_WITH_AS(shade::layer(white, white, 1.5), doctest::Contains("coat_weight"), shade::invalid_parameter);
    CHECK_THROWS_WITH_AS(shade::layer(white, white, -0.1), doctest::Contains("coat_weight"), shade::invalid_parameter);
}
