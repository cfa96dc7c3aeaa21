// shade::thin_film_reflectance and shade::thin_film_fresnel (Belcour, Barla 2017): the
// limits of no film and of a thick film, the spectral integral of the Airy formula, the
// range, total reflection and validation.

#include <cmath>
#include <complex>
#include <numbers>
#include <random>

#include <doctest/doctest.h>

#include <shade/brdf/cook_torrance.hpp>
#include <shade/brdf/fresnel.hpp>
#include <shade/brdf/thin_film.hpp>
#include <shade/check/doctest.hpp>
#include <shade/check/properties.hpp>
#include <shade/core/error.hpp>

#include "brdf/properties_support.hpp"
#include "brdf/support.hpp"

using namespace brdf_test;

static_assert(shade::fresnel_term<shade::thin_film_fresnel<float>, float>);
static_assert(shade::fresnel_term<shade::thin_film_fresnel<double>, double>);

namespace {

using complex = std::complex<double>;

// The s and p amplitudes of an interface from a real index n_i into a complex index n_t
// at cos_i, in the form r_s = (n_i cos_i - n_t cos_t) / (n_i cos_i + n_t cos_t),
// r_p = (n_t cos_i - n_i cos_t) / (n_t cos_i + n_i cos_t), with cos_t = sqrt(1 - (n_i sin_i /
// n_t)^2) (Born, Wolf 1999, sec. 1.5.2), the root with Im(n_t cos_t) >= 0.
struct amplitudes {
    complex s, p;
};

amplitudes fresnel_amplitudes(double n_i, complex n_t, double cos_i) {
    const double sin_i = std::sqrt(std::max(0.0, 1 - cos_i * cos_i));
    complex cos_t = std::sqrt(1.0 - (n_i * sin_i / n_t) * (n_i * sin_i / n_t));
    if ((n_t * cos_t).imag() < 0) cos_t = -cos_t;
    return {(n_i * cos_i - n_t * cos_t) / (n_i * cos_i + n_t * cos_t),
            (n_t * cos_i - n_i * cos_t) / (n_t * cos_i + n_i * cos_t)};
}

// Wyman, Sloan, Shirley 2013, "Simple Analytic Approximations to the CIE XYZ Color Matching
// Functions", JCGT 2(2), the multi-lobe fit of their sec. 2 (piecewise Gaussians).
double lobe(double lambda, double mu, double s1, double s2) {
    const double s = lambda < mu ? s1 : s2;
    return std::exp(-0.5 * (lambda - mu) * (lambda - mu) / (s * s));
}

glm::dvec3 cmf(double lambda) {
    return {1.056 * lobe(lambda, 599.8, 37.9, 31.0) + 0.362 * lobe(lambda, 442.0, 16.0, 26.7) -
                0.065 * lobe(lambda, 501.1, 20.4, 26.2),
            0.821 * lobe(lambda, 568.8, 46.9, 40.5) + 0.286 * lobe(lambda, 530.9, 16.3, 31.1),
            1.217 * lobe(lambda, 437.0, 11.8, 36.0) + 0.681 * lobe(lambda, 459.0, 26.0, 13.8)};
}

// The reference: the Airy reflectance of the film at each wavelength from 360 to 760 nm
// (every 0.25 nm), averaged over s and p, integrated against the colour matching functions
// (each normalised to integrate to 1) and taken to CIE RGB (E) with the matrix of
// Wyszecki, Stiles 1982 for the CIE 1931 primaries.
glm::dvec3 spectral_reference(double cos1, double n1, double n2, complex n3, double d_nm) {
    const double sin1 = std::sqrt(1 - cos1 * cos1);
    const double cos2 = std::sqrt(1 - (n1 * sin1 / n2) * (n1 * sin1 / n2));
    const amplitudes top = fresnel_amplitudes(n1, complex(n2), cos1);
    const amplitudes bottom = fresnel_amplitudes(n2, n3, cos2);
    glm::dvec3 xyz(0), norm(0);
    for (int i = 0; i <= 1600; ++i) {
        const double lambda = 360 + 0.25 * i;
        const complex phase = std::exp(complex(0, 2 * std::numbers::pi * 2 * n2 * d_nm * cos2 / lambda));
        const auto airy = [&](complex r12, complex r23) {
            return std::norm((r12 + r23 * phase) / (1.0 + r12 * r23 * phase));
        };
        const double r = 0.5 * (airy(top.s, bottom.s) + airy(top.p, bottom.p));
        xyz += r * cmf(lambda);
        norm += cmf(lambda);
    }
    xyz /= norm;
    return {2.3706743 * xyz.x - 0.9000405 * xyz.y - 0.4706338 * xyz.z,
            -0.5138850 * xyz.x + 1.4253036 * xyz.y + 0.0885814 * xyz.z,
            0.0052982 * xyz.x - 0.0146949 * xyz.y + 1.0093968 * xyz.z};
}

} // namespace

