#include <cmath>
#include <limits>
#include <optional>

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/bsdf/smooth_dielectric.hpp>

#include "bsdf/support.hpp"

using namespace bsdf_test;
using brdf_test::close;
using shade::transport_mode;

namespace {

/// The Fresnel reflectance from the angle form of the Fresnel equations (Born, Wolf 1999,
/// "Principles of Optics", 7th ed., sec. 1.5.2): with Snell's law
/// sin(theta_t) = sin(theta_i) / eta (eta = eta_t / eta_i),
///     r_s = -sin(theta_i - theta_t) / sin(theta_i + theta_t)
///     r_p =  tan(theta_i - theta_t) / tan(theta_i + theta_t)
/// and R = (r_s^2 + r_p^2) / 2; 1 beyond the critical angle. An independent route to the
/// value F_dielectric computes from g = sqrt(eta^2 - 1 + c^2). theta_i > 0 (at 0 both
/// ratios are 0/0; the limit is ((eta - 1)/(eta + 1))^2).
double fresnel_by_angles(double theta_i, double eta) {
    const double sin_t = std::sin(theta_i) / eta;
    if (sin_t >= 1) return 1;
    const double theta_t = std::asin(sin_t);
    const double rs = -std::sin(theta_i - theta_t) / std::sin(theta_i + theta_t);
    const double rp = std::tan(theta_i - theta_t) / std::tan(theta_i + theta_t);
    return 0.5 * (rs * rs + rp * rp);
}

constexpr double etas[] = {1.33, 1.5, 2.4};

} // namespace

static_assert(shade::bsdf<shade::smooth_dielectric<float>>);
static_assert(shade::bsdf_sampler<shade::smooth_dielectric<double>>);
static_assert(shade::sampled_bsdf<shade::smooth_dielectric<float>>);
static_assert(!shade::sampled_brdf<shade::smooth_dielectric<double>>);

TEST_CASE_TEMPLATE("smooth_dielectric: the sampled reflectance is the exact Fresnel reflectance", T, float, double) {
    // Known values at normal incidence, R = ((eta - 1)/(eta + 1))^2:
    //   eta = 1.33: (0.33/2.33)^2 = 0.0200593...; 1.5: 0.2^2 = 0.04; 2.4: (1.4/3.4)^2 = 0.1695501...
    // and the same from inside (eta -> 1/eta leaves it unchanged).
    const double normal[] = {0.0200593122, 0.04, 0.1695501730};
    const auto at = brdf_test::tilted<T>();
    const int n = 20000; // stratified uc: the fraction of reflections is R to within 1/n
    for (int k = 0; k < 3; ++k) {
        const double eta = etas[k];
        CAPTURE(eta);
        const shade::smooth_dielectric<T> glass{T(eta)};
        for (const double deg : {0.0, 30.0, 60.0, 85.0}) {
            CAPTURE(deg);
            const double theta = deg * shade::pi<double> / 180;
            const double R_outside = deg == 0 ? normal[k] : fresnel_by_angles(theta, eta);
            const auto out = sample_lobes(glass, view_deg(at, deg), at, transport_mode::radiance, n);
            CHECK(out.missing == 0);
            CHECK(std::abs(double(out.reflected) - R_outside) <= 1.0 / n + 1e-5);
            // A reflection's weight is 1: the mean reflected throughput is also R.
            CHECK(std::abs(double(out.reflected_weight) - R_outside) <= 1.0 / n + 1e-5);
            // From inside at the angle of the refracted ray the reflectance is the same
            // (Fresnel's equations are symmetric in the two sides).
            const double theta_t = std::asin(std::sin(theta) / eta);
            const auto in = sample_lobes(glass, view_deg(at, 180 - theta_t * 180 / shade::pi<double>), at,
                                         transport_mode::radiance, n);
            CHECK(in.missing == 0);
            CHECK(std::abs(double(in.reflected) - R_outside) <= 1.0 / n + 1e-4);
        }
    }
}

TEST_CASE_TEMPLATE("smooth_dielectric: total internal reflection above the critical angle from inside", T, float, double) {
    const auto at = brdf_test::tilted<T>();
    for (const double eta : etas) {
        CAPTURE(eta);
        const shade::smooth_dielectric<T> glass{T(eta)};
        // The critical angle from inside: sin(theta_c) = 1/eta (41.81 deg for eta = 1.5).
        const double critical = std::asin(1 / eta) * 180 / shade::pi<double>;
        for (const double above : {0.05, 1.0, 10.0, 30.0, 48.0}) {
            const double deg = critical + above;
            if (deg >= 90) continue;
            CAPTURE(deg);
            const auto v = view_deg(at, 180 - deg);
            // Every uc reflects, the last one included, with probability 1 and weight 1.
            for (const T uc : {T(0), T(0.5), T(1) - std::numeric_limits<T>::epsilon()}) {
                const auto s = glass.sample(v, uc, vec2<T>(0), at);
                REQUIRE(s);
                CHECK(shade::has_flags(s->flags, shade::bsdf_flags::specular_reflection));
                CHECK(s->pdf == T(1));
                CHECK(s->weight == rgb<T>(1));
                CHECK(s->eta == T(1));
                CHECK(glm::dot(at.n(), s->l) < T(0)); // stays inside
            }
        }
        // Just below the critical angle some light leaves: the fraction reflected is the
        // Fresnel reflectance there, from the angle form.
        const double just_below = critical - 0.5;
        const auto below =
            sample_lobes(glass, view_deg(at, 180 - just_below), at, transport_mode::radiance, 1000);
        CHECK(below.reflected < T(1));
        CHECK(std::abs(double(below.reflected) - fresnel_by_angles(just_below * shade::pi<double> / 180, 1 / eta)) <=
              1e-3 + 1e-4);
    }
}

