// shade::openpbr_surface at the far ends of valid parameters and directions, where rounding
// and subnormal numbers decide: the cases fuzz/fuzz_bsdf_openpbr.cpp found, kept as tests.

#include <cmath>
#include <limits>
#include <optional>

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/core/frame.hpp>
#include <shade/material/openpbr_surface.hpp>

namespace {

using shade::rgb;
using shade::vec2;
using shade::vec3;

} // namespace

TEST_CASE_TEMPLATE("openpbr_surface: a subnormal geometry_opacity gives finite weights equal to f |n.l| / pdf", T, float,
                   double) {
    // f and the density of the surface's lobes both carry alpha, so both are subnormal and
    // their ratio is an ordinary number; |n.l| / pdf alone overflows, and f times it was inf.
    shade::openpbr_parameters<T> p;
    p.geometry_opacity = std::numeric_limits<T>::denorm_min() * T(16);
    const shade::openpbr_surface<T> m(p);
    shade::surface_point<T> at;
    at.shading = shade::frame<T>::from_normal(vec3<T>(0, 0, 1));
    const vec3<T> v = glm::normalize(vec3<T>(T(0.3), T(0.2), T(1)));
    int surface_draws = 0;
    for (int i = 0; i < 16; ++i) {
        const auto s = m.sample(v, T(0), vec2<T>(T(i + 0.5) / T(16), T(0.3)), at);
        if (!s || shade::is_specular(s->flags)) continue;
        ++surface_draws;
        const long double exact =
            static_cast<long double>(s->f.x) * std::abs(glm::dot(at.n(), s->l)) / static_cast<long double>(s->pdf);
        CHECK(std::isfinite(s->weight.x));
        CHECK(std::abs(static_cast<long double>(s->weight.x) - exact) <= 1e-4L * exact);
    }
    CHECK(surface_draws > 0); // uc = 0 < alpha chooses the surface
}

TEST_CASE_TEMPLATE("openpbr_surface: a subnormal specular_ior and grazing subnormal cosines give finite values", T,
                   float, double) {
    // specular_ior is clamped to [1e-4, 1e4] inside; a fuzz lobe seen along the normal with l
    // in the surface's plane up to a subnormal cosine (importance mode evaluates f(v, l)).
    shade::openpbr_parameters<T> p;
    p.specular_ior = std::numeric_limits<T>::denorm_min() * T(1000);
    p.fuzz_weight = T(0.5);
    p.subsurface_weight = T(1e-4);
    const shade::openpbr_surface<T> m(p);
    shade::surface_point<T> at;
    at.shading = shade::frame<T>::from_normal_tangent(vec3<T>(1, 1, 0), vec3<T>(1, -1, 0));
    const T tiny = std::numeric_limits<T>::denorm_min() * T(1000);
    const vec3<T> grazing = glm::normalize(vec3<T>(tiny, tiny, -1));
    for (const auto mode : {shade::transport_mode::radiance, shade::transport_mode::importance}) {
        const auto f = shade::bsdf_f(m, grazing, at.n(), at, mode);
        const auto g = shade::bsdf_f(m, at.n(), grazing, at, mode);
        CHECK((std::isfinite(f.x) && f.x >= T(0)));
        CHECK((std::isfinite(g.x) && g.x >= T(0)));
        const auto s = m.sample(grazing, T(0.5), vec2<T>(0, 0), at, mode);
        if (s) CHECK((std::isfinite(s->weight.x) && s->weight.x >= T(0)));
    }
}

TEST_CASE_TEMPLATE("openpbr_surface: emission with the largest luminance under a black coat is 0, not NaN", T, float,
                   double) {
    // emission_luminance x emission_color overflows to inf; a coat of colour 0 passes none of
    // it (one-way transmittance 0), so the emission is 0. Multiplying the overflowed product
    // by the coat's 0 gave NaN.
    shade::openpbr_parameters<T> p;
    p.emission_luminance = std::numeric_limits<T>::max();
    p.emission_color = rgb<T>(T(38), T(1), T(1));
    p.coat_weight = T(1);
    p.coat_color = rgb<T>(0, T(0.5), T(0.25));
    const shade::openpbr_surface<T> m(p);
    shade::surface_point<T> at;
    at.shading = shade::frame<T>::from_normal(vec3<T>(0, 0, 1));
    const rgb<T> e = m.emission(glm::normalize(vec3<T>(T(0.2), T(0.1), T(1))), at);
    CHECK(e.x == T(0));
    CHECK(!std::isnan(e.y));
    CHECK(e.y > T(0));
}