TEST_CASE_TEMPLATE("thin film: no film is the base's own Fresnel reflectance", T, float, double) {
    const double tol = sizeof(T) <= 4 ? 2e-6 : 1e-8;
    for (const double cos1 : {1.0, 0.8, 0.5, 0.2, 0.05}) {
        CAPTURE(cos1);
        // Glass under air: R = F_dielectric(cos, 1.5), whatever the film's index.
        const auto glass = shade::thin_film_fresnel<T>::over_dielectric(T(1.5), T(1.33), T(0));
        CHECK(double(glass.F(T(cos1)).y) == doctest::Approx(shade::F_dielectric(cos1, 1.5)).epsilon(tol).scale(1));
        // Gold-like conductor (per-channel eta, kappa) under air.
        const rgb<T> eta(T(0.18), T(0.42), T(1.37)), kappa(T(3.42), T(2.35), T(1.77));
        const auto gold = shade::thin_film_fresnel<T>::over_conductor(eta, kappa, T(1.8), T(0));
        for (int c = 0; c < 3; ++c)
            CHECK(double(gold.F(T(cos1))[c]) ==
                  doctest::Approx(shade::F_conductor(cos1, double(eta[c]), double(kappa[c]))).epsilon(tol).scale(1));
    }
}

TEST_CASE_TEMPLATE("thin film: a thick film is the incoherent sum of its two interfaces", T, float, double) {
    // 100 micrometres: the fringes are far finer than the colour matching functions resolve,
    // so every m >= 1 term vanishes and, per polarization, R = R_12 + T^2 R_23 / (1 - R_12 R_23).
    for (const double cos1 : {1.0, 0.6, 0.3}) {
        CAPTURE(cos1);
        const double n2 = 1.38, n3 = 2.0;
        const double sin2 = std::sqrt(1 - cos1 * cos1) / n2;
        const double cos2 = std::sqrt(1 - sin2 * sin2);
        const amplitudes top = fresnel_amplitudes(1.0, complex(n2), cos1), bottom = fresnel_amplitudes(n2, n3, cos2);
        const auto incoherent = [](complex r12, complex r23) {
            const double a = std::norm(r12), b = std::norm(r23);
            return a + (1 - a) * (1 - a) * b / (1 - a * b);
        };
        const double expected = 0.5 * (incoherent(top.s, bottom.s) + incoherent(top.p, bottom.p));
        const auto film = shade::thin_film_fresnel<T>::over_dielectric(T(n3), T(n2), T(1e5));
        for (int c = 0; c < 3; ++c) CHECK(double(film.F(T(cos1))[c]) == doctest::Approx(expected).epsilon(1e-5).scale(1));
    }
}

TEST_CASE("thin film: matches the spectral integral of the Airy formula (films on dielectrics and metals)") {
    // The Gaussian fit of the colour matching functions (Belcour, Barla) against the
    // spectral integral with Wyman et al.'s fit: they agree to 0.02 per channel; a wrong
    // phase of r_21 or an optical path without cos(theta_2) misses by 0.1 to 0.8 at these
    // points.
    struct point {
        double n2;
        complex n3;
        double d;
    };
    const point points[] = {{1.4, 1.5, 300},         {1.33, 1.0, 500},         {1.5, complex(0.2, 3.6), 250},
                            {1.8, 1.5, 100},         {1.3, 1.5, 800},          {1.4, complex(1.1, 6.9), 400},
                            {2.2, complex(1.5, 0), 150}, {1.45, complex(0.3, 2.0), 650}};
    for (const point& q : points)
        for (const double cos1 : {1.0, 0.7, 0.3, 0.1}) {
            CAPTURE(q.n2);
            CAPTURE(q.d);
            CAPTURE(cos1);
            const glm::dvec3 expected = spectral_reference(cos1, 1.0, q.n2, q.n3, q.d);
            const auto film = shade::thin_film_fresnel<double>::over_conductor(
                rgb<double>(q.n3.real()), rgb<double>(q.n3.imag()), q.n2, q.d);
            const rgb<double> got = film.F(cos1);
            for (int c = 0; c < 3; ++c) CHECK(std::abs(got[c] - expected[c]) < 0.02);
        }
}

