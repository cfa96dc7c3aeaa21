#include <cmath>
#include <limits>
#include <type_traits>

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/brdf/cook_torrance.hpp>
#include <shade/brdf/lambert.hpp>
#include <shade/brdf/oren_nayar.hpp>
#include <shade/brdf/phong.hpp>
#include <shade/shading/checker.hpp>
#include <shade/shading/gradient.hpp>

#include "brdf/sampling.hpp"
#include "shading/local_models.hpp"

using test_models::constant_shader;
using test_models::lambert;
using test_models::near;
using test_models::split_constant;

namespace {

template <class T>
shade::light_sample<T> white_from_above() {
    shade::light_sample<T> s;
    s.l = shade::vec3<T>(0, 0, 1);
    s.distance = T(1);
    s.diffuse = shade::rgb<T>(1);
    s.specular = shade::rgb<T>(1);
    return s;
}

template <class T>
shade::surface_point<T> at_point(T x, T y, T z) {
    return shade::surface_point<T>::at(shade::vec3<T>(x, y, z), shade::vec3<T>(0, 0, 1));
}

} // namespace

TEST_CASE_TEMPLATE("checker: BRDF children make a BRDF, shader or mixed children a shader", T, float, double) {
    using S = constant_shader<T>;
    using L = lambert<T>;
    using P = split_constant<T>;
    static_assert(shade::brdf<shade::checker<L, L>>);
    static_assert(!shade::shader<shade::checker<L, L>>);
    static_assert(shade::split_brdf<shade::checker<P, P>>);
    static_assert(!shade::split_brdf<shade::checker<L, P>>);
    static_assert(shade::shader<shade::checker<S, S>>);
    static_assert(!shade::brdf<shade::checker<S, S>>);
    static_assert(shade::shader<shade::checker<S, L>>);
    static_assert(shade::shader<shade::checker<L, S>>);
    static_assert(!shade::brdf<shade::checker<L, S>>);
    static_assert(shade::brdf<shade::checker_2d<L, L>>);
    static_assert(shade::shader<shade::checker_2d<S, L>>);
    CHECK(true);
}

TEST_CASE_TEMPLATE("checker parity, including negative coordinates", T, float, double) {
    using v = shade::vec3<T>;
    using S = constant_shader<T>;
    // Size 1, default bias 1/2: parity = (floor(x + 1/2) + floor(y + 1/2) + floor(z + 1/2))
    // mod 2, i.e. the sum of the coordinates rounded to the nearest integer, mod 2.
    const shade::checker<S, S> board(S{shade::rgb<T>(1, 0, 0)}, S{shade::rgb<T>(0, 1, 0)}, T(1));
    CHECK(board.parity(v(0, 0, 0)) == 0);         // 0 + 0 + 0
    CHECK(board.parity(v(1, 0, 0)) == 1);         // floor(1.5) = 1
    CHECK(board.parity(v(T(0.49), 0, 0)) == 0);   // floor(0.99) = 0
    CHECK(board.parity(v(T(0.51), 0, 0)) == 1);   // floor(1.01) = 1
    CHECK(board.parity(v(-1, 0, 0)) == 1);        // floor(-0.5) = -1, odd
    CHECK(board.parity(v(T(-0.4), 0, 0)) == 0);   // floor(0.1) = 0
    CHECK(board.parity(v(T(-0.6), 0, 0)) == 1);   // floor(-0.1) = -1
    CHECK(board.parity(v(-1, -1, 0)) == 0);       // -1 - 1 = -2, even
    CHECK(board.parity(v(T(-2.6), T(1.2), T(-3.7))) == 0); // -3 + 1 - 4 = -6
    CHECK(board.parity(v(T(-2.6), T(1.2), T(-3.2))) == 1); // -3 + 1 - 3 = -5
    // Size 2: coordinates are halved first: (3, 0, 0) -> floor(1.5 + 0.5) = 2, even.
    const shade::checker<S, S> big(S{}, S{}, T(2));
    CHECK(big.parity(v(3, 0, 0)) == 0);
    CHECK(big.parity(v(T(-1.2), 0, 0)) == 1); // floor(-0.6 + 0.5) = -1
    // Bias 0: floor, not truncation: x = -0.5 is in cell -1 (odd), where truncation would
    // give 0 (even).
    const shade::checker<S, S> unbiased(S{}, S{}, T(1), T(0));
    CHECK(unbiased.parity(v(T(-0.5), 0, 0)) == 1);
    CHECK(unbiased.parity(v(T(-1.5), T(-0.5), T(2.5))) == 1); // -2 - 1 + 2 = -1, odd
}

