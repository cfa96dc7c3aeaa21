#include <vector>

#include <doctest/doctest.h>

#include <shade/light/any_light.hpp>
#include <shade/light/light.hpp>

namespace {

struct not_a_light {
    using scalar_type = float;
};

struct light_without_is_delta {
    using scalar_type = float;
    [[nodiscard]] shade::light_sample<float> sample(const shade::vec3<float>&, const shade::vec2<float>&) const {
        return {};
    }
};

} // namespace

TEST_CASE_TEMPLATE("every light type, and any_light, satisfies shade::light", T, float, double) {
    static_assert(shade::light<shade::directional_light<T>>);
    static_assert(shade::light<shade::point_light<T>>);
    static_assert(shade::light<shade::spot_light<T>>);
    static_assert(shade::light<shade::area_light<T>>);
    static_assert(shade::light<shade::any_light<T>>);
    static_assert(!shade::light<not_a_light>);
    static_assert(!shade::light<light_without_is_delta>);
    static_assert(!shade::light<int>);
    CHECK(true);
}

TEST_CASE_TEMPLATE("any_light dispatches sample and is_delta to the held light", T, float, double) {
    using v = shade::vec3<T>;
    const shade::directional_light<T> sun(v(0, 0, 1));
    const shade::point_light<T> bulb(v(0, 0, 2));
    const shade::spot_light<T> spot(v(0, 0, 4), v(0, 0, -1), T(0.2), T(0.4));
    const shade::area_light<T> panel(v(-1, -1, 1), v(0, 2, 0), v(2, 0, 0));
    const std::vector<shade::any_light<T>> lights{sun, bulb, spot, panel};
    const v p(0);
    const shade::vec2<T> u(T(0.25), T(0.75));
    CHECK(lights[0].is_delta());
    CHECK(lights[1].is_delta());
    CHECK(lights[2].is_delta());
    CHECK(!lights[3].is_delta());
    CHECK(lights[0].sample(p, u).diffuse == sun.sample(p, u).diffuse);
    CHECK(lights[1].sample(p, u).diffuse == bulb.sample(p, u).diffuse);
    CHECK(lights[2].sample(p, u).diffuse == spot.sample(p, u).diffuse);
    CHECK(lights[3].sample(p, u).l == panel.sample(p, u).l);
    CHECK(lights[3].sample(p, u).diffuse == panel.sample(p, u).diffuse);
    // The point light at distance 2 with 1/r^2: 1/4 (the dispatch reached the right type).
    CHECK(lights[1].sample(p, u).diffuse == shade::rgb<T>(T(0.25)));
    CHECK(std::holds_alternative<shade::area_light<T>>(lights[3].get()));
}
