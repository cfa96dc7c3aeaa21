// shade::light_sample_context: the constant environment samples only the hemisphere above
// the surface, cosine-weighted (every sample then estimates the irradiance pi L exactly),
// with a pdf that integrates to 1 and equals each sample's; without a surface, and for
// every other light, sampling is as for the point alone; any_light forwards.

#include <cmath>
#include <vector>

#include <doctest/doctest.h>

#include <shade/core/math.hpp>
#include <shade/light/any_light.hpp>
#include <shade/light/environment.hpp>
#include <shade/light/sample_context.hpp>

namespace {

template <class T>
using v3 = shade::vec3<T>;
template <class T>
using v2 = shade::vec2<T>;

} // namespace

TEST_CASE_TEMPLATE("environment light with a surface: cosine-weighted above n, pi L per sample", T, float, double) {
    const shade::rgb<T> L(1, 2, 3);
    const shade::environment_light<T> sky(shade::emission<T>::from_physical(L));
    const v3<T> n = glm::normalize(v3<T>(T(0.3), T(-0.4), T(0.8)));
    const shade::light_sample_context<T> ctx{v3<T>(T(5), T(-1), T(2)), n, n};
    const int k = 64;
    for (int j = 0; j < k; ++j)
        for (int i = 0; i < k; ++i) {
            const v2<T> u((T(i) + T(0.5)) / T(k), (T(j) + T(0.5)) / T(k));
            const auto s = sky.sample_incident(ctx, u);
            REQUIRE(s);
            const T cos = glm::dot(n, s->l);
            CHECK(cos > T(0));
            CHECK(s->pdf == sky.pdf_incident(ctx, s->l));
            // L cos / pdf = L cos / (cos / pi) = pi L: each sample is the irradiance.
            CHECK(double(s->radiance.z * cos / s->pdf) == doctest::Approx(3 * shade::pi<double>).epsilon(1e-4));
            CHECK(s->distance == shade::infinity<T>);
        }
    // The density integrates to 1 over the sphere (midpoint rule in (cos theta, phi)
    // about n, where it is cos theta / pi: exact up to rounding), and is 0 below.
    const auto frame = shade::frame<double>::from_normal(glm::dvec3(n));
    double total = 0;
    const int m = 200;
    for (int a = 0; a < m; ++a)
        for (int b = 0; b < m; ++b) {
            const double z = -1 + (a + 0.5) * 2.0 / m, phi = (b + 0.5) * 2 * shade::pi<double> / m;
            const double r = std::sqrt(1 - z * z);
            const glm::dvec3 w = frame.to_world(glm::dvec3(r * std::cos(phi), r * std::sin(phi), z));
            total += double(sky.pdf_incident(ctx, v3<T>(w))) * (2.0 / m) * (2 * shade::pi<double> / m);
        }
    CHECK(total == doctest::Approx(1).epsilon(1e-3));
    CHECK(sky.pdf_incident(ctx, -n) == T(0));
}

TEST_CASE_TEMPLATE("light_sample_context: no surface, or a light that does not use it, samples as for the point", T, float, double) {
    const auto e = shade::emission<T>::from_physical(shade::rgb<T>(2));
    const shade::environment_light<T> sky(e);
    const v3<T> p(T(0.1), T(0.2), T(0.3));
    const shade::light_sample_context<T> no_surface{p, v3<T>(0), v3<T>(0)};
    const v2<T> u(T(0.3), T(0.7));
    CHECK(sky.sample_incident(no_surface, u)->l == sky.sample_incident(p, u)->l);
    CHECK(sky.pdf_incident(no_surface, v3<T>(0, 0, 1)) == sky.pdf_incident(p, v3<T>(0, 0, 1)));
    const std::vector<shade::any_light<T>> lights{
        shade::area_light<T>(v3<T>(-1, -1, 2), v3<T>(2, 0, 0), v3<T>(0, 2, 0), e, shade::sidedness::two_sided),
        shade::point_light<T>(v3<T>(0, 0, 3), e), sky};
    const shade::light_sample_context<T> up{p, v3<T>(0, 0, 1), v3<T>(0, 0, 1)};
    for (const auto& light : lights) {
        const auto a = light.sample_incident(up, u);
        REQUIRE(a);
        const auto& held = light.get();
        if (std::holds_alternative<shade::environment_light<T>>(held)) {
            // any_light forwards the context to the environment.
            CHECK(a->l == sky.sample_incident(up, u)->l);
            CHECK(light.pdf_incident(up, a->l) == sky.pdf_incident(up, a->l));
        } else {
            const auto b = light.sample_incident(p, u);
            REQUIRE(b);
            CHECK(a->l == b->l);
            CHECK(a->pdf == b->pdf);
            CHECK(light.pdf_incident(up, a->l) == light.pdf_incident(p, a->l));
        }
    }
}