TEST_CASE_TEMPLATE("checker shades with the selected child", T, float, double) {
    using v = shade::vec3<T>;
    using c = shade::rgb<T>;
    using S = constant_shader<T>;
    const shade::checker board(S{c(1, 0, 0)}, S{c(0, 1, 0)}, T(1));
    const auto s = white_from_above<T>();
    CHECK(board.shade(at_point(T(0), T(0), T(0)), v(0, 0, 1), s) == c(1, 0, 0));
    CHECK(board.shade(at_point(T(1), T(0), T(0)), v(0, 0, 1), s) == c(0, 1, 0));
    // Mixed: a Lambert child (k_d = 0.5, lit without ambient: 0.5 facing the light).
    const shade::checker mixed(S{c(1, 0, 0)}, lambert<T>{c(T(0.5))}, T(1));
    CHECK(mixed.shade(at_point(T(0), T(0), T(0)), v(0, 0, 1), s) == c(1, 0, 0));
    CHECK(near(mixed.shade(at_point(T(1), T(0), T(0)), v(0, 0, 1), s), c(T(0.5)), T(1e-6)));
    // BRDF checker: f of the selected child, 0.2/pi or 0.8/pi.
    const shade::checker brdfs(lambert<T>{c(T(0.2))}, lambert<T>{c(T(0.8))}, T(1));
    const v l(0, 0, 1);
    CHECK(near(brdfs.f(l, l, at_point(T(0), T(0), T(0))), c(T(0.2) / shade::pi<T>), T(1e-7)));
    CHECK(near(brdfs.f(l, l, at_point(T(0), T(-1), T(0))), c(T(0.8) / shade::pi<T>), T(1e-7)));
}

TEST_CASE_TEMPLATE("checker on the plane y = 0: a clean pattern, stable under y = +-tiny", T, float, double) {
    using v = shade::vec3<T>;
    using S = constant_shader<T>;
    const shade::checker<S, S> board(S{}, S{}, T(1));
    // A ray hit on the plane y = 0 has y = 0 up to rounding, of the order of ulp(coordinate)
    // ~ 1e-7 here; test much larger offsets too.
    const T tiny_offsets[] = {T(0), std::numeric_limits<T>::denorm_min(), T(1e-7), T(1e-4)};
    // Sample points avoid the cell edges at x, z = k + 1/2 by 0.03 or more.
    for (int i = 0; i < 60; ++i) {
        for (int k = 0; k < 60; ++k) {
            const T x = T(-3) + T(0.1) * T(i) + T(0.03);
            const T z = T(-3) + T(0.1) * T(k) + T(0.03);
            // Expected: cells are centred on the integers (bias 1/2), so the cell index of
            // x is the nearest integer; parity of the sum of the two indices.
            const long expected = (std::lround(x) + std::lround(z)) & 1L;
            for (const T dy : tiny_offsets) {
                CHECK(board.parity(v(x, dy, z)) == expected);
                CHECK(board.parity(v(x, -dy, z)) == expected);
            }
        }
    }
    // Without the bias the same plane is noisy: y = +1e-4 and y = -1e-4 land in cells 0
    // and -1, flipping the parity. (This is the failure the bias removes.)
    const shade::checker<S, S> unbiased(S{}, S{}, T(1), T(0));
    CHECK(unbiased.parity(v(T(0.3), T(1e-4), T(0.3))) != unbiased.parity(v(T(0.3), T(-1e-4), T(0.3))));
}

