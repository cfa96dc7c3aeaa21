#include <limits>

#include <doctest/doctest.h>

#include <shade/light/directional.hpp>
#include <shade/shading/shader.hpp>

#include "shading/local_models.hpp"

using test_models::constant_shader;
using test_models::lambert;
using test_models::near;
using test_models::split_constant;

TEST_CASE_TEMPLATE("lit<Lambert> under a directional light is k_d I_d (n.l) + k_a I_a", T, float, double) {
    using v = shade::vec3<T>;
    using c = shade::rgb<T>;
    // l = (0.6, 0, 0.8), n = +z: n.l = 0.8. Lambert f = k_d/pi, and lit multiplies by
    // pi (n.l) I_d, so the diffuse term is k_d I_d 0.8 per channel:
    //   k_d = (0.5, 0.25, 1), I_d = (1, 2, 0.5): (0.4, 0.4, 0.4).
    // Ambient k_a I_a = (0.1, 0.2, 0.3) x (1, 1, 2) = (0.1, 0.2, 0.6). Total (0.5, 0.6, 1.0).
    shade::emission<T> e;
    e.ambient = {1, 1, 2};
    e.diffuse = {1, 2, T(0.5)};
    const shade::directional_light<T> sun(v(T(0.6), 0, T(0.8)), e);
    const shade::lit<lambert<T>> model{lambert<T>{c(T(0.5), T(0.25), 1)}, c(T(0.1), T(0.2), T(0.3))};
    const auto at = shade::surface_point<T>::at(v(0), v(0, 0, 1));
    const c out = model.shade(at, v(0, 0, 1), sun.sample(at.p));
    CHECK(near(out, c(T(0.5), T(0.6), T(1.0)), T(1e-6)));
    // The light below the horizon: ambient only.
    const shade::directional_light<T> below(v(0, T(0.6), T(-0.8)), e);
    CHECK(near(model.shade(at, v(0, 0, 1), below.sample(at.p)), c(T(0.1), T(0.2), T(0.6)), T(1e-6)));
}

TEST_CASE_TEMPLATE("lit of a split BRDF lights the specular part with the specular colour", T, float, double) {
    using v = shade::vec3<T>;
    using c = shade::rgb<T>;
    // l = n: n.l = 1. Diffuse k_d/pi x pi x I_d = k_d I_d = 0.5 x 1; specular
    // k_s x pi x I_s = 0.1 x pi x 2 = 0.2 pi in the red channel only.
    shade::emission<T> e;
    e.diffuse = c(1);
    e.specular = c(2, 0, 0);
    const shade::directional_light<T> sun(v(0, 0, 1), e);
    const shade::lit<split_constant<T>> model{split_constant<T>{c(T(0.5)), c(T(0.1))}, c(0)};
    const auto at = shade::surface_point<T>::at(v(0), v(0, 0, 1));
    const c out = model.shade(at, v(0, 0, 1), sun.sample(at.p));
    CHECK(near(out, c(T(0.5) + T(0.2) * shade::pi<T>, T(0.5), T(0.5)), T(1e-6)));
}

TEST_CASE_TEMPLATE("shade_of calls a shader and lifts a BRDF with lit (no ambient)", T, float, double) {
    using v = shade::vec3<T>;
    using c = shade::rgb<T>;
    static_assert(shade::shader_or_brdf<lambert<T>>);
    static_assert(shade::shader_or_brdf<constant_shader<T>>);
    static_assert(!shade::shader_or_brdf<int>);
    shade::emission<T> e;
    e.ambient = c(1);
    const shade::directional_light<T> sun(v(0, 0, 1), e);
    const auto at = shade::surface_point<T>::at(v(0), v(0, 0, 1));
    const auto s = sun.sample(at.p);
    CHECK(shade::shade_of(constant_shader<T>{c(1, 2, 3)}, at, v(0, 0, 1), s) == c(1, 2, 3));
    // Lambert k_d = 0.5 facing the light: 0.5, and the light's ambient 1 is not used.
    CHECK(near(shade::shade_of(lambert<T>{c(T(0.5))}, at, v(0, 0, 1), s), c(T(0.5)), T(1e-6)));
}

TEST_CASE_TEMPLATE("lit rejects an ambient reflectance that is negative or not finite, by name", T, float, double) {
    using c = shade::rgb<T>;
    const lambert<T> brdf{c(T(0.5))};
    const T nan = std::numeric_limits<T>::quiet_NaN();
    const T inf = std::numeric_limits<T>::infinity();
    for (const c bad : {c(-1), c(0, 0, T(-1e-30)), c(nan), c(T(0.1), nan, T(0.1)), c(inf)}) {
        CHECK_THROWS_WITH_AS(shade::lit<lambert<T>>(brdf, bad), doctest::Contains("'ambient'"),
                             shade::invalid_parameter);
    }
    // The documented domain: finite and >= 0 per channel, 0 the default.
    CHECK_NOTHROW(shade::lit<lambert<T>>(brdf, c(0)));
    CHECK_NOTHROW(shade::lit<lambert<T>>(brdf, c(T(0.1), 0, 5)));
    CHECK(shade::lit<lambert<T>>(brdf).ambient() == c(0));
    CHECK(shade::lit<lambert<T>>(brdf, c(T(0.25))).ambient() == c(T(0.25)));
}
