// Tests of the property checks themselves, on small BRDFs defined here whose properties
// are known analytically. (tests/check/test_models.cpp runs every shade model through
// them.)
#include <cmath>
#include <string>

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/check/doctest.hpp>
#include <shade/check/properties.hpp>

namespace {

template <class T>
shade::surface_point<T> tilted_point() {
    // A point away from the origin with a tilted normal, so the checks are seen to use
    // the frame of `at` rather than assume n = +z.
    return shade::surface_point<T>::at({T(1), T(-2), T(3)}, glm::normalize(shade::vec3<T>(1, 2, 2)));
}

/// rho / pi: albedo exactly rho for every view (each cosine-weighted sample is pi f = rho).
template <class T>
struct test_lambert {
    using scalar_type = T;
    T rho = 1;
    [[nodiscard]] shade::rgb<T> f(const shade::vec3<T>& l, const shade::vec3<T>& v,
                                  const shade::surface_point<T>& at) const {
        if (glm::dot(l, at.n()) <= 0 || glm::dot(v, at.n()) <= 0) return shade::rgb<T>(0);
        return shade::rgb<T>(rho / shade::pi<T>);
    }
};

/// Normalised modified Phong lobe k (e+2)/(2 pi) max(r.v, 0)^e with r = reflect(l) about n.
/// At v = n, r.v = n.l = cos theta, so
///   a(n) = k (e+2)/(2 pi) ∫_0^{2pi} ∫_0^{pi/2} cos^e(theta) cos(theta) sin(theta) dtheta dphi
///        = k (e+2)/(2 pi) * 2 pi / (e+2) = k.
template <class T>
struct test_phong_lobe {
    using scalar_type = T;
    T k = 1;
    T e = 20;
    [[nodiscard]] shade::rgb<T> f(const shade::vec3<T>& l, const shade::vec3<T>& v,
                                  const shade::surface_point<T>& at) const {
        const shade::vec3<T> n = at.n();
        if (glm::dot(l, n) <= 0 || glm::dot(v, n) <= 0) return shade::rgb<T>(0);
        const shade::vec3<T> r = T(2) * glm::dot(n, l) * n - l;
        const T r_dot_v = std::max(glm::dot(r, v), T(0));
        return shade::rgb<T>(k * (e + T(2)) / (T(2) * shade::pi<T>) * std::pow(r_dot_v, e));
    }
};

/// A user BRDF with one deliberate flaw each, to show that each check catches it.
enum class flaw { negative, not_reciprocal, creates_energy, nan_at_normal };

template <class T>
struct broken_brdf {
    using scalar_type = T;
    flaw kind;
    [[nodiscard]] shade::rgb<T> f(const shade::vec3<T>& l, const shade::vec3<T>& v,
                                  const shade::surface_point<T>& at) const {
        const T n_dot_l = glm::dot(l, at.n());
        const T n_dot_v = glm::dot(v, at.n());
        if (n_dot_l <= 0 || n_dot_v <= 0) return shade::rgb<T>(0);
        switch (kind) {
        case flaw::negative: // (l.v)/pi is negative when l and v are more than 90 deg apart
            return shade::rgb<T>(glm::dot(l, v) / shade::pi<T>);
        case flaw::not_reciprocal: // depends on l alone: f(l,v) != f(v,l) when n.l != n.v
            return shade::rgb<T>(n_dot_l / shade::pi<T>);
        case flaw::creates_energy: // 1.02/pi in green only: albedo exactly 1.02 in green
            return shade::rgb<T>(T(0.5), T(1.02), T(0.5)) / shade::pi<T>;
        case flaw::nan_at_normal: // 0/0 when l = v = n
            return shade::rgb<T>((T(1) - n_dot_l) / (T(1) - n_dot_v) / shade::pi<T>);
        }
        return shade::rgb<T>(0);
    }
};

} // namespace

static_assert(shade::brdf<test_lambert<float>>);
static_assert(shade::brdf<broken_brdf<double>>);

TEST_CASE_TEMPLATE("a white Lambert passes all three checks, with albedo exactly 1", T, float, double) {
    const auto at = tilted_point<T>();
    const test_lambert<T> white{1};
    shade::check::doctest_expect(shade::check::positivity(white, at));
    shade::check::doctest_expect(shade::check::reciprocity(white, at));
    // With pure cosine sampling (lobe_fraction 0) every sample contributes
    // f (n.l) / ((n.l)/pi) = pi * (1/pi) = 1, so the estimate is exact up to rounding.
    const auto energy = shade::check::energy_conservation(white, at, {.strata = 64, .lobe_fraction = 0});
    shade::check::doctest_expect(energy);
    CHECK(energy.worst == doctest::Approx(1.0).epsilon(1e-6));
    CHECK(energy.tried == 16 * 4);
    // The default mixture estimator is unbiased but not exact for Lambert: within 0.5% at
    // 64^2 samples, where its standard error (~0.002) is too large for a 4-sigma pass at
    // some views, so the verdict may be inconclusive but never fail; at the default 256^2
    // samples it passes.
    const auto mixed = shade::check::energy_conservation(white, at, {.strata = 64});
    CHECK(mixed.outcome != shade::check::verdict::fail);
    CHECK(mixed.worst == doctest::Approx(1.0).epsilon(0.005));
    shade::check::doctest_expect(shade::check::energy_conservation(white, at));
}