TEST_CASE_TEMPLATE("checker_2d: uv and world-axis planes", T, float, double) {
    using v = shade::vec3<T>;
    using S = constant_shader<T>;
    // uv, size 1/2, bias 0: parity = floor(2u) + floor(2v) mod 2.
    const shade::checker_2d<S, S> uv_board(S{}, S{}, T(0.5), shade::checker_plane::uv, T(0));
    auto with_uv = [](T u, T w) {
        auto at = shade::surface_point<T>::at(shade::vec3<T>(0), shade::vec3<T>(0, 0, 1));
        at.uv = shade::vec2<T>(u, w);
        return at;
    };
    CHECK(uv_board.parity(with_uv(T(0.2), T(0.2))) == 0); // 0 + 0
    CHECK(uv_board.parity(with_uv(T(0.7), T(0.2))) == 1); // 1 + 0
    CHECK(uv_board.parity(with_uv(T(0.7), T(0.7))) == 0); // 1 + 1
    CHECK(uv_board.parity(with_uv(T(-0.2), T(0.2))) == 1); // floor(-0.4) = -1
    // xz plane, size 1, default bias 1/2: y is ignored.
    const shade::checker_2d<S, S> floor_board(S{}, S{}, T(1), shade::checker_plane::xz);
    CHECK(floor_board.parity(at_point(T(1), T(123.4), T(0))) == 1); // 1 + 0
    CHECK(floor_board.parity(at_point(T(1), T(-7), T(0))) == 1);
    CHECK(floor_board.parity(at_point(T(-1), T(0), T(-1))) == 0); // -1 - 1 = -2
    CHECK(floor_board.coordinates(at_point(T(1), T(2), T(3))) == shade::vec2<T>(1, 3));
    const shade::checker_2d<S, S> xy(S{}, S{}, T(1), shade::checker_plane::xy);
    const shade::checker_2d<S, S> yz(S{}, S{}, T(1), shade::checker_plane::yz);
    CHECK(xy.coordinates(at_point(T(1), T(2), T(3))) == shade::vec2<T>(1, 2));
    CHECK(yz.coordinates(at_point(T(1), T(2), T(3))) == shade::vec2<T>(2, 3));
    CHECK(xy.parity(at_point(T(1), T(0), T(5))) == 1);
    // It shades: constant children picked by parity.
    const shade::checker_2d colours(S{shade::rgb<T>(1, 0, 0)}, S{shade::rgb<T>(0, 0, 1)}, T(1),
                                    shade::checker_plane::xz);
    CHECK(colours.shade(at_point(T(1), T(0), T(0)), v(0, 0, 1), white_from_above<T>()) ==
          shade::rgb<T>(0, 0, 1));
}

TEST_CASE_TEMPLATE("checkers reject bad parameters by name", T, float, double) {
    using S = constant_shader<T>;
    using board = shade::checker<S, S>;
    using board_2d = shade::checker_2d<S, S>;
    const T nan = std::numeric_limits<T>::quiet_NaN();
    CHECK_THROWS_WITH_AS(board(S{}, S{}, T(0)), doctest::Contains("'size'"),
                         shade::invalid_parameter);
    CHECK_THROWS_WITH_AS(board(S{}, S{}, nan), doctest::Contains("'size'"),
                         shade::invalid_parameter);
    CHECK_THROWS_WITH_AS(board(S{}, S{}, T(1), T(1)), doctest::Contains("'bias'"),
                         shade::invalid_parameter);
    CHECK_THROWS_WITH_AS(board(S{}, S{}, T(1), T(-0.1)), doctest::Contains("'bias'"),
                         shade::invalid_parameter);
    CHECK_THROWS_WITH_AS(board_2d(S{}, S{}, T(-1)), doctest::Contains("'size'"),
                         shade::invalid_parameter);
    CHECK_THROWS_WITH_AS(board_2d(S{}, S{}, T(1), static_cast<shade::checker_plane>(9)),
                         doctest::Contains("'plane'"), shade::invalid_parameter);
}

