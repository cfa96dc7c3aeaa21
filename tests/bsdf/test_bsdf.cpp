// The BSDF contract (shade/bsdf/bsdf.hpp): every shipped BRDF is a BSDF unchanged, the
// flags and their helpers, and shade::bsdf_f / shade::sample_bsdf over BRDFs and BSDFs.
#include <optional>

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/brdf/aliases.hpp>
#include <shade/brdf/any_brdf.hpp>
#include <shade/brdf/ashikhmin_shirley.hpp>
#include <shade/brdf/blinn_phong.hpp>
#include <shade/brdf/cook_torrance.hpp>
#include <shade/brdf/coupled_plastic.hpp>
#include <shade/brdf/lambert.hpp>
#include <shade/brdf/oren_nayar.hpp>
#include <shade/brdf/phong.hpp>
#include <shade/bsdf/bsdf.hpp>
#include <shade/bsdf/smooth_conductor.hpp>
#include <shade/bsdf/smooth_dielectric.hpp>
#include <shade/bsdf/thin_dielectric.hpp>
#include <shade/shading/checker.hpp>
#include <shade/shading/gradient.hpp>

#include "bsdf/support.hpp"

using namespace bsdf_test;
using shade::bsdf_flags;
using shade::transport_mode;

namespace {

/// A user BRDF with f only: a BSDF, but not a sampled one.
template <class T>
struct constant_brdf {
    using scalar_type = T;
    [[nodiscard]] rgb<T> f(const vec3<T>&, const vec3<T>&, const shade::surface_point<T>&) const { return rgb<T>(T(0.1)); }
};

/// Every sampled BRDF shade ships is a sampled BSDF, unchanged.
template <class T>
constexpr bool every_brdf_is_a_bsdf() {
    using namespace shade;
    static_assert(sampled_bsdf<lambert<T>>);
    static_assert(sampled_bsdf<oren_nayar<T>>);
    static_assert(sampled_bsdf<normalized_phong<T>>);
    static_assert(sampled_bsdf<classic_phong<T>>);
    static_assert(sampled_bsdf<modified_phong<T>>);
    static_assert(sampled_bsdf<blinn_phong<T>>);
    static_assert(sampled_bsdf<ashikhmin_shirley<T>>);
    static_assert(sampled_bsdf<cook_torrance<ggx<T>, schlick<T>, smith_ggx<T>>>);
    static_assert(sampled_bsdf<cook_torrance<beckmann<T>, dielectric_fresnel<T>, v_groove<T>>>);
    static_assert(sampled_bsdf<ggx_conductor<T>>);
    static_assert(sampled_bsdf<compensated_ggx_conductor<T>>);
    static_assert(sampled_bsdf<rough_plastic<T>>);
    static_assert(sampled_bsdf<coupled_plastic<T>>);
    static_assert(sampled_bsdf<any_brdf<T>>);
    static_assert(sampled_bsdf<checker<lambert<T>, blinn_phong<T>>>);
    static_assert(sampled_bsdf<gradient<lambert<T>, normalized_phong<T>>>);
    static_assert(bsdf<constant_brdf<T>> && !sampled_bsdf<constant_brdf<T>>);
    // The BSDFs with delta lobes have their own sampler and are not sampled BRDFs.
    static_assert(bsdf_sampler<smooth_dielectric<T>> && !sampled_brdf<smooth_dielectric<T>>);
    static_assert(bsdf_sampler<thin_dielectric<T>> && !sampled_brdf<thin_dielectric<T>>);
    static_assert(bsdf_sampler<smooth_conductor<T>> && !sampled_brdf<smooth_conductor<T>>);
    return true;
}
static_assert(every_brdf_is_a_bsdf<float>());
static_assert(every_brdf_is_a_bsdf<double>());

} // namespace

