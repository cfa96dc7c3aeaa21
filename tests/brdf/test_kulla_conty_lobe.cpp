// shade::kulla_conty_lobe: the multiple-scattering compensation as a lobe of its own. Mixed
// with the single-scattering lobe it has the f of the kulla_conty policy bit for bit; its
// albedo is F_ms (1 - E(mu)) (derived below); with F = 1 the mixture reflects all the light
// it receives; the property kit passes it; shade::layer reads its albedo.

#include <cmath>
#include <string>

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/brdf/kulla_conty_lobe.hpp>
#include <shade/brdf/lambert.hpp>
#include <shade/brdf/microfacet_reflection.hpp>
#include <shade/bsdf/layer.hpp>
#include <shade/bsdf/mix.hpp>
#include <shade/check/doctest.hpp>
#include <shade/check/properties.hpp>
#include <shade/core/random.hpp>
#include <shade/core/sampling.hpp>

#include "brdf/properties_support.hpp"
#include "brdf/support.hpp"

using namespace brdf_test;
using shade::vec2;

static_assert(shade::sampled_brdf<shade::kulla_conty_lobe<shade::ggx<float>, shade::schlick<float>>>);
static_assert(shade::detail::has_directional_albedo<shade::kulla_conty_lobe<shade::beckmann<double>, shade::dielectric_fresnel<double>>>);

namespace {

template <class D, class F>
using single_lobe = shade::microfacet_reflection<D, F, shade::smith_height_correlated<shade::scalar_of<D>>>;
template <class D, class F>
using compensated_lobe = shade::microfacet_reflection<D, F, shade::smith_height_correlated<shade::scalar_of<D>>,
                                                      shade::cook_torrance_form::walter, shade::kulla_conty>;

// mix(single, 1, compensation, 1) against the kulla_conty policy at 2000 random pairs over
// the sphere: f bit for bit (the same terms: w f_ss + w f_ms with w = 1, and kulla_conty's
// f_ss + f_ms).
template <class D, class F>
void expect_same_f(const D& d, const F& fresnel) {
    using T = shade::scalar_of<D>;
    const auto at = tilted<T>();
    const shade::mix mixed(single_lobe<D, F>(d, fresnel), rgb<T>(1), shade::kulla_conty_lobe<D, F>(d, fresnel), rgb<T>(1));
    const compensated_lobe<D, F> built_in(d, fresnel);
    shade::rng random(17);
    int differ = 0, positive = 0;
    for (int i = 0; i < 2000; ++i) {
        const vec3<T> l = at.shading.to_world(shade::square_to_uniform_sphere(vec2<T>(random.uniform<T>(), random.uniform<T>())));
        const vec3<T> v = at.shading.to_world(shade::square_to_uniform_sphere(vec2<T>(random.uniform<T>(), random.uniform<T>())));
        const rgb<T> a = mixed.f(l, v, at);
        if (!(a == built_in.f(l, v, at))) ++differ;
        if (a.x > T(0)) ++positive;
    }
    CHECK(differ == 0);
    CHECK(positive > 300); // about a quarter of the pairs have both directions above
}

} // namespace

TEST_CASE_TEMPLATE("kulla_conty_lobe: mixed with the single-scattering lobe it is the kulla_conty policy, bit for bit", T,
                   float, double) {
    expect_same_f(shade::ggx<T>(T(0.5)), shade::schlick<T>(rgb<T>(T(1), T(0.71), T(0.29))));
    expect_same_f(shade::ggx<T>(T(0.1), T(0.4)), shade::conductor_fresnel<T>(rgb<T>(T(0.2), T(0.9), T(1.1)), rgb<T>(T(3.9), T(2.4), T(2.2))));
    expect_same_f(shade::beckmann<T>(T(0.3)), shade::dielectric_fresnel<T>(T(1.5)));
    expect_same_f(shade::ggx<T>(T(1)), shade::dielectric_fresnel<T>(T(1) / T(1.33)));
}

