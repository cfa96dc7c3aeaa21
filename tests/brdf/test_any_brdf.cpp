#include <cmath>
#include <limits>
#include <numbers>
#include <type_traits>
#include <utility>
#include <vector>

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/brdf/aliases.hpp>
#include <shade/brdf/any_brdf.hpp>
#include <shade/brdf/lambert.hpp>
#include <shade/brdf/phong.hpp>
#include <shade/core/sampling.hpp>
#include <shade/light/light_sample.hpp>
#include <shade/shading/shader.hpp>

#include "brdf/support.hpp"

namespace {

// A BRDF with f only (no sampler, no split): f = c (n·l) for n·l, n·v > 0. Its albedo is
// integral c cos^2 dw over the hemisphere = 2 pi c / 3.
template <class T>
struct cosine_power {
    using scalar_type = T;
    T c = T(0.3);
    [[nodiscard]] shade::rgb<T> f(const shade::vec3<T>& l, const shade::vec3<T>& v,
                                  const shade::surface_point<T>& at) const {
        const T n_dot_l = glm::dot(at.n(), l);
        if (!(n_dot_l > T(0)) || !(glm::dot(at.n(), v) > T(0))) return shade::rgb<T>(0);
        return shade::rgb<T>(c * n_dot_l);
    }
};

} // namespace

TEST_CASE_TEMPLATE("any_brdf is a brdf and a sampled_brdf, not a classic split_brdf", T, float, double) {
    static_assert(shade::brdf<shade::any_brdf<T>>);
    static_assert(shade::sampled_brdf<shade::any_brdf<T>>);
    static_assert(!shade::split_brdf<shade::any_brdf<T>>);
    static_assert(std::is_nothrow_move_constructible_v<shade::any_brdf<T>>);
    static_assert(!shade::sampled_brdf<cosine_power<T>>);
    CHECK(true);
}

TEST_CASE_TEMPLATE("any_brdf forwards f, sample and pdf of a sampled BRDF bit for bit", T, float, double) {
    const shade::phong<T> model(shade::rgb<T>(T(0.4)), shade::rgb<T>(T(0.5)), T(20));
    const shade::any_brdf<T> erased = model;
    CHECK(erased.has_own_sampler());
    const auto at = brdf_test::tilted<T>();
    shade::rng g(9);
    for (int i = 0; i < 200; ++i) {
        const auto v = brdf_test::direction(at, T(1.2) * g.uniform<T>(), T(6.28) * g.uniform<T>());
        const shade::vec2<T> u(g.uniform<T>(), g.uniform<T>());
        const T uc = g.uniform<T>();
        const auto a = model.sample(v, uc, u, at);
        const auto b = erased.sample(v, uc, u, at);
        REQUIRE(a.has_value() == b.has_value());
        if (!a) continue;
        CHECK(a->l == b->l);
        CHECK(a->pdf == b->pdf);
        CHECK(a->weight == b->weight);
        CHECK(erased.pdf(a->l, v, at) == model.pdf(a->l, v, at));
        CHECK(erased.f(a->l, v, at) == model.f(a->l, v, at));
    }
}

TEST_CASE_TEMPLATE("any_brdf samples a BRDF without a sampler by the cosine, unbiased", T, float, double) {
    const cosine_power<T> model;
    const shade::any_brdf<T> erased = model;
    CHECK(!erased.has_own_sampler());
    const auto at = brdf_test::tilted<T>();
    const auto v = brdf_test::direction(at, T(0.4), T(1.0));
    // Stratified estimate of the albedo: mean weight f cos / pdf -> 2 pi c / 3.
    const int n = 128;
    double sum = 0;
    for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
            const auto s = erased.sample(v, T(0.5), shade::stratified_u<T>(i, j, n, shade::vec2<T>(T(0.5))), at);
            if (!s) continue;
            CHECK(s->pdf == doctest::Approx(erased.pdf(s->l, v, at)).epsilon(1e-5));
            CHECK(s->pdf == doctest::Approx(glm::dot(at.n(), s->l) / std::numbers::pi_v<T>).epsilon(1e-5));
            sum += double(s->weight.x);
        }
    }
    CHECK(sum / (n * n) == doctest::Approx(2 * std::numbers::pi * 0.3 / 3).epsilon(1e-3));
    // Below the surface: no sample, no density.
    CHECK(!erased.sample(-v, T(0.5), shade::vec2<T>(T(0.5)), at));
    CHECK(erased.pdf(at.n(), -v, at) == T(0));
    // Not split: lit lights all of f with the light's diffuse colour, as it lights the
    // unsplit model itself.
    const auto l = brdf_test::direction(at, T(0.7), T(2.0));
    shade::light_sample<T> light;
    light.l = l;
    light.diffuse = shade::rgb<T>(T(0.8), T(0.5), T(0.2));
    light.specular = shade::rgb<T>(T(0.1), T(0.9), T(0.4));
    const auto wrapped = shade::lit{erased}.shade(at, v, light);
    const auto direct = shade::lit{model}.shade(at, v, light);
    CHECK(glm::length(wrapped - direct) <= T(4) * std::numeric_limits<T>::epsilon() * glm::length(direct));
}

