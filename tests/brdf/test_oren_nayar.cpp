#include <cmath>

#include <doctest/doctest.h>

#include <shade/brdf/lambert.hpp>
#include <shade/brdf/oren_nayar.hpp>

#include "brdf/support.hpp"

using namespace brdf_test;

static_assert(shade::brdf<shade::oren_nayar<float>>);
static_assert(shade::brdf<shade::oren_nayar_trig<double>>);

namespace {

template <class T>
constexpr T tol = sizeof(T) <= 4 ? T(1e-5) : T(1e-12);

} // namespace

TEST_CASE_TEMPLATE("oren-nayar: sigma = 0 is Lambert", T, float, double) {
    // A = 1 - 0 = 1, B = 0: f = rho/pi for every pair.
    const rgb<T> rho(T(0.7), T(0.5), T(0.2));
    const shade::oren_nayar<T> on(rho, T(0));
    const shade::oren_nayar_trig<T> ont(rho, T(0));
    const shade::lambert<T> lambert(rho);
    CHECK(on.a() == T(1));
    CHECK(on.b() == T(0));
    const auto at = tilted<T>();
    for (const auto& p : random_pairs(at, 500)) {
        CHECK(close(on.f(p.l, p.v, at), lambert.f(p.l, p.v, at), tol<T>));
        CHECK(close(ont.f(p.l, p.v, at), lambert.f(p.l, p.v, at), tol<T>));
    }
}

TEST_CASE_TEMPLATE("oren-nayar: hand values", T, float, double) {
    // sigma = 0.5: sigma^2 = 0.25, A = 1 - 0.125/0.58 = 0.7844827586, B = 0.1125/0.34 =
    // 0.3308823529.
    const T a = T(1) - T(0.125) / T(0.58);
    const T b = T(0.1125) / T(0.34);
    const rgb<T> rho(T(0.8));
    const shade::oren_nayar<T> on(rho, T(0.5));
    const shade::oren_nayar_trig<T> ont(rho, T(0.5));
    CHECK(close(on.a(), a, tol<T>));
    CHECK(close(on.b(), b, tol<T>));
    for (const auto& at : {flat<T>(), tilted<T>()}) {
        const T third = shade::pi<T> / 3, sixth = shade::pi<T> / 6;
        // l = n: theta_l = 0 = beta, tan(beta) = 0: f = rho A / pi (no NaN from the
        // undefined azimuth of l).
        const auto v = direction(at, T(1), T(2));
        CHECK(close(on.f(at.n(), v, at), rho * (a / shade::pi<T>), tol<T>));
        CHECK(close(ont.f(at.n(), v, at), rho * (a / shade::pi<T>), tol<T>));
        // l = v at 60 deg: alpha = beta = 60 deg, cos(phi) = 1: sin 60 tan 60 = 3/2.
        const auto l60 = direction(at, third, T(0.4));
        CHECK(close(on.f(l60, l60, at), rho * ((a + T(1.5) * b) / shade::pi<T>), tol<T>));
        CHECK(close(ont.f(l60, l60, at), rho * ((a + T(1.5) * b) / shade::pi<T>), tol<T>));
        // l at 30 deg, v at 60 deg, same azimuth: alpha = 60, beta = 30:
        // sin 60 tan 30 = (sqrt3/2)(1/sqrt3) = 1/2.
        const auto l30 = direction(at, sixth, T(0.4));
        CHECK(close(on.f(l30, l60, at), rho * ((a + T(0.5) * b) / shade::pi<T>), tol<T>));
        CHECK(close(ont.f(l30, l60, at), rho * ((a + T(0.5) * b) / shade::pi<T>), tol<T>));
        // Opposite azimuths: cos(phi) = -1, clamped to 0: f = rho A / pi.
        const auto v_opposite = direction(at, third, T(0.4) + shade::pi<T>);
        CHECK(close(on.f(l30, v_opposite, at), rho * (a / shade::pi<T>), tol<T>));
        CHECK(close(ont.f(l30, v_opposite, at), rho * (a / shade::pi<T>), tol<T>));
    }
}

TEST_CASE_TEMPLATE("oren-nayar: the trig-free and trig evaluations agree", T, float, double) {
    // Same function, two evaluations. The trig path computes theta = acos(n.w), which is
    // ill-conditioned near the normal and near grazing; pairs within 1e-3 of either are
    // compared with a looser, absolute tolerance relative to rho/pi instead (the B term
    // there is tiny, or the value is dominated by the epsilon floor of cos(beta)).
    const auto at = tilted<T>();
    const rgb<T> rho(T(0.9), T(0.6), T(0.3));
    for (const T sigma : {T(0.1), T(0.5), T(1.5)}) {
        const shade::oren_nayar<T> on(rho, sigma);
        const shade::oren_nayar_trig<T> ont(rho, sigma);
        for (const auto& p : random_pairs(at, 5000, 3)) {
            const T n_dot_l = glm::dot(at.n(), p.l), n_dot_v = glm::dot(at.n(), p.v);
            const rgb<T> x = on.f(p.l, p.v, at), y = ont.f(p.l, p.v, at);
            CAPTURE(n_dot_l);
            CAPTURE(n_dot_v);
            const bool interior = n_dot_l > T(1e-3) && n_dot_v > T(1e-3) && n_dot_l < T(0.999) && n_dot_v < T(0.999);
            if (interior) {
                // float: acos/sin/tan each add an ulp or so, amplified by up to ~1/sin(theta)
                // ~ 20 near the interior boundary: a few hundred ulps.
                CHECK(close(x, y, sizeof(T) <= 4 ? T(5e-5) : T(1e-11)));
            } else {
                CHECK(glm::length(x - y) <= (sizeof(T) <= 4 ? T(2e-3) : T(1e-6)) * glm::length(x));
            }
        }
    }
}

TEST_CASE_TEMPLATE("oren-nayar: reciprocal", T, float, double) {
    const auto at = tilted<T>();
    const shade::oren_nayar<T> on(rgb<T>(T(0.5)), T(0.4));
    for (const auto& p : random_pairs(at, 1000)) CHECK(on.f(p.l, p.v, at) == on.f(p.v, p.l, at));
}

TEST_CASE_TEMPLATE("oren-nayar: zero below, finite and non-negative for degenerate pairs", T, float, double) {
    for (const auto& at : {flat<T>(), tilted<T>()}) {
        for (const T sigma : {T(0), T(0.3), T(1), T(1e6)}) {
            CAPTURE(sigma);
            const shade::oren_nayar<T> a(rgb<T>(T(0.8)), sigma);
            const shade::oren_nayar_trig<T> b(rgb<T>(T(0.8)), sigma);
            check_zero_below(a, at);
            check_zero_below(b, at);
            check_finite_non_negative(a, at);
            check_finite_non_negative(b, at);
        }
    }
}

TEST_CASE_TEMPLATE("oren-nayar: invalid parameters throw naming the parameter", T, float, double) {
    check_throws_naming([] { (void)shade::oren_nayar<T>(rgb<T>(-1), T(0.3)); }, "rho");
    check_throws_naming([] { (void)shade::oren_nayar<T>(rgb<T>(1), T(-0.3)); }, "sigma");
    check_throws_naming([] { (void)shade::oren_nayar<T>(rgb<T>(1), std::numeric_limits<T>::quiet_NaN()); }, "sigma");
    check_throws_naming([] { (void)shade::oren_nayar<T>(rgb<T>(std::numeric_limits<T>::max()), T(0.3)); }, "rho");
    CHECK_NOTHROW((void)shade::oren_nayar<T>(shade::unchecked, rgb<T>(-1), T(-1)));
}
