// The debug-build precondition checks (SHADE_ASSERT, include/shade/core/config.hpp): each
// fires on input outside the documented precondition and stays quiet inside it. SHADE_ASSERT
// is defined here, before any shade header, to count failures instead of aborting, so the
// checks run whatever NDEBUG says (tests/robustness/assert_default.cpp checks the default
// definition: abort without NDEBUG, nothing with it). Built as its own program, without the
// test-suite's precompiled header (tests/CMakeLists.txt).

#include <limits>

namespace precondition_test {
inline int failures = 0;
} // namespace precondition_test

#define SHADE_ASSERT(cond) ((cond) ? void(0) : void(++precondition_test::failures))

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/brdf/ashikhmin_shirley.hpp>
#include <shade/brdf/blinn_phong.hpp>
#include <shade/brdf/eon.hpp>
#include <shade/brdf/lambert.hpp>
#include <shade/brdf/oren_nayar.hpp>
#include <shade/brdf/phong.hpp>
#include <shade/core/sampling.hpp>
#include <shade/core/surface_point.hpp>
#include <shade/light/directional.hpp>
#include <shade/shading/shader.hpp>

#include "shading/local_models.hpp"

namespace {

// The number of SHADE_ASSERT failures while f runs.
template <class F>
int failures_during(F&& f) {
    const int before = precondition_test::failures;
    f();
    return precondition_test::failures - before;
}

} // namespace

TEST_CASE_TEMPLATE("SHADE_ASSERT: the square_to_* maps check u in the half-open unit square", T, float, double) {
    using v2 = shade::vec2<T>;
    const T nan = std::numeric_limits<T>::quiet_NaN();
    const T below_one = T(1) - std::numeric_limits<T>::epsilon() / 2;
    for (const v2 u : {v2(0, 0), v2(T(0.3), T(0.7)), v2(below_one, below_one)}) {
        CHECK(failures_during([&] { (void)shade::square_to_cosine_hemisphere(u); }) == 0);
        CHECK(failures_during([&] { (void)shade::square_to_uniform_hemisphere(u); }) == 0);
        CHECK(failures_during([&] { (void)shade::square_to_concentric_disk(u); }) == 0);
    }
    for (const v2 u : {v2(T(1.5), T(0.5)), v2(T(-0.1), T(0.2)), v2(1, 0), v2(T(0.5), 1), v2(nan, T(0.5))}) {
        CAPTURE(u.x);
        CAPTURE(u.y);
        // square_to_cosine_hemisphere checks u itself and again in the disk map it calls.
        CHECK(failures_during([&] { (void)shade::square_to_cosine_hemisphere(u); }) >= 1);
        CHECK(failures_during([&] { (void)shade::square_to_uniform_hemisphere(u); }) == 1);
        CHECK(failures_during([&] { (void)shade::square_to_concentric_disk(u); }) == 1);
    }
    // What the check is for: u = (1.5, 0.5) maps outside the disk (a = 2, so r = 2), and
    // the lifted direction (2, 0, 0) is not a unit vector.
    const auto w = shade::square_to_cosine_hemisphere(v2(T(1.5), T(0.5)));
    CHECK_FALSE(shade::is_unit_length(w));
}

TEST_CASE_TEMPLATE("SHADE_ASSERT: stratified_u checks the stratum and the jitter", T, float, double) {
    using v2 = shade::vec2<T>;
    CHECK(failures_during([] { (void)shade::stratified_u(3, 0, 4, v2(T(0.5))); }) == 0);
    CHECK(failures_during([] { (void)shade::stratified_u(4, 0, 4, v2(T(0.5))); }) == 1);
    CHECK(failures_during([] { (void)shade::stratified_u(0, -1, 4, v2(T(0.5))); }) == 1);
    CHECK(failures_during([] { (void)shade::stratified_u(0, 0, 4, v2(1, 0)); }) == 1);
}

TEST_CASE_TEMPLATE("SHADE_ASSERT: surface_point::at and lit::shade check unit-length directions", T, float,
                   double) {
    using v = shade::vec3<T>;
    using c = shade::rgb<T>;
    CHECK(failures_during([] { (void)shade::surface_point<T>::at(v(0), v(0, 0, 1)); }) == 0);
    CHECK(failures_during([] { (void)shade::surface_point<T>::at(v(0), v(0, 0, 2)); }) == 1);
    CHECK(failures_during([] { (void)shade::surface_point<T>::at(v(0), v(1, 1, 0)); }) == 1);

    const shade::lit<test_models::lambert<T>> model(test_models::lambert<T>{c(T(0.5))});
    const auto at = shade::surface_point<T>::at(v(0), v(0, 0, 1));
    const shade::directional_light<T> sun(v(T(0.6), 0, T(0.8)));
    const auto sample = sun.sample(at.p);
    CHECK(failures_during([&] { (void)model.shade(at, v(0, 0, 1), sample); }) == 0);
    // v of length 2 (a ray direction not normalised).
    CHECK(failures_during([&] { (void)model.shade(at, v(0, 0, 2), sample); }) == 1);
    auto long_l = sample;
    long_l.l = v(T(1.2), 0, T(1.6));
    CHECK(failures_during([&] { (void)model.shade(at, v(0, 0, 1), long_l); }) == 1);
}

TEST_CASE_TEMPLATE("SHADE_ASSERT: the models' f checks unit-length l, v and n", T, float, double) {
    using v = shade::vec3<T>;
    using c = shade::rgb<T>;
    const auto at = shade::surface_point<T>::at(v(0), v(0, 0, 1));
    const v l = glm::normalize(v(T(0.3), T(0.2), 1));
    const v view = glm::normalize(v(T(-0.4), T(0.1), 1));
    const auto check = [&](const auto& brdf) {
        CHECK(failures_during([&] { (void)brdf.f(l, view, at); }) == 0);
        // The same directions scaled by 2, and a shading frame built on a normal of length 2
        // (at() asserts that one too).
        CHECK(failures_during([&] { (void)brdf.f(T(2) * l, view, at); }) >= 1);
        CHECK(failures_during([&] { (void)brdf.f(l, T(2) * view, at); }) >= 1);
        auto long_n = at;
        long_n.shading.n = v(0, 0, 2);
        CHECK(failures_during([&] { (void)brdf.f(l, view, long_n); }) >= 1);
    };
    check(shade::lambert<T>(c(T(0.5))));
    check(shade::oren_nayar<T>(c(T(0.5)), T(0.3)));
    check(shade::eon<T>(c(T(0.5)), T(0.3)));
    check(shade::fujii_oren_nayar<T>(c(T(0.5)), T(0.3)));
    check(shade::phong<T>(c(T(0.25)), c(T(0.5)), T(20)));
    check(shade::blinn_phong<T>(c(T(0.25)), c(T(0.5)), T(20)));
    check(shade::ashikhmin_shirley<T>(c(T(0.25)), c(T(0.5)), T(10), T(100)));
}
