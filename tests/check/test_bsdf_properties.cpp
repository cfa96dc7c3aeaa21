// The BSDF property checks over the whole sphere (shade/check/bsdf_energy.hpp and
// shade/check/bsdf_reciprocity.hpp): known values on the smooth dielectric, shade's BSDFs
// passing, and each check catching a deliberately broken BSDF.
#include <cmath>
#include <optional>

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/brdf/lambert.hpp>
#include <shade/brdf/microfacet.hpp>
#include <shade/bsdf/rough_dielectric.hpp>
#include <shade/bsdf/smooth_conductor.hpp>
#include <shade/bsdf/smooth_dielectric.hpp>
#include <shade/bsdf/thin_dielectric.hpp>
#include <shade/check/bsdf_energy.hpp>
#include <shade/check/bsdf_reciprocity.hpp>
#include <shade/check/doctest.hpp>

namespace {

template <class T>
shade::surface_point<T> tilted_point() {
    // Away from the origin with a tilted normal: the checks must use the frame of `at`.
    return shade::surface_point<T>::at({T(1), T(-2), T(3)}, glm::normalize(shade::vec3<T>(1, 2, 2)));
}

// A rough dielectric with one deliberate flaw each.
enum class bsdf_flaw {
    importance_f,       ///< f returns the importance-mode value (no (eta_v / eta_l)^2)
    radiance_weights,   ///< sample ignores the mode: radiance-mode weights in importance mode
};

template <class T>
struct broken_dielectric {
    using scalar_type = T;
    shade::rough_dielectric<shade::ggx<T>> model{shade::ggx<T>(T(0.3)), T(1.5)};
    bsdf_flaw kind;
    [[nodiscard]] shade::rgb<T> f(const shade::vec3<T>& l, const shade::vec3<T>& v,
                                  const shade::surface_point<T>& at) const {
        return kind == bsdf_flaw::importance_f ? model.f(v, l, at) : model.f(l, v, at);
    }
    [[nodiscard]] T pdf(const shade::vec3<T>& l, const shade::vec3<T>& v, const shade::surface_point<T>& at) const {
        return model.pdf(l, v, at);
    }
    [[nodiscard]] std::optional<shade::bsdf_sample<T>> sample(const shade::vec3<T>& v, T uc, const shade::vec2<T>& u,
                                                              const shade::surface_point<T>& at,
                                                              shade::transport_mode mode) const {
        return model.sample(v, uc, u, at, kind == bsdf_flaw::radiance_weights ? shade::transport_mode::radiance : mode);
    }
};

} // namespace

TEST_CASE_TEMPLATE("bsdf_albedo: the smooth dielectric at normal incidence reflects R = ((eta - 1)/(eta + 1))^2 and transmits the rest",
                   T, float, double) {
    // Fresnel at normal incidence (Born, Wolf 1999, "Principles of Optics", 7th ed., eq.
    // 1.5.(21)): R = ((eta - 1)/(eta + 1))^2 = (0.5 / 2.5)^2 = 0.04 for eta 1.5, the same
    // from either side. The lossless interface sends R back and 1 - R = 0.96 through, so
    // every importance-mode sample weighs exactly 1 (reflection with probability R, weight
    // 1; refraction with 1 - R, weight 1): the total is 1 with zero error, and each part
    // is a binomial proportion, within 4 standard errors of R and 1 - R.
    const auto at = tilted_point<T>();
    const shade::smooth_dielectric<T> glass(T(1.5));
    for (const T side : {T(1), T(-1)}) {
        CAPTURE(side);
        const auto a = shade::check::bsdf_albedo(glass, side * at.n(), at, 128);
        CHECK(a.inside == (side < 0));
        CHECK(a.total.x == doctest::Approx(1).epsilon(1e-6));
        CHECK(a.total_error.x <= 1e-6);
        CHECK(std::abs(a.reflected.x - 0.04) <= 4 * a.reflected_error.x + 1e-6);
        CHECK(std::abs(a.transmitted.x - 0.96) <= 4 * a.transmitted_error.x + 1e-6);
        CHECK(a.reflected_error.x > 0);
        CHECK(a.reflected.x + a.transmitted.x == doctest::Approx(1).epsilon(1e-6));
    }
}

TEST_CASE_TEMPLATE("bsdf_albedo: a BRDF reflects its albedo and transmits nothing; from below it sends out nothing",
                   T, float, double) {
    // Lambert k_d / pi: every cosine-weighted sample weighs k_d (Lambert 1760; the
    // albedo of k_d / pi is pi k_d / pi = k_d). Seen from below, a BRDF draws nothing.
    const auto at = tilted_point<T>();
    const shade::lambert<T> white(shade::rgb<T>(T(0.5)));
    const auto above = shade::check::bsdf_albedo(white, glm::normalize(at.n() + at.shading.t), at, 64);
    CHECK(above.reflected.x == doctest::Approx(0.5).epsilon(1e-5));
    CHECK(above.transmitted.x == 0);
    const auto below = shade::check::bsdf_albedo(white, -at.n(), at, 64);
    CHECK(below.total.x == 0);
}