TEST_CASE_TEMPLATE("any_brdf: a split model is lit as unsplit, f times the diffuse colour", T, float, double) {
    // Phong splits into k_d / pi and its lobe; through any_brdf the classic specular colour
    // no longer applies: lit gives pi f (n·l) times the diffuse colour (shade::lit's formula
    // for an unsplit BRDF), which with equal diffuse and specular colours is what the model
    // gives lit directly.
    const shade::phong<T> model(shade::rgb<T>(T(0.4)), shade::rgb<T>(T(0.5)), T(20));
    const shade::any_brdf<T> erased = model;
    const auto at = brdf_test::flat<T>();
    const shade::vec3<T> v = glm::normalize(shade::vec3<T>(0.2, 0, 1));
    const shade::vec3<T> l = glm::normalize(shade::vec3<T>(-0.3, 0.1, 1));
    shade::light_sample<T> light;
    light.l = l;
    light.diffuse = shade::rgb<T>(T(0.8), T(0.5), T(0.2));
    light.specular = light.diffuse;
    const auto wrapped = shade::lit{erased}.shade(at, v, light);
    const auto direct = shade::lit{model}.shade(at, v, light);
    const auto by_hand = std::numbers::pi_v<T> * glm::dot(at.n(), l) * model.f(l, v, at) * light.diffuse;
    CHECK(glm::length(wrapped - by_hand) <= T(8) * std::numeric_limits<T>::epsilon() * glm::length(by_hand));
    CHECK(glm::length(wrapped - direct) <= T(8) * std::numeric_limits<T>::epsilon() * glm::length(direct));
}

TEST_CASE_TEMPLATE("any_brdf: copies own their own model, moves take it", T, float, double) {
    shade::any_brdf<T> a = shade::lambert<T>(shade::rgb<T>(T(0.5)));
    shade::any_brdf<T> b = shade::lambert<T>(shade::rgb<T>(T(0.25)));
    const auto at = brdf_test::flat<T>();
    const shade::vec3<T> w(0, 0, 1);
    b = a; // copy: b holds its own Lambert 0.5
    a = shade::lambert<T>(shade::rgb<T>(T(0.1)));
    CHECK(b.f(w, w, at).x == doctest::Approx(0.5 / std::numbers::pi));
    CHECK(a.f(w, w, at).x == doctest::Approx(0.1 / std::numbers::pi));
    shade::any_brdf<T> c = std::move(b);
    CHECK(c.f(w, w, at).x == doctest::Approx(0.5 / std::numbers::pi));
    b = c; // a moved-from any_brdf may be assigned to
    CHECK(b.f(w, w, at).x == doctest::Approx(0.5 / std::numbers::pi));
}

TEST_CASE_TEMPLATE("a vector of any_brdf holds models of different types", T, float, double) {
    const std::vector<shade::any_brdf<T>> materials{
        shade::lambert<T>(shade::rgb<T>(T(0.5))), cosine_power<T>{},
        shade::make_ggx_conductor(T(0.3), shade::rgb<T>(T(1.0), T(0.71), T(0.29))),
        shade::make_rough_plastic(T(0.2), shade::rgb<T>(T(0.3), T(0.1), T(0.1)))};
    const auto at = brdf_test::flat<T>();
    const shade::vec3<T> v = glm::normalize(shade::vec3<T>(0.2, 0, 1));
    const shade::vec3<T> l = glm::normalize(shade::vec3<T>(-0.3, 0.1, 1));
    CHECK(materials[0].f(l, v, at).x == doctest::Approx(0.5 / std::numbers::pi));
    CHECK(materials[1].f(l, v, at).x == doctest::Approx(0.3 * l.z));
    CHECK(materials[2].has_own_sampler());
    CHECK(!materials[1].has_own_sampler());
    for (const auto& m : materials) CHECK(m.f(l, v, at).x > T(0));
}

TEST_CASE_TEMPLATE("aliases name the long configurations; their factories validate", T, float, double) {
    using long_conductor =
        shade::cook_torrance<shade::ggx<T>, shade::schlick<T>, shade::smith_height_correlated<T>>;
    static_assert(std::same_as<shade::ggx_conductor<T>, long_conductor>);
    const auto gold = shade::make_ggx_conductor(T(0.3), shade::rgb<T>(T(1.0), T(0.71), T(0.29)));
    const long_conductor spelled(shade::ggx<T>(T(0.3)), shade::schlick<T>(shade::rgb<T>(T(1.0), T(0.71), T(0.29))));
    const auto at = brdf_test::flat<T>();
    const shade::vec3<T> v = glm::normalize(shade::vec3<T>(0.2, 0, 1));
    const shade::vec3<T> l = glm::normalize(shade::vec3<T>(-0.3, 0.1, 1));
    CHECK(gold.f(l, v, at) == spelled.f(l, v, at));
    const auto plastic = shade::make_rough_plastic(T(0.2), shade::rgb<T>(T(0.3)));
    CHECK(plastic.k_d() == shade::rgb<T>(T(0.3)));
    CHECK(plastic.fresnel().eta() == T(1.5));
    CHECK_THROWS_WITH_AS((void)shade::make_ggx_conductor(T(0), shade::rgb<T>(1)), doctest::Contains("'alpha'"),
                         shade::invalid_parameter);
    CHECK_THROWS_WITH_AS((void)shade::make_ggx_conductor(T(0.3), shade::rgb<T>(2)), doctest::Contains("'f0'"),
                         shade::invalid_parameter);
    CHECK_THROWS_WITH_AS((void)shade::make_rough_plastic(T(0.3), shade::rgb<T>(-1)), doctest::Contains("'k_d'"),
                         shade::invalid_parameter);
}
