#include <cmath>
#include <limits>

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/brdf/aliases.hpp>
#include <shade/brdf/cook_torrance.hpp>
#include <shade/brdf/metals.hpp>
#include <shade/bsdf/smooth_conductor.hpp>
#include <shade/core/random.hpp>

#include "bsdf/support.hpp"

using namespace bsdf_test;
using brdf_test::close;
using shade::transport_mode;

static_assert(shade::bsdf_sampler<shade::smooth_conductor<float>>);
static_assert(shade::sampled_bsdf<shade::smooth_conductor<double>>);

TEST_CASE_TEMPLATE("smooth_conductor: a mirror weighted by the conductor Fresnel reflectance", T, float, double) {
    const auto at = brdf_test::tilted<T>();
    const shade::smooth_conductor<T> gold{shade::metals::gold<T>()};
    // Normal incidence: ((eta - 1)^2 + kappa^2) / ((eta + 1)^2 + kappa^2); gold's red
    // channel, eta = 0.14, kappa = 3.697: (0.7396 + 13.667809) / (1.2996 + 13.667809)
    // = 14.407409 / 14.967409 = 0.962585...
    const auto s0 = gold.sample(at.n(), T(0.5), vec2<T>(0), at);
    REQUIRE(s0);
    CHECK(close(s0->weight.x, T(14.407409 / 14.967409), T(1e-5)));
    for (const double deg : {0.0, 30.0, 60.0, 85.0, 89.99}) {
        CAPTURE(deg);
        const auto v = view_deg(at, deg);
        for (const transport_mode mode : {transport_mode::radiance, transport_mode::importance}) {
            const auto s = gold.sample(v, T(0.5), vec2<T>(0), at, mode);
            REQUIRE(s);
            check_sample(*s, v, at, T(1e-5));
            CHECK(s->flags == shade::bsdf_flags::specular_reflection);
            CHECK(s->pdf == T(1));
            CHECK(s->eta == T(1));
            CHECK(close(s->weight, gold.fresnel().F(glm::dot(at.n(), v)), T(1e-6)));
            // The mirror direction: same cosine, in the plane of v and n, across n.
            CHECK(std::abs(glm::dot(at.n(), s->l) - glm::dot(at.n(), v)) <= T(1e-6));
            CHECK(glm::length(s->l + v - T(2) * glm::dot(at.n(), v) * at.n()) <= T(1e-5));
        }
    }
    // Opaque: nothing drawn from below or on the surface; f and pdf are 0.
    CHECK(!gold.sample(-at.n(), T(0.5), vec2<T>(0), at));
    CHECK(!gold.sample(view_deg(at, 100), T(0.5), vec2<T>(0), at));
    CHECK(gold.f(at.n(), at.n(), at) == rgb<T>(0));
    CHECK(gold.pdf(at.n(), at.n(), at) == T(0));
}

TEST_CASE_TEMPLATE("smooth_conductor: the limit of a GGX conductor as alpha goes to 0", T, float, double) {
    // The albedo of cook_torrance GGX at alpha = 1e-4 (its smallest) with the same Fresnel
    // term is F(n·v) to within what the microfacets lose to masking at that roughness.
    const auto at = brdf_test::tilted<T>();
    const shade::conductor_fresnel<T> copper = shade::metals::copper<T>();
    const shade::smooth_conductor<T> mirror{copper};
    const shade::cook_torrance<shade::ggx<T>, shade::conductor_fresnel<T>, shade::smith_height_correlated<T>> rough(
        shade::ggx<T>(T(1e-4)), copper);
    shade::rng random(3);
    for (const double deg : {0.0, 45.0, 80.0}) {
        CAPTURE(deg);
        const auto v = view_deg(at, deg);
        rgb<double> mean(0);
        const int n = 2000;
        for (int i = 0; i < n; ++i) {
            const T uc = random.uniform<T>(); // drawn in sequence, the same with every compiler
            const T u0 = random.uniform<T>();
            const T u1 = random.uniform<T>();
            const auto s = rough.sample(v, uc, vec2<T>(u0, u1), at);
            if (s) mean += rgb<double>(s->weight) / double(n);
        }
        const auto m = mirror.sample(v, T(0), vec2<T>(0), at);
        REQUIRE(m);
        CHECK(close(rgb<T>(mean), m->weight, T(2e-3)));
    }
}

TEST_CASE_TEMPLATE("smooth_conductor: bad eta or kappa throws invalid_parameter naming it", T, float, double) {
    const rgb<T> one(1);
    brdf_test::check_throws_naming([&] { (void)shade::smooth_conductor<T>(rgb<T>(0), one); }, "eta");
    brdf_test::check_throws_naming([&] { (void)shade::smooth_conductor<T>(rgb<T>(T(1e5)), one); }, "eta");
    brdf_test::check_throws_naming([&] { (void)shade::smooth_conductor<T>(one, rgb<T>(-1)); }, "kappa");
    brdf_test::check_throws_naming(
        [&] { (void)shade::smooth_conductor<T>(one, rgb<T>(std::numeric_limits<T>::quiet_NaN())); }, "kappa");
}