TEST_CASE_TEMPLATE("the albedo estimator tells 1.00 from 1.02", T, float, double) {
    const auto at = tilted_point<T>();
    // Normalised Phong lobe, exponent 20: a(n) = 1 exactly (derivation above); the estimate
    // must be within 0.005 so that 1.00 and 1.02 are told apart with tolerance 0.01.
    const auto s = shade::check::directional_albedo(test_phong_lobe<T>{1, 20}, at.n(), at);
    CHECK(s.albedo.x == doctest::Approx(1.0).epsilon(0.005));
    CHECK(s.standard_error.x < 0.005);
    // The same lobe at oblique views loses energy below the horizon: a(v) < 1.
    const auto energy = shade::check::energy_conservation(test_phong_lobe<T>{1, 20}, at);
    shade::check::doctest_expect(energy);

    const auto over = shade::check::energy_conservation(broken_brdf<T>{flaw::creates_energy}, at,
                                                        {.strata = 32, .lobe_fraction = 0, .model = "green 1.02"});
    shade::check::doctest_expect_failure(over);
    CHECK(over.worst == doctest::Approx(1.02).epsilon(1e-5));
    CHECK(over.failures == over.tried);
    CHECK(over.message.find("green 1.02") != std::string::npos);
    CHECK(over.message.find("FAILS") != std::string::npos);
    CHECK(over.message.find("albedo 1.02") != std::string::npos);
}

TEST_CASE_TEMPLATE("the white-furnace curve covers the requested views", T, float, double) {
    const auto at = shade::surface_point<T>::at({0, 0, 0}, {0, 0, 1});
    const auto curve = shade::check::white_furnace(test_lambert<T>{T(0.5)}, at,
                                                   {.strata = 16, .lobe_fraction = 0, .view_angles = 5, .azimuths = 2});
    REQUIRE(curve.size() == 10);
    CHECK(curve.front().theta_v == T(0));
    CHECK(double(curve[4].theta_v) == doctest::Approx(89.0 * shade::pi<double> / 180.0).epsilon(1e-6));
    CHECK(double(curve[5].phi_v) == doctest::Approx(shade::pi<double> / 2).epsilon(1e-6));
    for (const auto& s : curve) CHECK(s.albedo.y == doctest::Approx(0.5).epsilon(1e-6));
}

TEST_CASE_TEMPLATE("a negative BRDF is caught by the positivity check with the failing pair", T, float, double) {
    const auto at = tilted_point<T>();
    const auto r = shade::check::positivity(broken_brdf<T>{flaw::negative}, at, {.model = "dot(l,v)/pi"});
    shade::check::doctest_expect_failure(r);
    CHECK(r.failures > 0);
    CHECK(r.worst > 0.1);
    // The reported pair really gives the reported negative value.
    const auto again = broken_brdf<T>{flaw::negative}.f(r.l, r.v, at);
    CHECK(again.x == r.value.x);
    CHECK(again.x < T(0));
    CHECK(r.message.find("dot(l,v)/pi") != std::string::npos);
    CHECK(r.message.find("l = (") != std::string::npos);
}

TEST_CASE_TEMPLATE("a NaN is caught by the positivity check", T, float, double) {
    const auto at = tilted_point<T>();
    const auto r = shade::check::positivity(broken_brdf<T>{flaw::nan_at_normal}, at);
    shade::check::doctest_expect_failure(r);
    CHECK(std::isinf(r.worst));
    CHECK(std::isnan(r.value.x));
}

TEST_CASE_TEMPLATE("a BRDF depending on l alone is caught by the reciprocity check", T, float, double) {
    const auto at = tilted_point<T>();
    const auto r = shade::check::reciprocity(broken_brdf<T>{flaw::not_reciprocal}, at,
                                             {.pairs = 2000, .model = "n.l/pi"});
    shade::check::doctest_expect_failure(r);
    // f(l,v)/f(v,l) = (n.l)/(n.v): the hard cases include n.l = 1 against n.v = 1e-4 or
    // 1e-7, a relative difference of 1 - n.v ~ 1.
    CHECK(r.worst > 0.99);
    CHECK(r.value.x != r.other.x);
    CHECK(r.message.find("f(v, l)") != std::string::npos);
    // Positivity and energy are fine for this one: the checks are independent.
    shade::check::doctest_expect(shade::check::positivity(broken_brdf<T>{flaw::not_reciprocal}, at));
}