TEST_CASE_TEMPLATE("bsdf_energy_conservation: shade's BSDFs pass on both sides, a sampler that ignores the mode fails",
                   T, float, double) {
    const auto at = tilted_point<T>();
    shade::check::albedo_options options{.strata = 64, .view_angles = 6, .azimuths = 2};
    options.model = "rough glass";
    shade::check::doctest_expect(shade::check::bsdf_energy_conservation(
        shade::rough_dielectric<shade::ggx<T>>(shade::ggx<T>(T(0.3)), T(1.5)), at, options));
    shade::check::doctest_expect(shade::check::bsdf_energy_conservation(
        shade::rough_dielectric<shade::beckmann<T>>(shade::beckmann<T>(T(0.5)), T(1) / T(1.33)), at, options));
    shade::check::doctest_expect(shade::check::bsdf_energy_conservation(shade::smooth_dielectric<T>(T(1.5)), at, options));
    shade::check::doctest_expect(shade::check::bsdf_energy_conservation(shade::thin_dielectric<T>(T(1.5)), at, options));
    // Radiance-mode weights from inside gain 1/eta'^2 = 1.5^2 = 2.25 through a refraction
    // into the air (shade/bsdf/bsdf.hpp), so at the failing view, with the same draws (same
    // seed), the broken transmitted albedo is exactly 2.25 times the true one, and the
    // reflected one is the same.
    const broken_dielectric<T> broken{.kind = bsdf_flaw::radiance_weights};
    const auto r = shade::check::bsdf_energy_conservation(broken, at, options);
    shade::check::doctest_expect_failure(r);
    CHECK(glm::dot(r.v, at.n()) < 0); // the failing view is inside
    const auto wrong = shade::check::bsdf_albedo(broken, r.v, at, 64, 5);
    const auto right = shade::check::bsdf_albedo(broken.model, r.v, at, 64, 5);
    CHECK(right.total.x <= 1);
    CHECK(wrong.transmitted.x == doctest::Approx(2.25 * right.transmitted.x).epsilon(1e-5));
    CHECK(wrong.reflected.x == doctest::Approx(right.reflected.x).epsilon(1e-5));
    CHECK(r.worst > 1.5);
}

TEST_CASE_TEMPLATE("adjoint_reciprocity: shade's BSDFs hold f(l, v) eta_l^2 = f(v, l) eta_v^2; the importance-mode f and a wrong eta fail",
                   T, float, double) {
    const auto at = tilted_point<T>();
    shade::check::pair_options options{.pairs = 4000};
    options.model = "rough glass";
    const shade::rough_dielectric<shade::ggx<T>> glass(shade::ggx<T>(T(0.3)), T(1.5));
    const auto r = shade::check::adjoint_reciprocity(glass, at, 1.5, options);
    shade::check::doctest_expect(r);
    MESSAGE("rough glass, worst relative difference ", r.worst);
    CHECK(r.tried == 4000);
    shade::check::doctest_expect(shade::check::adjoint_reciprocity(
        shade::rough_dielectric<shade::beckmann<T>>(shade::beckmann<T>(T(0.1), T(0.4)), T(1) / T(1.33)), at,
        1 / 1.33, options));
    // Delta lobes have f = 0 (the check passes trivially), a BRDF is reciprocal with eta 1.
    shade::check::doctest_expect(shade::check::adjoint_reciprocity(shade::thin_dielectric<T>(T(1.5)), at, 1, options));
    shade::check::doctest_expect(shade::check::adjoint_reciprocity(shade::lambert<T>(shade::rgb<T>(T(0.5))), at, 1, options));
    // The same interface checked with the wrong index inside: transmission is off by
    // 1.5^2 = 2.25 (relative difference 1 - 1/2.25 = 0.56).
    const auto wrong_eta = shade::check::adjoint_reciprocity(glass, at, 1, options);
    shade::check::doctest_expect_failure(wrong_eta);
    CHECK(wrong_eta.worst > 0.5);
    // f in importance mode: every transmission off by eta'^4 (1 - 1/1.5^4 = 0.80).
    const auto importance = shade::check::adjoint_reciprocity(broken_dielectric<T>{.kind = bsdf_flaw::importance_f},
                                                              at, 1.5, options);
    shade::check::doctest_expect_failure(importance);
    CHECK(importance.worst > 0.75);
    // Reflection alone is symmetric: the failures are all transmissions, half the pairs
    // (l and v on opposite sides) at most.
    CHECK(importance.failures <= options.pairs / 2);
    CHECK(glm::dot(importance.l, at.n()) * glm::dot(importance.v, at.n()) < 0);
}

TEST_CASE("sphere_pairs: the four combinations of sides, equally often") {
    const auto at = tilted_point<double>();
    const auto pairs = shade::check::sphere_pairs(at, 400, 3);
    REQUIRE(pairs.size() == 400);
    int counts[2][2] = {};
    for (const auto& p : pairs) {
        CHECK(glm::length(p.l) == doctest::Approx(1));
        CHECK(glm::length(p.v) == doctest::Approx(1));
        ++counts[glm::dot(p.l, at.n()) < 0][glm::dot(p.v, at.n()) < 0];
    }
    for (const auto& row : counts)
        for (const int c : row) CHECK(c == 100);
}

TEST_CASE("adjoint_reciprocity and bsdf_albedo: bad parameters are refused by name") {
    const auto at = tilted_point<double>();
    const shade::smooth_dielectric<double> glass(1.5);
    CHECK_THROWS_WITH_AS(shade::check::adjoint_reciprocity(glass, at, 0.0), doctest::Contains("eta_inside"),
                         shade::invalid_parameter);
    CHECK_THROWS_WITH_AS(shade::check::bsdf_albedo(glass, at.n(), at, 1), doctest::Contains("strata"),
                         shade::invalid_parameter);
}
