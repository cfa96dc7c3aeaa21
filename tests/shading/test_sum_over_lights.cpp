#include <cmath>
#include <span>
#include <tuple>
#include <vector>

#include <doctest/doctest.h>

#include <shade/light/any_light.hpp>
#include <shade/shading/sum_over_lights.hpp>

#include "shading/local_models.hpp"

using test_models::lambert;
using test_models::near;

namespace {

// Three lights around the origin (normal +z), each delivering diffuse colour 1 along a
// known direction, each with ambient intensity x colour = 0.1 (the ambient colour is
// scaled by the intensity, so 0.1/25 and 0.1/4 for the brighter two):
//   * directional from +z:                         n.l = 1
//   * point at (0, 3, 4), intensity 25, 1/r^2:     r = 5, 25/25 = 1, n.l = 4/5
//   * spot at (0, 0, 2) pointing down, inner 0.5 rad, outer 1 rad, intensity 4, 1/r^2:
//     on the axis, factor 1, 4/4 = 1, n.l = 1
template <class T>
std::vector<shade::any_light<T>> three_lights() {
    using v = shade::vec3<T>;
    shade::emission<T> e;
    e.ambient = shade::rgb<T>(T(0.1));
    shade::emission<T> e25 = e;
    e25.intensity = T(25);
    e25.ambient = shade::rgb<T>(T(0.004));
    shade::emission<T> e4 = e;
    e4.intensity = T(4);
    e4.ambient = shade::rgb<T>(T(0.025));
    return {shade::directional_light<T>(v(0, 0, 1), e), shade::point_light<T>(v(0, 3, 4), e25),
            shade::spot_light<T>(v(0, 0, 2), v(0, 0, -1), T(0.5), T(1), e4)};
}

} // namespace

TEST_CASE_TEMPLATE("sum_over_lights sums a lit Lambert over several lights", T, float, double) {
    using v = shade::vec3<T>;
    using c = shade::rgb<T>;
    // k_d = 0.5: diffuse terms 0.5 x (1 + 4/5 + 1) = 1.4; ambient k_a = 0.2 x 0.1 per
    // light, 3 lights: 0.06. Total 1.46.
    const shade::lit<lambert<T>> model{lambert<T>{c(T(0.5))}, c(T(0.2))};
    const auto at = shade::surface_point<T>::at(v(0), v(0, 0, 1));
    const auto lights = three_lights<T>();
    const c sum = shade::sum_over_lights(model, at, v(0, 0, 1), lights);
    CHECK(near(sum, c(T(1.46)), T(1e-5)));
    // It is the sum of the individual shades.
    c by_hand(0);
    for (const auto& l : lights) by_hand += model.shade(at, v(0, 0, 1), l.sample(at.p, shade::vec2<T>(T(0.5))));
    CHECK(near(sum, by_hand, T(1e-6)));
    // Same through a span and through a tuple of concrete light types.
    CHECK(near(shade::sum_over_lights(model, at, v(0, 0, 1), std::span(lights)), sum, T(1e-6)));
    shade::emission<T> e;
    e.ambient = c(T(0.1));
    shade::emission<T> e25 = e;
    e25.intensity = T(25);
    e25.ambient = shade::rgb<T>(T(0.004));
    shade::emission<T> e4 = e;
    e4.intensity = T(4);
    e4.ambient = shade::rgb<T>(T(0.025));
    const auto tuple = std::make_tuple(shade::directional_light<T>(v(0, 0, 1), e),
                                       shade::point_light<T>(v(0, 3, 4), e25),
                                       shade::spot_light<T>(v(0, 0, 2), v(0, 0, -1), T(0.5), T(1), e4));
    CHECK(near(shade::sum_over_lights(model, at, v(0, 0, 1), tuple), sum, T(1e-6)));
    // A BRDF directly: the lift without ambient, 1.4.
    CHECK(near(shade::sum_over_lights(lambert<T>{c(T(0.5))}, at, v(0, 0, 1), lights), c(T(1.4)), T(1e-5)));
    // No lights: black.
    CHECK(shade::sum_over_lights(model, at, v(0, 0, 1), std::vector<shade::any_light<T>>{}) == c(0));
}

TEST_CASE_TEMPLATE("sum_over_lights: the visibility callback shadows lights, not their ambient", T, float, double) {
    using v = shade::vec3<T>;
    using c = shade::rgb<T>;
    const shade::lit<lambert<T>> model{lambert<T>{c(T(0.5))}, c(T(0.2))};
    const auto at = shade::surface_point<T>::at(v(0), v(0, 0, 1));
    const auto lights = three_lights<T>();
    // Occlude the point light (the only sample at distance 5): its 0.4 goes, its ambient
    // 0.02 stays: 1.46 - 0.4 = 1.06.
    int calls = 0;
    const auto occlude_point = [&](const shade::light_sample<T>& s) {
        ++calls;
        return !(std::abs(s.distance - T(5)) < T(1e-3));
    };
    CHECK(near(shade::sum_over_lights(model, at, v(0, 0, 1), lights, occlude_point), c(T(1.06)), T(1e-5)));
    CHECK(calls == 3);
    // Everything occluded: only the ambient 0.06 remains.
    const auto all_blocked = [](const shade::light_sample<T>&) { return false; };
    CHECK(near(shade::sum_over_lights(model, at, v(0, 0, 1), lights, all_blocked), c(T(0.06)), T(1e-6)));
    // A scalar transmittance 1/2 halves the direct part: 0.7 + 0.06.
    const auto half = [](const shade::light_sample<T>&) { return T(0.5); };
    CHECK(near(shade::sum_over_lights(model, at, v(0, 0, 1), lights, half), c(T(0.76)), T(1e-5)));
    // An rgb transmittance filters per channel: (1.46, 0.06, 1.46).
    const auto green_filter = [](const shade::light_sample<T>&) { return c(1, 0, 1); };
    CHECK(near(shade::sum_over_lights(model, at, v(0, 0, 1), lights, green_filter),
               c(T(1.46), T(0.06), T(1.46)), T(1e-5)));
}

