// shade::coupled_plastic: with a white base (k_d = 1) the albedo is in [0.97, 1.001] at
// every alpha in {0.05, 0.25, 0.5, 0.75, 1} and view cosine down to 0.05 (issue #19), with
// k_d = 0 it is the compensated coating exactly, the base term is reciprocal, and the
// property kit passes it.

#include <cmath>
#include <string>

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/brdf/aliases.hpp>
#include <shade/brdf/coupled_plastic.hpp>
#include <shade/check/doctest.hpp>
#include <shade/check/properties.hpp>
#include <shade/core/error.hpp>

#include "brdf/properties_support.hpp"
#include "brdf/support.hpp"

using namespace brdf_test;
using shade::vec2;

static_assert(shade::sampled_brdf<shade::coupled_plastic<float>> && shade::split_brdf<shade::coupled_plastic<double>>);

namespace {

constexpr double alphas[] = {0.05, 0.25, 0.5, 0.75, 1.0};
constexpr double view_cosines[] = {1.0, 0.75, 0.5, 0.25, 0.1, 0.05};

template <class T>
vec3<T> view_of(double mu) {
    return vec3<T>(T(std::sqrt((1 - mu) * (1 + mu))), 0, T(mu));
}

} // namespace

TEST_CASE_TEMPLATE("coupled_plastic: with k_d = 1 the albedo is in [0.97, 1.001] at every roughness and view", T, float,
                   double) {
    // The albedo split into parts: the coating's single-scattering lobe E_F(mu), estimated
    // with its own visible-normal sampler (weight F G2 / G1: low variance; standard error
    // < 2e-4, asserted), and the parts that are exact by quadrature of the model's table
    // reads: the coating's multiple-scattering lobe F_ms (1 - E(mu)) (1 - A) / (1 - E_avg)
    // (A = 2 integral E mu), and the base k_d (1 - E_s(mu)) (1 - A_s) / (1 - E_s,avg)
    // (A_s = 2 integral E_s mu = E_s,avg up to the table's consistency). The model's own
    // sampler (noisier: three lobes) must agree with the split within 4 standard errors.
    using single_lobe = shade::cook_torrance<shade::ggx<T>, shade::dielectric_fresnel<T>, shade::smith_height_correlated<T>>;
    for (const double alpha : alphas) {
        CAPTURE(alpha);
        const shade::coupled_plastic<T> white(shade::ggx<T>(T(alpha)), rgb<T>(1));
        const auto& coating = white.coating();
        const single_lobe single(shade::ggx<T>(T(alpha)), shade::dielectric_fresnel<T>(T(1.5)));
        // The uncoupled rough_plastic (base k_d / pi simply added) reflects more than it
        // receives with the same white base: the coupling is what keeps it below 1.
        const auto uncoupled = shade::make_rough_plastic<T>(T(alpha), rgb<T>(1));
        const auto average = [](const auto& g) {
            double sum = 0;
            for (int i = 0; i < 20000; ++i) {
                const double mu = (i + 0.5) / 20000;
                sum += 2 * g(mu) * mu / 20000;
            }
            return sum;
        };
        const double e_avg = double(coating.average_single_scattering_albedo());
        const double a = average([&](double x) { return double(coating.single_scattering_albedo(T(x))); });
        const double a_s = average([&](double x) { return double(white.coating_albedo(T(x))); });
        const double f_ms = double(shade::detail::multiple_scattering_fresnel(
                                       shade::detail::fresnel_average<T>(shade::dielectric_fresnel<T>(T(1.5))), T(e_avg))
                                       .x);
        const double e_s_avg = double(shade::detail::albedo_average_lookup(shade::detail::ggx_dielectric_albedo_average,
                                                                           shade::detail::albedo_grid_nodes, T(alpha))) +
                               f_ms * (1 - e_avg);
        for (const double mu : view_cosines) {
            CAPTURE(mu);
            const auto ss = shade::check::sampled_albedo(single, view_of<T>(mu), flat<T>(), 192, 3);
            CHECK(ss.standard_error.x < 2e-4);
            const double coating_ms = f_ms * (1 - double(coating.single_scattering_albedo(T(mu)))) * (1 - a) / (1 - e_avg);
            const double base = (1 - double(white.coating_albedo(T(mu)))) * (1 - a_s) / (1 - e_s_avg);
            const double total = ss.albedo.x + coating_ms + base;
            CHECK(total >= 0.97);
            CHECK(total <= 1.001);
            const auto own = shade::check::sampled_albedo(white, view_of<T>(mu), flat<T>(), 128, 3);
            CHECK(std::abs(own.albedo.x - total) < 4 * (own.standard_error.x + ss.standard_error.x));
            const auto b = shade::check::sampled_albedo(uncoupled, view_of<T>(mu), flat<T>(), 64, 3);
            CHECK(b.albedo.x > 1.001);
        }
    }
}