TEST_CASE_TEMPLATE("smooth_dielectric: radiance mode carries 1/eta'^2 through a refraction, importance mode does not",
                   T, float, double) {
    const auto at = brdf_test::tilted<T>();
    const T tol = sizeof(T) <= 4 ? T(2e-6) : T(1e-14);
    const shade::smooth_dielectric<T> glass{T(1.5)};
    const T last = T(1) - std::numeric_limits<T>::epsilon(); // uc that picks the refraction
    // From outside at 30 deg: eta' = 1.5, the radiance weight is 1/2.25, the importance weight 1.
    const auto v = view_deg(at, 30);
    const auto rad = glass.sample(v, last, vec2<T>(0), at, transport_mode::radiance);
    const auto imp = glass.sample(v, last, vec2<T>(0), at, transport_mode::importance);
    REQUIRE(rad);
    REQUIRE(imp);
    CHECK(shade::has_flags(rad->flags, shade::bsdf_flags::specular_transmission));
    CHECK(rad->eta == T(1.5));
    CHECK(imp->eta == T(1.5));
    CHECK(rad->l == imp->l);
    CHECK(rad->pdf == imp->pdf);
    CHECK(close(rad->weight.x, T(1) / T(2.25), tol));
    CHECK(close(imp->weight.x, T(1), tol));
    // The transmitted fraction 1 - R is the pdf, and throughput = weight * pdf.
    const T R = shade::F_dielectric(std::cos(T(30) * shade::pi<T> / T(180)), T(1.5));
    CHECK(close(rad->pdf, T(1) - R, tol));
    // Back through the interface from inside along the refracted ray: the same
    // transmittance (same pdf), l returns to v, eta' = 1/1.5, radiance weight 2.25.
    const auto back_rad = glass.sample(rad->l, last, vec2<T>(0), at, transport_mode::radiance);
    const auto back_imp = glass.sample(rad->l, last, vec2<T>(0), at, transport_mode::importance);
    REQUIRE(back_rad);
    REQUIRE(back_imp);
    CHECK(shade::is_transmission(back_rad->flags));
    CHECK(close(back_rad->eta, T(1) / T(1.5), tol));
    CHECK(glm::length(back_rad->l - v) <= T(8) * tol);
    CHECK(close(back_rad->pdf, rad->pdf, T(8) * tol));
    CHECK(close(back_rad->weight.x, T(2.25), tol));
    CHECK(close(back_imp->weight.x, T(1), tol));
    // The guarantee in docs/conventions.md: weight_radiance * eta^2 = weight_importance.
    for (const auto& s : {*rad, *back_rad})
        CHECK(close(s.weight.x * s.eta * s.eta, T(1), T(4) * tol));
}

TEST_CASE_TEMPLATE("smooth_dielectric: sampled throughput in importance mode is the energy, R + T = 1", T, float, double) {
    const auto at = brdf_test::tilted<T>();
    for (const double eta : {1.0 / 2.4, 1.0 / 1.33, 1.0, 1.33, 1.5, 2.4}) {
        CAPTURE(eta);
        const shade::smooth_dielectric<T> glass{T(eta)};
        for (const double deg : {0.0, 30.0, 60.0, 85.0, 89.9, 95.0, 120.0, 150.0, 180.0}) {
            CAPTURE(deg);
            const auto v = view_deg(at, deg);
            const auto imp = sample_lobes(glass, v, at, transport_mode::importance, 2000);
            const T energy = imp.reflected_weight + imp.transmitted_weight;
            CHECK(energy <= T(1) + T(1e-5));
            CHECK(energy >= T(1) - T(1e-5)); // a lossless interface
            // Radiance mode from the rarer side (eta' > 1) carries less: R + T / eta'^2 < 1.
            const double eta_prime = deg < 90 ? eta : 1 / eta;
            if (eta_prime > 1.01) {
                const auto rad = sample_lobes(glass, v, at, transport_mode::radiance, 2000);
                if (imp.transmitted_weight > T(0.01))
                    CHECK(rad.reflected_weight + rad.transmitted_weight < T(1));
            }
        }
    }
}

