#include <algorithm>
#include <cmath>
#include <numbers>

#include <doctest/doctest.h>

#include <shade/brdf/lambert.hpp>
#include <shade/brdf/oren_nayar.hpp>

#include "brdf/support.hpp"
#include "brdf/sampling.hpp"

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
    // Same function, two evaluations. The trig path's cos(phi) comes from normalised
    // tangent-plane projections, which lose accuracy near the normal (short projections),
    // and the trig-free numerator l.v - (n.l)(n.v) cancels near grazing; pairs within 1e-3
    // of either are compared with a looser, absolute tolerance relative to rho/pi instead
    // (the B term there is tiny, or the value is dominated by the epsilon floor of cos(beta)).
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
                // float: each factor adds an ulp or so, amplified by up to ~1/sin(theta) ~ 20
                // near the interior boundary: a few hundred ulps.
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

static_assert(shade::sampled_brdf<shade::oren_nayar<float>>);
static_assert(shade::sampled_brdf<shade::oren_nayar_trig<double>>);
static_assert(shade::sampled_brdf<shade::oren_nayar<double, shade::oren_nayar_evaluation::trig_free,
                                                    shade::oren_nayar_form::course>>);

TEST_CASE_TEMPLATE("oren-nayar: sample (cosine) and pdf agree, integrate to 1 and pass chi-square", T, float, double) {
    for (const T sigma : {T(0), T(0.5), T(1.5)}) {
        CAPTURE(sigma);
        check_sampled_model(shade::oren_nayar<T>(rgb<T>(T(0.7), T(0.5), T(0.3)), sigma), flat<T>());
        check_sampled_model(shade::oren_nayar_trig<T>(rgb<T>(T(0.7)), sigma), tilted<T>());
    }
    // pdf = n.l / pi: at 60 deg 1/(2 pi), whatever v (above).
    const auto at = flat<T>();
    const shade::oren_nayar<T> model(rgb<T>(T(0.5)), T(0.4));
    CHECK(close(model.pdf(direction(at, shade::pi<T> / 3, T(0)), direction(at, T(1.2), T(2)), at),
                T(0.5) / shade::pi<T>, T(1e-6)));
    CHECK(model.pdf(direction(at, shade::pi<T> / 3, T(0)), -at.n(), at) == T(0));
}

namespace {

// The paper's formula (eq. 30) in long double, with the angles formed by acos: the
// reference the float and double evaluations are compared with. l and v are the exact
// values of the T-valued directions; n = +z.
template <class T>
long double oren_nayar_reference(const vec3<T>& l, const vec3<T>& v, long double sigma, long double a_constant) {
    const long double lx = l.x, ly = l.y, lz = l.z, vx = v.x, vy = v.y, vz = v.z;
    const long double theta_l = std::acos(lz), theta_v = std::acos(vz);
    const long double alpha = std::max(theta_l, theta_v), beta = std::min(theta_l, theta_v);
    const long double cos_phi = (lx * vx + ly * vy) / (std::hypot(lx, ly) * std::hypot(vx, vy));
    const long double s2 = sigma * sigma;
    const long double a = 1 - 0.5L * s2 / (s2 + a_constant), b = 0.45L * s2 / (s2 + 0.09L);
    return (a + b * std::max(cos_phi, 0.0L) * std::sin(alpha) * std::tan(beta)) / std::numbers::pi_v<long double>;
}

} // namespace

TEST_CASE_TEMPLATE("oren-nayar: both evaluations within 1e-4 (float) / 1e-9 (double) of a long double reference, grazing included", T, float, double) {
    // Where the formula is well conditioned: cos(phi) away from 0 (azimuths 0.4 rad apart),
    // cosines from 1e-4 (grazing) to 0.9. The reference uses acos in long double, whose
    // round trip costs ~1e-19 / 1e-4 relative: far below the tolerances.
    const auto at = flat<T>();
    const T tol = sizeof(T) <= 4 ? T(1e-4) : T(1e-9);
    const T sigma = T(0.5);
    const shade::oren_nayar<T> on(rgb<T>(1), sigma);
    const shade::oren_nayar_trig<T> ont(rgb<T>(1), sigma);
    const auto at_cos = [](T c, T phi) {
        const T s = std::sqrt((1 - c) * (1 + c));
        return vec3<T>(s * std::cos(phi), s * std::sin(phi), c);
    };
    for (const T c_l : {T(1e-4), T(1e-3), T(0.1), T(0.5), T(0.9)}) {
        for (const T c_v : {T(1e-4), T(2e-4), T(0.3), T(0.9)}) {
            const vec3<T> l = at_cos(c_l, T(0.2)), v = at_cos(c_v, T(0.6));
            CAPTURE(c_l);
            CAPTURE(c_v);
            const long double ref = oren_nayar_reference(l, v, sigma, 0.33L);
            CHECK(std::abs(ont.f(l, v, at).x - ref) <= tol * ref);
            CHECK(std::abs(on.f(l, v, at).x - ref) <= tol * ref);
        }
    }
}

TEST_CASE_TEMPLATE("oren-nayar: the course form's A uses 0.57, the default eq. 30's 0.33", T, float, double) {
    // sigma = 0.5: default A = 1 - 0.5 * 0.25/0.58 = 0.78448276; course A = 1 - 0.5 * 0.25/0.82
    // = 0.84756098; B = 0.45 * 0.25/0.34 = 0.33088235 in both. At l = v = n the angular term
    // is 0, so f = rho A / pi.
    using course = shade::oren_nayar<T, shade::oren_nayar_evaluation::trig_free, shade::oren_nayar_form::course>;
    using course_trig = shade::oren_nayar<T, shade::oren_nayar_evaluation::trig, shade::oren_nayar_form::course>;
    const auto at = flat<T>();
    const shade::oren_nayar<T> paper(rgb<T>(1), T(0.5));
    const course slides(rgb<T>(1), T(0.5));
    CHECK(close(paper.a(), T(0.78448276), T(1e-6)));
    CHECK(close(slides.a(), T(0.84756098), T(1e-6)));
    CHECK(close(slides.b(), paper.b(), T(1e-7)));
    CHECK(close(slides.f(at.n(), at.n(), at).x, T(0.84756098) / shade::pi<T>, T(1e-6)));
    CHECK(close(course_trig(rgb<T>(1), T(0.5)).f(at.n(), at.n(), at).x, T(0.84756098) / shade::pi<T>, T(1e-6)));
    // The forms differ only in A: against the long double reference with 0.57 at a grazing pair.
    const vec3<T> l = glm::normalize(vec3<T>(1, T(0.2), T(0.01))), v = glm::normalize(vec3<T>(1, T(-0.1), T(0.02)));
    const long double ref = oren_nayar_reference(l, v, 0.5L, 0.57L);
    CHECK(std::abs(slides.f(l, v, at).x - ref) <= (sizeof(T) <= 4 ? 1e-4 : 1e-9) * ref);
}
