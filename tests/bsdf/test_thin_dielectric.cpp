#include <cmath>
#include <limits>

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/bsdf/thin_dielectric.hpp>

#include "bsdf/support.hpp"

using namespace bsdf_test;
using brdf_test::close;
using shade::transport_mode;

static_assert(shade::bsdf_sampler<shade::thin_dielectric<float>>);
static_assert(shade::sampled_bsdf<shade::thin_dielectric<double>>);

TEST_CASE_TEMPLATE("thin_dielectric: the slab's reflectance is the sum of the inter-reflection series", T, float, double) {
    // Normal incidence, eta = 1.5: R = 0.04 per face, R' = 2R/(1 + R) = 0.08/1.04 = 0.0769230769...
    const shade::thin_dielectric<T> pane{T(1.5)};
    CHECK(close(pane.reflectance(T(1)), T(0.0769230769230769), T(1e-6)));
    CHECK(close(pane.reflectance(T(-1)), T(0.0769230769230769), T(1e-6)));
    // The series summed term by term: R + T^2 R (1 + R^2 + R^4 + ...).
    for (const double eta : {1.05, 1.33, 1.5, 2.4, 1 / 1.5}) {
        const shade::thin_dielectric<T> slab{T(eta)};
        for (const double c : {1.0, 0.8, 0.5, 0.2, 0.05, 0.001}) {
            CAPTURE(eta);
            CAPTURE(c);
            const double R = double(shade::F_dielectric(T(c), T(eta)));
            const double Tr = 1 - R;
            double series = R;
            double term = Tr * Tr * R;
            for (int k = 0; k < 100000 && term > 1e-18; ++k) {
                series += term;
                term *= R * R;
            }
            CHECK(std::abs(double(slab.reflectance(T(c))) - series) <= (sizeof(T) <= 4 ? 1e-6 : 1e-12));
        }
    }
}

TEST_CASE_TEMPLATE("thin_dielectric: R + T = 1, straight transmission with weight 1 in both modes", T, float, double) {
    const auto at = brdf_test::tilted<T>();
    for (const double eta : {1.33, 1.5, 2.4}) {
        const shade::thin_dielectric<T> slab{T(eta)};
        for (const double deg : {0.0, 30.0, 60.0, 85.0, 120.0, 170.0}) {
            CAPTURE(eta);
            CAPTURE(deg);
            const auto v = view_deg(at, deg);
            for (const transport_mode mode : {transport_mode::radiance, transport_mode::importance}) {
                const auto r = sample_lobes(slab, v, at, mode, 4000);
                CHECK(r.missing == 0);
                CHECK(std::abs(r.reflected_weight + r.transmitted_weight - T(1)) <= T(1e-5));
                CHECK(std::abs(r.reflected - slab.reflectance(glm::dot(at.n(), v))) <= T(1) / T(4000));
            }
            const auto s = slab.sample(v, T(0.9999), vec2<T>(0), at, transport_mode::radiance);
            REQUIRE(s);
            CHECK(shade::has_flags(s->flags, shade::bsdf_flags::specular_transmission));
            CHECK(s->l == -v);
            CHECK(s->eta == T(1));
            CHECK(s->weight == rgb<T>(1));
            const auto m = slab.sample(v, T(0), vec2<T>(0), at, transport_mode::importance);
            REQUIRE(m);
            CHECK(shade::has_flags(m->flags, shade::bsdf_flags::specular_reflection));
            CHECK(close(glm::dot(at.n(), m->l), glm::dot(at.n(), v), T(1e-5)));
        }
    }
}

TEST_CASE_TEMPLATE("thin_dielectric: no NaN at grazing and normal incidence; bad eta throws", T, float, double) {
    const auto at = brdf_test::tilted<T>();
    const shade::thin_dielectric<T> slab{T(1.5)};
    const vec3<T> t = at.shading.t;
    const vec3<T> n = at.n();
    for (const vec3<T>& v : {n, -n, glm::normalize(t + T(1e-30) * n), glm::normalize(t - T(1e-6) * n)})
        for (const T uc : {T(0), T(0.5), T(0.9999)}) {
            const auto s = slab.sample(v, uc, vec2<T>(0), at);
            REQUIRE(s);
            check_sample(*s, v, at, T(1e-5));
        }
    CHECK(slab.f(n, -n, at) == rgb<T>(0));
    CHECK(slab.pdf(n, -n, at) == T(0));
    for (const T eta : {T(0), T(-1), T(1e-5), T(2e4), std::numeric_limits<T>::quiet_NaN()})
        brdf_test::check_throws_naming([&] { (void)shade::thin_dielectric<T>(eta); }, "eta");
}
