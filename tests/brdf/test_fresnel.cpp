#include <cmath>
#include <complex>
#include <limits>
#include <utility>

#include <doctest/doctest.h>

#include <shade/brdf/fresnel.hpp>

#include "brdf/support.hpp"

using namespace brdf_test;

static_assert(shade::fresnel_term<shade::schlick<float>, float>);
static_assert(shade::fresnel_term<shade::dielectric_fresnel<double>, double>);

namespace {

template <class T>
constexpr T tol = sizeof(T) <= 4 ? T(1e-6) : T(1e-14);

} // namespace

TEST_CASE_TEMPLATE("F_schlick: f0 at normal incidence, 1 at grazing, the fifth power between", T, float, double) {
    const rgb<T> f0(T(0.04), T(0.5), T(0.9));
    CHECK(close(shade::F_schlick(f0, T(1)), f0, tol<T>));
    CHECK(close(shade::F_schlick(f0, T(0)), rgb<T>(1), tol<T>));
    // cos = 1/2: (1 - 1/2)^5 = 1/32, F = f0 + (1 - f0)/32.
    CHECK(close(shade::F_schlick(f0, T(0.5)), f0 + (rgb<T>(1) - f0) / T(32), tol<T>));
    // A cosine a hair above 1 is clamped: F stays in [f0, 1]. A hair below 0 is a grazing
    // cosine from the other side: F(1e-7) = f0 + (1 - f0)(1 - 5e-7) to first order, 1 to
    // within 5e-7.
    CHECK(close(shade::F_schlick(f0, T(1.0000001)), f0, tol<T>));
    CHECK(close(shade::F_schlick(f0, T(-1e-7)), rgb<T>(1), T(1e-6)));
    const shade::schlick<T> term(f0);
    CHECK(close(term.F(T(0.5)), shade::F_schlick(f0, T(0.5)), tol<T>));
}

TEST_CASE_TEMPLATE("F_dielectric: glass (eta = 1.5) at normal incidence is 0.04", T, float, double) {
    // ((1.5 - 1)/(1.5 + 1))^2 = 0.2^2 = 0.04.
    CHECK(close(shade::F_dielectric(T(1), T(1.5)), T(0.04), T(1e-5)));
    CHECK(close(shade::f0_from_ior(T(1.5)), T(0.04), tol<T>));
    CHECK(close(shade::schlick<T>::from_ior(T(1.5)).f0(), rgb<T>(T(0.04)), tol<T>));
    // Grazing incidence reflects everything.
    CHECK(close(shade::F_dielectric(T(0), T(1.5)), T(1), tol<T>));
    // eta = 1: no interface, nothing reflected, including the 0/0 point c = 0.
    CHECK(shade::F_dielectric(T(0.3), T(1)) == doctest::Approx(0).epsilon(1e-6));
    CHECK(shade::F_dielectric(T(0), T(1)) == T(0));
}

TEST_CASE_TEMPLATE("F_dielectric: Brewster's angle reflects only the s-polarized half", T, float, double) {
    // At Brewster's angle tan(theta_B) = eta, r_p = 0 and theta_i + theta_t = 90 deg, so
    // r_s = (cos_i - eta cos_t)/(cos_i + eta cos_t) with cos_i = 1/sqrt(1 + eta^2),
    // cos_t = eta/sqrt(1 + eta^2): r_s = (1 - eta^2)/(1 + eta^2), F = r_s^2 / 2.
    // eta = 1.5: r_s = -1.25/3.25, F = 0.0739644970...
    const T eta = T(1.5);
    const T cos_b = T(1) / std::sqrt(T(1) + eta * eta);
    CHECK(close(shade::F_dielectric(cos_b, eta), T(0.5) * shade::sqr(T(1.25) / T(3.25)), T(1e-5)));
}

TEST_CASE_TEMPLATE("F_dielectric: total internal reflection from the dense side", T, float, double) {
    // eta = 1/1.5 (glass to air): the critical angle has sin = 1/1.5, cos = sqrt(5)/3 = 0.745.
    // Any cos below it is totally reflected: F = 1. Just above it F < 1, and at normal
    // incidence it is again 0.04 (the reflectance is symmetric in eta <-> 1/eta there).
    const T eta = T(1) / T(1.5);
    CHECK(shade::F_dielectric(T(0.5), eta) == T(1));
    CHECK(shade::F_dielectric(T(0), eta) == T(1));
    CHECK(shade::F_dielectric(T(0.8), eta) < T(1));
    CHECK(close(shade::F_dielectric(T(1), eta), T(0.04), T(1e-5)));
    // In range everywhere, with no NaN.
    for (int i = 0; i <= 1000; ++i) {
        const T c = T(i) / T(1000);
        for (const T e : {T(1e-3), eta, T(1), T(1.5), T(1e3)}) {
            const T f = shade::F_dielectric(c, e);
            CHECK((f >= T(0) && f <= T(1)));
        }
    }
}