TEST_CASE_TEMPLATE("thin film: reflectance in [0, 1], 1 at grazing and under total reflection at the film's top", T,
                   float, double) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(0, 1);
    for (int i = 0; i < 2000; ++i) {
        const T n2 = T(1 + 1.5 * u(rng)), d = T(2000 * u(rng)), c = T(u(rng));
        const auto film = u(rng) < 0.5 ? shade::thin_film_fresnel<T>::over_dielectric(T(1 + 2 * u(rng)), n2, d)
                                       : shade::thin_film_fresnel<T>::over_conductor(
                                             rgb<T>(T(0.1 + 2 * u(rng))), rgb<T>(T(5 * u(rng))), n2, d);
        const rgb<T> f = film.F(c);
        for (int k = 0; k < 3; ++k) {
            CHECK(std::isfinite(f[k]));
            CHECK(f[k] >= T(0));
            CHECK(f[k] <= T(1));
        }
    }
    const auto film = shade::thin_film_fresnel<T>::over_dielectric(T(1.5), T(1.3), T(400));
    CHECK(close(film.F(T(0)), rgb<T>(1), T(1e-6)));
    // Under a coat of index 1.6 a film of 1.3 reflects totally beyond sin(theta_1) = 1.3 / 1.6
    // (cos < 0.583): cos = 0.5 returns 1.
    const auto under_coat = shade::thin_film_fresnel<T>::over_dielectric(T(1.5), T(1.3), T(400), T(1.6));
    CHECK(close(under_coat.F(T(0.5)), rgb<T>(1), T(1e-6)));
    CHECK(under_coat.F(T(0.7)).x < T(0.5));
}

TEST_CASE_TEMPLATE("thin film: rejects bad parameters, naming them", T, float, double) {
    using film = shade::thin_film_fresnel<T>;
    CHECK_THROWS_WITH_AS((void)film::over_dielectric(T(0), T(1.4), T(500)), doctest::Contains("'base_ior'"),
                         shade::invalid_parameter);
    CHECK_THROWS_WITH_AS((void)film::over_dielectric(T(1.5), T(-1), T(500)), doctest::Contains("'film_ior'"),
                         shade::invalid_parameter);
    CHECK_THROWS_WITH_AS((void)film::over_dielectric(T(1.5), T(1.4), T(-1)), doctest::Contains("'thickness_nm'"),
                         shade::invalid_parameter);
    CHECK_THROWS_WITH_AS((void)film::over_dielectric(T(1.5), T(1.4), T(500), T(std::nan(""))),
                         doctest::Contains("'outside_ior'"), shade::invalid_parameter);
    CHECK_THROWS_WITH_AS((void)film::over_conductor(rgb<T>(T(-1)), rgb<T>(1), T(1.4), T(500)), doctest::Contains("'eta'"),
                         shade::invalid_parameter);
    CHECK_THROWS_WITH_AS((void)film::over_conductor(rgb<T>(1), rgb<T>(T(-1)), T(1.4), T(500)), doctest::Contains("'kappa'"),
                         shade::invalid_parameter);
}

TEST_CASE_TEMPLATE("thin film: an iridescent GGX metal passes every property check", T, float, double) {
    using model = shade::cook_torrance<shade::ggx<T>, shade::thin_film_fresnel<T>, shade::smith_height_correlated<T>>;
    const auto film =
        shade::thin_film_fresnel<T>::over_conductor(rgb<T>(T(1.66), T(0.88), T(0.52)), rgb<T>(T(9.2), T(6.3), T(4.8)),
                                                    T(1.4), T(450));
    expect_every_property(model(shade::ggx<T>(T(0.3)), film), "GGX alpha 0.3, 450 nm film on aluminium", 36);
}