TEST_CASE_TEMPLATE("kulla_conty_lobe: its albedo is F_ms (1 - E(mu)); with F = 1 the mixture reflects everything", T,
                   float, double) {
    // ∫ f_ms (n·l) dl = F_ms (1 - E(mu_v)) ∫ (1 - E(mu_l)) mu_l dmu_l dphi / (pi (1 - E_avg))
    //                 = F_ms (1 - E(mu_v)) (1 - A) / (1 - E_avg),   A = 2 ∫ E(mu) mu dmu,
    // and A = E_avg up to the tables' consistency, so the lobe's albedo is F_ms (1 - E(mu)).
    // With F = 1 (Schlick, f0 = 1): F_avg = 1, F_ms = E_avg / (1 - (1 - E_avg)) = 1, and the
    // mixture's albedo E(mu) + 1 - E(mu) = 1.
    const auto at = flat<T>();
    for (const double alpha : {0.25, 0.6, 1.0}) {
        CAPTURE(alpha);
        using D = shade::ggx<T>;
        using F = shade::schlick<T>;
        const shade::kulla_conty_lobe<D, F> white(D(T(alpha)), F(rgb<T>(1)));
        double a = 0;
        for (int i = 0; i < 20000; ++i) {
            const double mu = (i + 0.5) / 20000;
            a += 2 * double(white.single_scattering_albedo(T(mu))) * mu / 20000;
        }
        const shade::mix mixed(single_lobe<D, F>(D(T(alpha)), F(rgb<T>(1))), rgb<T>(1), white, rgb<T>(1));
        for (const double mu : {1.0, 0.5, 0.2, 0.05}) {
            CAPTURE(mu);
            const vec3<T> v(T(std::sqrt((1 - mu) * (1 + mu))), 0, T(mu));
            const double expected = (1 - double(white.single_scattering_albedo(T(mu)))) * (1 - a) /
                                    (1 - double(white.average_single_scattering_albedo()));
            const auto own = shade::check::sampled_albedo(white, v, at, 128, 3);
            CHECK(std::abs(own.albedo.x - expected) <= 4 * own.standard_error.x + 1e-6);
            CHECK(std::abs(double(white.albedo(T(mu))) - expected) <= 0.01); // the property kit's albedo tolerance
            const auto furnace = shade::check::sampled_albedo(mixed, v, at, 128, 3);
            CHECK(std::abs(furnace.albedo.x - 1) <= 0.01 + 4 * furnace.standard_error.x);
        }
    }
}

TEST_CASE_TEMPLATE("kulla_conty_lobe: every property check passes; a layer reads its albedo", T, float, double) {
    using D = shade::ggx<T>;
    const auto run = [](const auto& model, const std::string& name) { expect_every_property(model, name, 8); };
    run(shade::kulla_conty_lobe<D, shade::schlick<T>>(D(T(0.7)), shade::schlick<T>(rgb<T>(T(0.9), T(0.6), T(0.3)))),
        "Kulla-Conty lobe, GGX 0.7, Schlick");
    run(shade::kulla_conty_lobe<shade::beckmann<T>, shade::dielectric_fresnel<T>>(shade::beckmann<T>(T(0.5)),
                                                                                shade::dielectric_fresnel<T>(T(1.5))),
        "Kulla-Conty lobe, Beckmann 0.5, eta 1.5");
    const shade::kulla_conty_lobe<D, shade::schlick<T>> coat(D(T(0.7)), shade::schlick<T>(rgb<T>(1)));
    const shade::layer coated(coat, shade::lambert<T>(rgb<T>(T(0.5))));
    for (const T mu : {T(0.1), T(0.5), T(1)}) CHECK(coated.coat_albedo(mu) == coat.albedo(mu));
    CHECK(coated.coat_average_albedo() == coat.average_albedo());
}