TEST_CASE_TEMPLATE("checker: non-finite points pick a child without NaN", T, float, double) {
    using S = constant_shader<T>;
    const shade::checker<S, S> board(S{shade::rgb<T>(1)}, S{shade::rgb<T>(2)}, T(1));
    const T nan = std::numeric_limits<T>::quiet_NaN();
    const T inf = std::numeric_limits<T>::infinity();
    const int p_nan = board.parity(shade::vec3<T>(nan, 0, 0));
    const int p_inf = board.parity(shade::vec3<T>(inf, 0, 0));
    CHECK((p_nan == 0 || p_nan == 1));
    CHECK((p_inf == 0 || p_inf == 1));
    // Huge but finite coordinates: floor is exact, no integer overflow.
    CHECK(board.parity(shade::vec3<T>(T(1e30), 0, 0)) == 0); // 1e30 is even
}

TEST_CASE_TEMPLATE("combinators nest: a checker of gradients of local BRDFs", T, float, double) {
    using v = shade::vec3<T>;
    using c = shade::rgb<T>;
    using L = lambert<T>;
    // Two gradients along x (period 4) of Lambert BRDFs, checkered with size 1.
    const shade::gradient g0(L{c(T(0.2))}, L{c(T(0.6))}, v(1, 0, 0), T(4));
    const shade::gradient g1(L{c(T(0.8))}, L{c(T(0.4))}, v(1, 0, 0), T(4));
    const shade::checker nested(g0, g1, T(1));
    static_assert(shade::brdf<decltype(nested)>);
    const v l(0, 0, 1);
    // At x = 0 (parity 0, alpha 1): g0's first child, 0.2/pi.
    CHECK(near(nested.f(l, l, at_point(T(0), T(0), T(0))), c(T(0.2) / shade::pi<T>), T(1e-6)));
    // At x = 1 (parity 1, alpha (1 + cos(pi/2))/2 = 1/2): g1 halfway, (0.8 + 0.4)/2/pi.
    CHECK(near(nested.f(l, l, at_point(T(1), T(0), T(0))), c(T(0.6) / shade::pi<T>), T(1e-6)));
    // At x = 2 (parity 0, alpha 0): g0's second child, 0.6/pi.
    CHECK(near(nested.f(l, l, at_point(T(2), T(0), T(0))), c(T(0.6) / shade::pi<T>), T(1e-6)));
    // Lifted to a shader with lit: 0.6 at x = 2 facing a white light.
    const shade::lit<std::remove_cvref_t<decltype(nested)>> lit_nested{nested, c(0)};
    CHECK(near(lit_nested.shade(at_point(T(2), T(0), T(0)), l, white_from_above<T>()), c(T(0.6)), T(1e-6)));
}


TEST_CASE_TEMPLATE("combinators nest: a checker of gradients of Cook-Torrance and Phong", T, float, double) {
    using v = shade::vec3<T>;
    using c = shade::rgb<T>;
    using ct_type = shade::cook_torrance<shade::beckmann<T>, shade::schlick<T>, shade::v_groove<T>>;
    const ct_type ct(shade::beckmann<T>(T(0.3)), shade::schlick<T>(c(T(0.04))), c(T(0.5)), c(T(0.3)));
    const shade::phong<T> ph(c(T(0.4)), c(T(0.2)), T(20));
    // Gradients along x with period 4: alpha = (1 + cos(pi x / 2)) / 2, i.e. 1 at x = 0,
    // 1/2 at x = 1, 0 at x = 2. Checker size 1 (bias 1/2): parity 0 at x = 0 and 2,
    // 1 at x = 1.
    const shade::gradient g0(ct, ph, v(1, 0, 0), T(4));
    const shade::gradient g1(ph, ct, v(1, 0, 0), T(4));
    const shade::checker nested(g0, g1, T(1));
    using nested_type = std::remove_cvref_t<decltype(nested)>;
    static_assert(shade::brdf<nested_type>);
    static_assert(shade::split_brdf<nested_type>);
    const v l = glm::normalize(v(T(0.3), T(0.1), 1));
    const v view = glm::normalize(v(T(-0.2), T(0.2), 1));
    const auto at0 = shade::surface_point<T>::at(v(0, 0, 0), v(0, 0, 1));
    const auto at1 = shade::surface_point<T>::at(v(1, 0, 0), v(0, 0, 1));
    const auto at2 = shade::surface_point<T>::at(v(2, 0, 0), v(0, 0, 1));
    // x = 0: parity 0 -> g0, alpha 1 -> Cook-Torrance.
    CHECK(near(nested.f(l, view, at0), ct.f(l, view, at0), T(1e-6)));
    // x = 1: parity 1 -> g1, alpha 1/2 -> the mean of Phong and Cook-Torrance.
    CHECK(near(nested.f(l, view, at1), (ph.f(l, view, at1) + ct.f(l, view, at1)) * T(0.5), T(1e-5)));
    // x = 2: parity 0 -> g0, alpha 0 -> Phong.
    CHECK(near(nested.f(l, view, at2), ph.f(l, view, at2), T(1e-6)));
    CHECK(near(nested.f_specular(l, view, at2), ph.f_specular(l, view, at2), T(1e-6)));
    // Lifted with lit and lit by a white light from l: finite, non-negative radiance.
    const shade::lit<nested_type> model{nested, c(0)};
    shade::light_sample<T> s;
    s.l = l;
    s.distance = T(1);
    s.diffuse = c(1);
    s.specular = c(1);
    for (const auto& at : {at0, at1, at2}) {
        const c out = model.shade(at, view, s);
        CHECK(shade::is_finite(out));
        CHECK((out.x >= T(0) && out.y >= T(0) && out.z >= T(0)));
    }
    // A mixed nest (a shader inside) is a shader: checker of (gradient of BRDFs, toon-like
    // constant shader).
    const shade::checker mixed(g0, constant_shader<T>{c(1)}, T(1));
    static_assert(shade::shader<std::remove_cvref_t<decltype(mixed)>>);
    CHECK(mixed.shade(at1, view, s) == c(1));
    CHECK(near(mixed.shade(at0, view, s), shade::lit<ct_type>{ct, c(0)}.shade(at0, view, s), T(1e-5)));
}