TEST_CASE_TEMPLATE("F_dielectric: a tiny eta at normal incidence is 1, not NaN (regression, found by fuzzing)",
                   T, float, double) {
    // eta = 1e-20 passes the constructor (finite, > 0), but eta^2 - 1 + c^2 rounds to 0
    // at c = 1, so g = 0 and the second factor was (c(g + c) - 1)/(c(g - c) + 1) = 0/0.
    // Exact value: F(1) = f0_from_ior(eta) = ((eta - 1)/(eta + 1))^2 = (1 - 2 eta + ...)
    // = 1 to working precision; also the limit of the formula as g -> 0 at c = 1
    // (a -> -1, b -> 1, F = a^2 (1 + b^2)/2 = 1).
    const T eta = T(1e-20);
    const T F = shade::F_dielectric(T(1), eta);
    CHECK(F == doctest::Approx(1.0).epsilon(1e-6));
    CHECK(F <= T(1));
    // The BRDF built on it stays finite at l = v = n (v·h = 1).
    const shade::dielectric_fresnel<T> fresnel(eta);
    CHECK(fresnel.F(T(1)).x == doctest::Approx(1.0).epsilon(1e-6));
}

TEST_CASE_TEMPLATE("F_dielectric: a huge eta reflects everything, not NaN (regression, found by fuzzing)",
                   T, float, double) {
    // eta = the largest finite value passes the constructor, but eta^2 overflows, g = inf
    // and (g - c)/(g + c) was inf/inf = NaN. As eta -> inf, a = (g - c)/(g + c) -> 1 and
    // b = (c(g + c) - 1)/(c(g - c) + 1) -> 1 for c > 0 and -1 for c = 0, so
    // F = a^2 (1 + b^2)/2 -> 1 at every angle.
    const T eta = std::numeric_limits<T>::max();
    for (const T c : {T(0), T(0.5), T(1)}) {
        CAPTURE(c);
        CHECK(shade::F_dielectric(c, eta) == T(1));
    }
}

TEST_CASE_TEMPLATE("fresnel terms: invalid parameters throw naming the parameter", T, float, double) {
    check_throws_naming([] { (void)shade::schlick<T>(rgb<T>(T(1.1), 0, 0)); }, "f0");
    check_throws_naming([] { (void)shade::schlick<T>(rgb<T>(T(-0.1))); }, "f0");
    check_throws_naming([] { (void)shade::schlick<T>::from_ior(T(0)); }, "eta");
    check_throws_naming([] { (void)shade::dielectric_fresnel<T>(T(-1.5)); }, "eta");
    check_throws_naming([] { (void)shade::dielectric_fresnel<T>(std::numeric_limits<T>::quiet_NaN()); }, "eta");
    CHECK_NOTHROW((void)shade::dielectric_fresnel<T>(shade::unchecked, T(-1)));
}

// ---------------------------------------------------------------------------------------
// Conductor Fresnel.

namespace {

// The unpolarized conductor reflectance computed directly in complex long double
// arithmetic (Born & Wolf: r_s = (c - eta_c cos_t)/(c + eta_c cos_t),
// r_p = (eta_c c - cos_t)/(eta_c c + cos_t), cos_t = sqrt(1 - s^2/eta_c^2)): an
// independent reference for the real-arithmetic form of F_conductor.
long double conductor_reference(long double c, long double eta, long double kappa) {
    const std::complex<long double> n(eta, kappa);
    const long double s2 = 1.0L - c * c;
    const std::complex<long double> cos_t = std::sqrt(1.0L - s2 / (n * n));
    const std::complex<long double> rs = (c - n * cos_t) / (c + n * cos_t);
    const std::complex<long double> rp = (n * c - cos_t) / (n * c + cos_t);
    return (std::norm(rs) + std::norm(rp)) / 2.0L;
}

} // namespace