TEST_CASE_TEMPLATE("coupled_plastic: with k_d = 0 it is the coating alone, bit for bit", T, float, double) {
    const auto at = tilted<T>();
    for (const double alpha : {0.05, 0.4, 1.0}) {
        const shade::coupled_plastic<T> plastic(shade::ggx<T>(T(alpha)), rgb<T>(0));
        const typename shade::coupled_plastic<T>::coating_type coating(shade::ggx<T>(T(alpha)),
                                                                       shade::dielectric_fresnel<T>(T(1.5)));
        shade::rng random(11);
        for (int k = 0; k < 500; ++k) {
            const vec3<T> l = at.shading.to_world(shade::square_to_cosine_hemisphere(vec2<T>(random.uniform<T>(), random.uniform<T>())));
            const vec3<T> v = at.shading.to_world(shade::square_to_cosine_hemisphere(vec2<T>(random.uniform<T>(), random.uniform<T>())));
            CHECK(plastic.f(l, v, at) == coating.f(l, v, at));
            CHECK(plastic.pdf(l, v, at) == coating.pdf(l, v, at));
            const T uc = random.uniform<T>();
            const vec2<T> u(random.uniform<T>(), random.uniform<T>());
            const auto a = plastic.sample(v, uc, u, at);
            const auto b = coating.sample(v, uc, u, at);
            REQUIRE(a.has_value() == b.has_value());
            if (a) {
                CHECK(a->l == b->l);
                CHECK(a->f == b->f);
                CHECK(a->pdf == b->pdf);
                CHECK(a->weight == b->weight);
            }
        }
    }
}

TEST_CASE_TEMPLATE("coupled_plastic: the base term is k_d (1 - E_s(l))(1 - E_s(v)) / (pi (1 - E_s,avg))", T, float, double) {
    const rgb<T> k_d(T(0.8), T(0.4), T(0.1));
    const shade::coupled_plastic<T> plastic(shade::ggx<T>(T(0.3)), k_d);
    const auto at = flat<T>();
    const vec3<T> l = glm::normalize(vec3<T>(T(0.3), T(-0.4), T(0.6)));
    const vec3<T> v = glm::normalize(vec3<T>(T(-0.7), T(0.1), T(0.3)));
    // E_s,avg by its definition, 2 integral E_s(mu) mu dmu (midpoint rule, 20000 cells).
    double e_s_avg = 0;
    for (int i = 0; i < 20000; ++i) {
        const double mu = (i + 0.5) / 20000;
        e_s_avg += 2 * double(plastic.coating_albedo(T(mu))) * mu / 20000;
    }
    const double expected_factor = (1 - double(plastic.coating_albedo(l.z))) * (1 - double(plastic.coating_albedo(v.z))) /
                                   (shade::pi<double> * (1 - e_s_avg));
    const rgb<T> base = plastic.f_diffuse(l, v, at);
    for (int c = 0; c < 3; ++c) CHECK(double(base[c]) == doctest::Approx(double(k_d[c]) * expected_factor).epsilon(1e-4));
    CHECK(plastic.f_diffuse(l, v, at) == plastic.f_diffuse(v, l, at));
    // The coating reflects little of normal light (F(1) = ((1.5 - 1) / (1.5 + 1))^2 = 0.04,
    // plus a little multiple scattering) and more toward grazing, where F grows to 1.
    CHECK(plastic.coating_albedo(T(1)) < T(0.06));
    CHECK(plastic.coating_albedo(T(0.05)) > T(2) * plastic.coating_albedo(T(1)));
    CHECK_THROWS_AS(shade::coupled_plastic<T>(shade::ggx<T>(T(0.3)), rgb<T>(T(-0.1), 0, 0)), shade::invalid_parameter);
}

TEST_CASE_TEMPLATE("coupled_plastic: every property check passes", T, float, double) {
    const auto run = [](const auto& model, const std::string& name) { expect_every_property(model, name, 24); };
    run(shade::coupled_plastic<T>(shade::ggx<T>(T(0.1)), rgb<T>(T(0.9), T(0.2), T(0.1))), "coupled plastic alpha 0.1");
    run(shade::make_coupled_plastic<T>(T(0.8), rgb<T>(1)), "coupled plastic alpha 0.8, white");
}