TEST_CASE_TEMPLATE("sum_over_lights does not ask visibility for samples that bring no light", T, float, double) {
    using v = shade::vec3<T>;
    using c = shade::rgb<T>;
    // The spot from three_lights seen from (5, 0, 0): angle atan(5/2) = 68 degrees > 1 rad
    // (57 degrees), outside the cone. Only the directional and point lights need a ray.
    const auto lights = three_lights<T>();
    const auto at = shade::surface_point<T>::at(v(5, 0, 0), v(0, 0, 1));
    int calls = 0;
    const auto count = [&](const shade::light_sample<T>&) {
        ++calls;
        return true;
    };
    (void)shade::sum_over_lights(lambert<T>{c(1)}, at, v(0, 0, 1), lights, count);
    CHECK(calls == 2);
}

TEST_CASE_TEMPLATE("sum_over_lights samples area lights on an n x n grid", T, float, double) {
    using v = shade::vec3<T>;
    using c = shade::rgb<T>;
    // The unit-height square [-1, 1]^2 facing down over the origin, white, intensity 1: a
    // white Lambert surface reflects pi F = 4 k atan(k), k = 1/sqrt(2) (derived in
    // tests/light/test_area.cpp), 1.7408395; the 32 x 32 midpoint-rule error bound there
    // scales with Delta^2: (1/16)^2 / 24 x 32 = 5.2e-3.
    const shade::area_light<T> panel(v(-1, -1, 1), v(0, 2, 0), v(2, 0, 0));
    const std::vector<shade::any_light<T>> lights{panel};
    const auto at = shade::surface_point<T>::at(v(0), v(0, 0, 1));
    int calls = 0;
    const auto count = [&](const shade::light_sample<T>&) {
        ++calls;
        return true;
    };
    const c out = shade::sum_over_lights(lambert<T>{c(1)}, at, v(0, 0, 1), lights, count, 32);
    CHECK(calls == 32 * 32);
    const double k = 1.0 / std::sqrt(2.0);
    CHECK(std::abs(double(out.x) - 4 * k * std::atan(k)) <= 5.2e-3);
    // One sample per side is the centre sample alone: cos 1, r 1, A 4: 4.
    const c one = shade::sum_over_lights(lambert<T>{c(1)}, at, v(0, 0, 1), lights, shade::always_visible{}, 1);
    CHECK(near(one, c(4), T(1e-5)));
    CHECK_THROWS_WITH_AS((void)shade::sum_over_lights(lambert<T>{c(1)}, at, v(0, 0, 1), lights,
                                                      shade::always_visible{}, 0),
                         doctest::Contains("'samples_per_side'"), shade::invalid_parameter);
}

namespace {

/// A light that holds an any_light but is not one, without a visit member: sum_over_lights
/// dispatches each of its samples separately (the per-sample path), so comparing with a
/// plain any_light checks the dispatch-once path of light_holder lights.
template <class T>
struct per_sample_light {
    using scalar_type = T;
    shade::any_light<T> held;
    [[nodiscard]] shade::light_sample<T> sample(const shade::vec3<T>& p, const shade::vec2<T>& u) const {
        return held.sample(p, u);
    }
    [[nodiscard]] bool is_delta() const { return held.is_delta(); }
};

} // namespace

TEST_CASE_TEMPLATE("sum_over_lights gives any_light's held lights the same samples as a per-sample dispatch", T, float, double) {
    using v = shade::vec3<T>;
    using c = shade::rgb<T>;
    static_assert(shade::detail::light_holder<shade::any_light<T>>);
    static_assert(!shade::detail::light_holder<per_sample_light<T>>);
    auto lights = three_lights<T>();
    lights.emplace_back(shade::area_light<T>(v(-1, -1, 1), v(0, 2, 0), v(2, 0, 0)));
    std::vector<per_sample_light<T>> wrapped;
    for (const auto& l : lights) wrapped.push_back({l});
    const auto at = shade::surface_point<T>::at(v(T(0.1), T(-0.2), 0), v(0, 0, 1));
    const v view = glm::normalize(v(1, 0, 2));
    // A jitter that draws from a sequence and a visibility that shadows every third
    // sample: both paths must ask them in the same order, with the same samples.
    const auto run = [&](const auto& ls) {
        int draws = 0;
        int asked = 0;
        std::vector<shade::vec3<T>> directions;
        const auto jitter = [&](int, int) {
            ++draws;
            return shade::vec2<T>(T(draws % 7) / T(7), T(draws % 5) / T(5));
        };
        const auto visible = [&](const shade::light_sample<T>& s) {
            directions.push_back(s.l);
            return ++asked % 3 != 0;
        };
        const c out = shade::sum_over_lights(lambert<T>{c(T(0.8))}, at, view, ls, visible, 3, jitter);
        return std::tuple(out, draws, directions);
    };
    const auto [direct, draws_direct, directions_direct] = run(lights);
    const auto [dispatched, draws_dispatched, directions_dispatched] = run(wrapped);
    CHECK(draws_direct == 9);
    CHECK(draws_direct == draws_dispatched);
    CHECK(directions_direct == directions_dispatched);
    CHECK(direct == dispatched); // bit for bit
    CHECK(direct.x > 0);
}