TEST_CASE("bsdf_flags: combinations and helpers") {
    using namespace shade;
    static_assert(bsdf_flags::specular_transmission == (bsdf_flags::specular | bsdf_flags::transmission));
    static_assert(is_transmission(bsdf_flags::glossy_transmission) && !is_reflection(bsdf_flags::glossy_transmission));
    static_assert(is_reflection(bsdf_flags::diffuse_reflection) && is_diffuse(bsdf_flags::diffuse_reflection));
    static_assert(is_specular(bsdf_flags::specular_reflection) && !is_non_specular(bsdf_flags::specular_reflection));
    static_assert(is_non_specular(bsdf_flags::glossy_reflection) && is_glossy(bsdf_flags::glossy_reflection));
    static_assert(is_non_specular(bsdf_flags::diffuse_transmission) && !is_specular(bsdf_flags::diffuse_transmission));
    static_assert(!is_reflection(bsdf_flags::none) && !is_non_specular(bsdf_flags::none));
    static_assert(has_flags(bsdf_flags::specular_reflection, bsdf_flags::specular));
    static_assert(!has_flags(bsdf_flags::specular_reflection, bsdf_flags::specular_transmission));
    CHECK((bsdf_flags::glossy | bsdf_flags::reflection) == bsdf_flags::glossy_reflection);
}

TEST_CASE_TEMPLATE("sample_bsdf: a BRDF's sample in radiance mode, bit for bit, flagged glossy reflection", T, float, double) {
    const auto at = brdf_test::tilted<T>();
    const shade::normalized_phong<T> model(rgb<T>(T(0.3)), rgb<T>(T(0.6)), T(30));
    const auto v = view_deg(at, 40);
    for (const T uc : {T(0.1), T(0.9)}) {
        const vec2<T> u(T(0.3), T(0.7));
        const auto b = model.sample(v, uc, u, at);
        const auto s = shade::sample_bsdf(model, v, uc, u, at, transport_mode::radiance);
        REQUIRE(b);
        REQUIRE(s);
        CHECK(s->l == b->l);
        CHECK(s->f == b->f);
        CHECK(s->pdf == b->pdf);
        CHECK(s->weight == b->weight);
        CHECK(s->flags == bsdf_flags::glossy_reflection);
        CHECK(s->eta == T(1));
    }
    CHECK(!shade::sample_bsdf(model, view_deg(at, 120), T(0.5), vec2<T>(T(0.5)), at, transport_mode::radiance));
}

TEST_CASE_TEMPLATE("bsdf_f and sample_bsdf in importance mode use the adjoint f(v, l)", T, float, double) {
    // Classic Phong divides by n·l, so it is not reciprocal: the adjoint differs from f.
    const auto at = brdf_test::tilted<T>();
    const shade::classic_phong<T> model(rgb<T>(0), rgb<T>(T(0.8)), T(5));
    const auto v = view_deg(at, 30);
    const vec2<T> u(T(0.4), T(0.45));
    const auto b = model.sample(v, T(0.5), u, at);
    const auto s = shade::sample_bsdf(model, v, T(0.5), u, at, transport_mode::importance);
    REQUIRE(b);
    REQUIRE(s);
    CHECK(s->l == b->l);
    CHECK(s->pdf == b->pdf);
    CHECK(s->f == model.f(v, s->l, at));
    CHECK(s->f != b->f);
    CHECK(brdf_test::close(s->weight, s->f * glm::dot(at.n(), s->l) / s->pdf, T(1e-6)));
    CHECK(shade::bsdf_f(model, s->l, v, at, transport_mode::importance) == model.f(v, s->l, at));
    CHECK(shade::bsdf_f(model, s->l, v, at, transport_mode::radiance) == model.f(s->l, v, at));
}

TEST_CASE_TEMPLATE("sample_bsdf forwards to a BSDF's own sampler with the mode", T, float, double) {
    const auto at = brdf_test::tilted<T>();
    const shade::smooth_dielectric<T> glass{T(1.5)};
    const auto v = view_deg(at, 30);
    for (const transport_mode mode : {transport_mode::radiance, transport_mode::importance}) {
        const auto a = shade::sample_bsdf(glass, v, T(0.99), vec2<T>(0), at, mode);
        const auto b = glass.sample(v, T(0.99), vec2<T>(0), at, mode);
        REQUIRE(a);
        REQUIRE(b);
        CHECK(a->l == b->l);
        CHECK(a->weight == b->weight);
        CHECK(a->flags == b->flags);
    }
}