TEST_CASE_TEMPLATE("F_conductor: normal incidence ((eta - 1)^2 + kappa^2) / ((eta + 1)^2 + kappa^2)", T, float, double) {
    // At c = 1, s = 0: Snell gives cos_t = 1, so r_s = (1 - eta_c)/(1 + eta_c) and
    // r_p = (eta_c - 1)/(eta_c + 1); |1 - eta_c|^2 = (1 - eta)^2 + kappa^2 and
    // |1 + eta_c|^2 = (1 + eta)^2 + kappa^2, the same for both polarizations.
    for (const auto& parameters : {std::pair{T(0.14), T(3.697)}, std::pair{T(1.5), T(0)}, std::pair{T(0.05), T(4.483)},
                                     std::pair{T(2), T(1)}, std::pair{T(1e-4), T(1e4)}, std::pair{T(1e4), T(0)}}) {
        const auto eta = parameters.first;
        const auto kappa = parameters.second;
        CAPTURE(eta);
        CAPTURE(kappa);
        const T expected = ((eta - 1) * (eta - 1) + kappa * kappa) / ((eta + 1) * (eta + 1) + kappa * kappa);
        CHECK(close(shade::F_conductor(T(1), eta, kappa), expected, T(10) * tol<T>));
    }
    // Gold's red channel (0.14 + 3.697i): (0.86^2 + 3.697^2)/(1.14^2 + 3.697^2) =
    // 14.407409/14.967409 = 0.96258537...
    CHECK(close(shade::F_conductor(T(1), T(0.14), T(3.697)), T(0.9625853746630428), T(10) * tol<T>));
}

TEST_CASE_TEMPLATE("F_conductor: F -> 1 at grazing", T, float, double) {
    // c = 0: r_s = -w/w = -1 and r_p = -w/w = -1.
    for (const auto& parameters : {std::pair{T(0.14), T(3.697)}, std::pair{T(1.5), T(0)}, std::pair{T(1.02), T(2.577)}}) {
        const auto eta = parameters.first;
        const auto kappa = parameters.second;
        CHECK(close(shade::F_conductor(T(0), eta, kappa), T(1), T(10) * tol<T>));
        T previous = shade::F_conductor(T(0.05), eta, kappa);
        for (const T c : {T(1e-2), T(1e-3), T(1e-5)}) {
            const T f = shade::F_conductor(c, eta, kappa);
            CHECK(f >= previous); // increasing toward grazing below 0.05
            previous = f;
        }
        CHECK(previous > T(0.999));
    }
}

TEST_CASE_TEMPLATE("F_conductor: kappa = 0 is the dielectric Fresnel", T, float, double) {
    for (const T eta : {T(1.5), T(1.33), T(2.4), T(0.67), T(1)}) {
        for (int i = 0; i <= 50; ++i) {
            const T c = T(i) / T(50);
            CAPTURE(eta);
            CAPTURE(c);
            const T dielectric = shade::F_dielectric(c, eta);
            CHECK(std::abs(shade::F_conductor(c, eta, T(0)) - dielectric) <= T(100) * tol<T> * std::max(dielectric, T(1e-3)));
        }
    }
}

TEST_CASE_TEMPLATE("F_conductor: agrees with a complex long double reference (1e-4 float, 1e-9 double)", T, float, double) {
    const T rel = sizeof(T) <= 4 ? T(1e-4) : T(1e-9);
    for (const auto& parameters : {std::pair{T(0.14), T(3.697)}, std::pair{T(0.05), T(4.483)}, std::pair{T(1.38), T(1.914)},
                                     std::pair{T(1.4665), T(7.5603)}, std::pair{T(3), T(0.1)}, std::pair{T(0.5), T(0.01)},
                                     std::pair{T(1e-4), T(2)}, std::pair{T(100), T(300)}}) {
        const auto eta = parameters.first;
        const auto kappa = parameters.second;
        for (const T c : {T(1), T(0.9), T(0.5), T(0.2), T(0.05), T(1e-3)}) {
            CAPTURE(eta);
            CAPTURE(kappa);
            CAPTURE(c);
            const long double reference = conductor_reference(c, eta, kappa);
            const T f = shade::F_conductor(c, eta, kappa);
            CHECK(std::abs(f - reference) <= rel * reference);
            CHECK(f >= T(0));
            CHECK(f <= T(1));
        }
    }
}