TEST_CASE_TEMPLATE("smooth_dielectric: v from inside refracts out by Snell's law", T, float, double) {
    const auto at = brdf_test::tilted<T>();
    const shade::smooth_dielectric<T> glass{T(1.5)};
    // v inside at 20 deg from -n: l leaves at sin(theta_l) = 1.5 sin(20 deg) = 0.51303.
    const auto v = view_deg(at, 160);
    const auto s = glass.sample(v, T(0.99), vec2<T>(0), at, transport_mode::radiance);
    REQUIRE(s);
    CHECK(shade::is_transmission(s->flags));
    const T cos_l = glm::dot(at.n(), s->l);
    CHECK(cos_l > T(0));
    const T sin_l = std::sqrt(T(1) - cos_l * cos_l);
    CHECK(close(sin_l, T(1.5) * std::sin(T(20) * shade::pi<T> / T(180)), T(1e-5)));
    // l lies in the plane of v and n, on the far side of n.
    CHECK(std::abs(glm::dot(glm::cross(at.n(), v), s->l)) <= T(1e-6));
    // Leaving the dense side, radiance gains eta^2 (weight 2.25 = 1.5^2).
    CHECK(close(s->weight.x, T(2.25), T(1e-5)));
    // The reflection stays inside, mirrored about n.
    const auto r = glass.sample(v, T(0), vec2<T>(0), at);
    REQUIRE(r);
    CHECK(shade::is_reflection(r->flags));
    CHECK(close(glm::dot(at.n(), r->l), glm::dot(at.n(), v), T(1e-6)));
}

TEST_CASE_TEMPLATE("smooth_dielectric: no NaN at normal and grazing incidence, from both sides", T, float, double) {
    for (const auto& at : {brdf_test::flat<T>(), brdf_test::tilted<T>()}) {
        const vec3<T> t = at.shading.t;
        const vec3<T> n = at.n();
        for (const double eta : {1e-4, 1 / 1.5, 1.0, 1.5, 1e4}) {
            CAPTURE(eta);
            const shade::smooth_dielectric<T> glass{T(eta)};
            for (const vec3<T>& v : {n, -n, glm::normalize(t + T(1e-6) * n), glm::normalize(t - T(1e-6) * n),
                                     glm::normalize(t + T(1e-30) * n), glm::normalize(t - T(1e-30) * n),
                                     glm::normalize(t + T(1e-3) * n)}) {
                for (const transport_mode mode : {transport_mode::radiance, transport_mode::importance}) {
                    for (const T uc : {T(0), T(0.3), T(0.9999)}) {
                        const auto s = glass.sample(v, uc, vec2<T>(0), at, mode);
                        if (glm::dot(n, v) == T(0)) {
                            CHECK(!s);
                            continue;
                        }
                        REQUIRE(s);
                        check_sample(*s, v, at, sizeof(T) <= 4 ? T(1e-5) : T(1e-12));
                    }
                }
            }
            // On the surface (n·v = 0 in the frame): nothing is drawn.
            if (glm::dot(n, t) == T(0)) CHECK(!glass.sample(t, T(0.5), vec2<T>(0), at));
        }
    }
}

TEST_CASE_TEMPLATE("smooth_dielectric: f and pdf are 0 for every pair; eta = 1 transmits straight through", T, float, double) {
    const auto at = brdf_test::tilted<T>();
    const shade::smooth_dielectric<T> glass{T(1.5)};
    for (const auto& p : brdf_test::degenerate_pairs(at)) {
        CHECK(glass.f(p.l, p.v, at) == rgb<T>(0));
        CHECK(glass.pdf(p.l, p.v, at) == T(0));
    }
    const shade::smooth_dielectric<T> matched{T(1)};
    const auto v = view_deg(at, 50);
    for (const T uc : {T(0), T(0.5), T(0.999)}) {
        const auto s = matched.sample(v, uc, vec2<T>(0), at);
        REQUIRE(s);
        CHECK(shade::is_transmission(s->flags));
        CHECK(glm::length(s->l + v) <= T(1e-6));
        CHECK(close(s->weight.x, T(1), T(1e-6)));
    }
}

TEST_CASE_TEMPLATE("smooth_dielectric: bad eta throws invalid_parameter naming it", T, float, double) {
    for (const T eta : {T(0), T(-1.5), T(1e-5), T(2e4), std::numeric_limits<T>::infinity(),
                        std::numeric_limits<T>::quiet_NaN()}) {
        CAPTURE(eta);
        brdf_test::check_throws_naming([&] { (void)shade::smooth_dielectric<T>(eta); }, "eta");
    }
    CHECK(shade::smooth_dielectric<T>(T(1e-4)).eta() == T(1e-4));
    CHECK(shade::smooth_dielectric<T>(T(1e4)).eta() == T(1e4));
}