TEST_CASE_TEMPLATE("checks are deterministic for a seed and depend on it", T, float, double) {
    const auto at = tilted_point<T>();
    const auto a = shade::check::reciprocity(broken_brdf<T>{flaw::not_reciprocal}, at, {.pairs = 500, .seed = 7});
    const auto b = shade::check::reciprocity(broken_brdf<T>{flaw::not_reciprocal}, at, {.pairs = 500, .seed = 7});
    CHECK(a.message == b.message);
    CHECK(a.failures == b.failures);
    const auto pairs7 = shade::check::hemisphere_pairs(at, 100, 7);
    const auto pairs8 = shade::check::hemisphere_pairs(at, 100, 8);
    CHECK(pairs7.back().l != pairs8.back().l);
}

TEST_CASE_TEMPLATE("hemisphere pairs are unit and strictly above the surface", T, float, double) {
    const auto at = tilted_point<T>();
    for (const auto& p : shade::check::hemisphere_pairs(at, 5000, 3)) {
        CHECK(glm::dot(p.l, at.n()) > T(0));
        CHECK(glm::dot(p.v, at.n()) > T(0));
        CHECK(std::abs(glm::length(p.l) - T(1)) < T(1e-5));
    }
}

TEST_CASE_TEMPLATE("the mixture estimator is accurate at a grazing glossy view", T, float, double) {
    // Normalised Phong lobe, exponent 200, seen at 85 degrees. Since (r_l . v) = (l . r_v),
    //   a(v) = (e+2)/(2 pi) ∫ (l . r_v)^e max(n.l, 0) dl,
    // a narrow lobe around r_v (5 degrees above the horizon) weighted by n.l ~ cos 85 deg.
    // Reference: midpoint quadrature in lobe coordinates (alpha from r_v, azimuth psi),
    // dl = sin(alpha) dalpha dpsi, 4000 x 1000 cells over alpha in [0, pi/2] (the lobe is
    // below 1e-60 beyond), computed here independently of the estimator.
    const auto at = shade::surface_point<T>::at({0, 0, 0}, {0, 0, 1});
    const double theta = 85.0 * shade::pi<double> / 180.0, e = 200;
    const glm::dvec3 r_v(-std::sin(theta), 0, std::cos(theta));
    const glm::dvec3 a1(std::cos(theta), 0, std::sin(theta)); // unit, orthogonal to r_v
    const glm::dvec3 a2(0, 1, 0);
    double reference = 0;
    const int na = 4000, np = 1000;
    const double da = shade::pi<double> / 2 / na, dp = 2 * shade::pi<double> / np;
    for (int i = 0; i < na; ++i) {
        const double alpha = (i + 0.5) * da;
        const double lobe = (e + 2) / (2 * shade::pi<double>) * std::pow(std::cos(alpha), e) * std::sin(alpha);
        for (int k = 0; k < np; ++k) {
            const double psi = (k + 0.5) * dp;
            const glm::dvec3 l = std::cos(alpha) * r_v + std::sin(alpha) * (std::cos(psi) * a1 + std::sin(psi) * a2);
            reference += lobe * std::max(l.z, 0.0) * da * dp;
        }
    }
    CHECK(reference == doctest::Approx(std::cos(theta)).epsilon(0.15)); // sanity: ~ cos 85 deg
    const shade::vec3<T> v(T(std::sin(theta)), 0, T(std::cos(theta)));
    const auto s = shade::check::directional_albedo(test_phong_lobe<T>{1, 200}, v, at, 128);
    CHECK(s.albedo.x == doctest::Approx(reference).epsilon(0.01));
    CHECK(s.standard_error.x < 0.002);
}

TEST_CASE_TEMPLATE("bad estimator settings are rejected by name", T, float, double) {
    const auto at = tilted_point<T>();
    const test_lambert<T> white{1};
    CHECK_THROWS_WITH_AS((void)shade::check::directional_albedo(white, at.n(), at, 1),
                         doctest::Contains("'strata'"), shade::invalid_parameter);
    CHECK_THROWS_WITH_AS((void)shade::check::energy_conservation(white, at, {.strata = 8, .tolerance = -1}),
                         doctest::Contains("'tolerance'"), shade::invalid_parameter);
    CHECK_THROWS_WITH_AS((void)shade::check::directional_albedo(white, at.n(), at, 8, 1, 1.0),
                         doctest::Contains("'lobe_fraction'"), shade::invalid_parameter);
    CHECK_THROWS_WITH_AS((void)shade::check::white_furnace(white, at, {.strata = 8, .max_theta_degrees = 95}),
                         doctest::Contains("'max_theta_degrees'"), shade::invalid_parameter);
}