TEST_CASE_TEMPLATE("conductor_fresnel: per channel, f0, validation", T, float, double) {
    static_assert(shade::fresnel_term<shade::conductor_fresnel<T>, T>);
    const shade::conductor_fresnel<T> f(rgb<T>(T(0.14), T(1.5), T(2)), rgb<T>(T(3.697), T(0), T(1)));
    const rgb<T> at_60 = f.F(T(0.5));
    CHECK(at_60.x == shade::F_conductor(T(0.5), T(0.14), T(3.697)));
    CHECK(at_60.y == shade::F_conductor(T(0.5), T(1.5), T(0)));
    CHECK(at_60.z == shade::F_conductor(T(0.5), T(2), T(1)));
    // f0 = F(1): 0.96258537..., 0.04 (glass), (1 + 1)/(9 + 1) = 0.2.
    CHECK(close(f.f0(), rgb<T>(T(0.9625853746630428), T(0.04), T(0.2)), T(10) * tol<T>));
    check_throws_naming([] { (void)shade::conductor_fresnel<T>(rgb<T>(T(0)), rgb<T>(T(1))); }, "eta");
    check_throws_naming([] { (void)shade::conductor_fresnel<T>(rgb<T>(T(1), T(2e4), T(1)), rgb<T>(T(1))); }, "eta");
    check_throws_naming([] { (void)shade::conductor_fresnel<T>(rgb<T>(T(1)), rgb<T>(T(1), T(-1), T(1))); }, "kappa");
    check_throws_naming([] { (void)shade::conductor_fresnel<T>(rgb<T>(T(1)), rgb<T>(std::numeric_limits<T>::quiet_NaN())); }, "kappa");
}

TEST_CASE_TEMPLATE("F_dielectric_two_sided: from outside as F_dielectric, from inside with 1/eta", T, float, double) {
    // Outside (n·w > 0): the relative index is eta; inside (n·w < 0): 1/eta, with total
    // internal reflection beyond sin(theta) = 1/eta (eta = 1.5: cos < sqrt(5)/3 = 0.745).
    const T eta = T(1.5);
    for (int i = 0; i <= 100; ++i) {
        const T c = T(i) / T(100);
        CAPTURE(c);
        CHECK(shade::F_dielectric_two_sided(c, eta) == shade::F_dielectric(c, eta));
        CHECK(shade::F_dielectric_two_sided(-c, eta) == shade::F_dielectric(c, T(1) / eta));
    }
    CHECK(shade::F_dielectric_two_sided(T(-0.7), eta) == T(1));
    CHECK(shade::F_dielectric_two_sided(T(-0.8), eta) < T(1));
    // Normal incidence from either side: ((eta - 1)/(eta + 1))^2 = 0.04.
    CHECK(close(shade::F_dielectric_two_sided(T(-1), eta), T(0.04), T(1e-5)));
    CHECK(close(shade::F_dielectric_two_sided(T(1), eta), T(0.04), T(1e-5)));
    // Grazing from either side reflects everything.
    CHECK(shade::F_dielectric_two_sided(T(-0.0), eta) == T(1));
    CHECK(close(shade::F_dielectric_two_sided(T(1e-9), eta), T(1), T(1e-6)));
}

TEST_CASE_TEMPLATE("Fresnel terms are two-sided: |cos| for Schlick and conductors, 1/eta for a dielectric seen from behind", T, float, double) {
    const rgb<T> f0(T(0.04), T(0.5), T(0.9));
    const shade::conductor_fresnel<T> gold_like(rgb<T>(T(0.18), T(0.42), T(1.37)), rgb<T>(T(3.42), T(2.35), T(1.77)));
    for (int i = 0; i <= 100; ++i) {
        const T c = T(i) / T(100);
        CAPTURE(c);
        // An opaque reflector depends on the angle only: F(-c) = F(c) to the last bit.
        CHECK(shade::F_schlick(f0, -c) == shade::F_schlick(f0, c));
        CHECK(shade::F_conductor(-c, T(0.2), T(3.9)) == shade::F_conductor(c, T(0.2), T(3.9)));
        CHECK(gold_like.F(-c) == gold_like.F(c));
        // A dielectric seen from the side opposite its normal: the relative index inverted.
        CHECK(shade::F_dielectric(-c, T(1.5)) == shade::F_dielectric(c, T(1) / T(1.5)));
        CHECK(shade::F_dielectric(-c, T(1) / T(1.33)) == shade::F_dielectric(c, T(1) / (T(1) / T(1.33))));
        CHECK(shade::dielectric_fresnel<T>(T(1.5)).F(-c) == rgb<T>(shade::F_dielectric(c, T(1) / T(1.5))));
    }
    // By hand, eta = 1.5 seen from inside (relative index 1/1.5): normal incidence reflects
    // ((1 - 1.5)/(1 + 1.5))^2 = 0.04 as from outside; beyond the critical angle, sin > 1/1.5
    // (cos < sqrt(5)/3 = 0.745), everything: cos 0.7 is totally reflected, cos 0.8 is not.
    CHECK(close(shade::F_dielectric(T(-1), T(1.5)), T(0.04), T(1e-5)));
    CHECK(shade::F_dielectric(T(-0.7), T(1.5)) == T(1));
    CHECK(shade::F_dielectric(T(-0.8), T(1.5)) < T(1));
    // From outside at the same cosines there is no total reflection.
    CHECK(shade::F_dielectric(T(0.7), T(1.5)) < T(0.1));
}