TEST_CASE_TEMPLATE("checker of two sampled BRDFs samples the child it evaluates", T, float, double) {
    using D = shade::oren_nayar<T>;
    using P = shade::normalized_phong<T>;
    using C = shade::checker<D, P>;
    static_assert(shade::sampled_brdf<C>);
    static_assert(shade::sampled_brdf<shade::checker_2d<P, D>>);
    static_assert(shade::sampled_brdf<shade::checker<C, shade::gradient<D, P>>>); // nests
    // A user BRDF with f only: the checker is a BRDF, not a sampled one, and shades as before.
    static_assert(shade::brdf<shade::checker<lambert<T>, D>> && !shade::sampled_brdf<shade::checker<lambert<T>, D>>);
    const C c(D(shade::rgb<T>(T(0.7)), T(0.4)), P(shade::rgb<T>(T(0.1)), shade::rgb<T>(T(0.6)), T(30)), T(1));
    // Bias 1/2, size 1: parity 0 at the origin, 1 at (1, 0, 0).
    const auto even = at_point(T(0), T(0), T(0));
    const auto odd = at_point(T(1), T(0), T(0));
    REQUIRE(c.parity(even) == 0);
    REQUIRE(c.parity(odd) == 1);
    const shade::vec3<T> v = glm::normalize(shade::vec3<T>(T(-0.4), T(0.1), 1));
    for (const T uc : {T(0.1), T(0.6), T(0.95)}) {
        const shade::vec2<T> u(T(0.2), T(0.7));
        const auto s0 = c.sample(v, uc, u, even);
        const auto s1 = c.sample(v, uc, u, odd);
        const auto e0 = c.first().sample(v, uc, u, even);
        const auto e1 = c.second().sample(v, uc, u, odd);
        REQUIRE((s0.has_value() && e0.has_value() && s1.has_value() && e1.has_value()));
        CHECK(s0->l == e0->l);
        CHECK(s0->pdf == e0->pdf);
        CHECK(s1->l == e1->l);
        CHECK(s1->pdf == e1->pdf);
        CHECK(c.pdf(s1->l, v, odd) == c.second().pdf(s1->l, v, odd));
        CHECK(c.pdf(s1->l, v, even) == c.first().pdf(s1->l, v, even));
    }
    brdf_test::check_sampled_model(c, even);
    brdf_test::check_sampled_model(c, odd, brdf_test::pdf_rounding(T(30))); // a cos^30 lobe
}
