// shade::kulla_conty, the multiple-scattering policy of cook_torrance
// (shade/brdf/multiple_scattering.hpp): the white furnace of the compensated GGX and
// Beckmann conductors with F = 1 (the acceptance table of issue #19: albedo in
// [0.99, 1.001] for alpha in {0.05, 0.25, 0.5, 0.75, 1} and view cosines down to 0.05,
// where the single-scattering ones fall below), the Fresnel average and F_ms, reciprocity
// and every check of the property kit on the compensated lobe and its sampler.
//
// Sample counts keep the file to a few seconds: the white furnace is split into the
// single-scattering lobe, estimated with 384^2 (GGX) or 224^2 (Beckmann, whose sampler is
// slower) visible-normal samples per view for a standard error below 2e-4 (asserted),
// small against the [0.99, 1.001] window, and the multiple-scattering lobe, integrated
// exactly; the full model's own sampler (128^2 samples) must agree within its error.

#include <algorithm>
#include <cmath>
#include <string>

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/brdf/aliases.hpp>
#include <shade/brdf/cook_torrance.hpp>
#include <shade/check/doctest.hpp>
#include <shade/check/properties.hpp>

#include "brdf/properties_support.hpp"
#include "brdf/support.hpp"

using namespace brdf_test;
namespace form = shade::cook_torrance_form;

namespace {

template <class T>
using ggx_ms = shade::cook_torrance<shade::ggx<T>, shade::schlick<T>, shade::smith_height_correlated<T>, form::walter,
                                    shade::kulla_conty>;
template <class T>
using beckmann_ms = shade::cook_torrance<shade::beckmann<T>, shade::schlick<T>, shade::smith_height_correlated<T>,
                                         form::walter, shade::kulla_conty>;
template <class T>
using ggx_ss = shade::cook_torrance<shade::ggx<T>, shade::schlick<T>, shade::smith_height_correlated<T>>;
template <class T>
using beckmann_ss = shade::cook_torrance<shade::beckmann<T>, shade::schlick<T>, shade::smith_height_correlated<T>>;

// The policy is accepted only with the masking and form the tables were made for.
static_assert(shade::kulla_conty_compensable<shade::ggx<float>, shade::smith_height_correlated<float>, form::walter>);
static_assert(!shade::kulla_conty_compensable<shade::ggx<float>, shade::smith_ggx<float>, form::walter>);
static_assert(!shade::kulla_conty_compensable<shade::ggx<float>, shade::smith_height_correlated<float>, form::course>);
static_assert(shade::sampled_brdf<ggx_ms<float>> && shade::sampled_brdf<beckmann_ms<double>>);
static_assert(shade::split_brdf<ggx_ms<double>>);

constexpr double alphas[] = {0.05, 0.25, 0.5, 0.75, 1.0};
constexpr double view_cosines[] = {1.0, 0.75, 0.5, 0.25, 0.1, 0.05};

template <class T>
vec3<T> view_of(double mu) {
    return vec3<T>(T(std::sqrt((1 - mu) * (1 + mu))), 0, T(mu));
}

template <class B>
shade::check::albedo_sample<shade::scalar_of<B>> furnace(const B& model, double mu, std::size_t strata = 256) {
    using T = shade::scalar_of<B>;
    return shade::check::sampled_albedo(model, view_of<T>(mu), flat<T>(), strata, 7);
}

// 2 integral_0^1 g(mu) mu dmu by the midpoint rule on 20000 cells.
template <class G>
double cosine_average(const G& g) {
    double sum = 0;
    for (int i = 0; i < 20000; ++i) {
        const double mu = (i + 0.5) / 20000;
        sum += 2 * g(mu) * mu / 20000;
    }
    return sum;
}

// The white furnace of a compensated model with F = 1, k_s = 1, k_d = 0, split into its
// two lobes: the single-scattering lobe's albedo E(mu) estimated with its own
// visible-normal sampler (low variance: the weight is G2 / G1), plus the
// multiple-scattering lobe's albedo, which is exact by quadrature,
//     integral f_ms (n·l) dl = (1 - E_t(mu)) (1 - 2 integral E_t(mu') mu' dmu') / (1 - E_avg,t),
// E_t being the model's table reads. ss is the first part's estimate; returns the total.
template <class Compensated>
double split_furnace(const Compensated& compensated, const shade::check::albedo_sample<shade::scalar_of<Compensated>>& ss,
                     double mu) {
    using T = shade::scalar_of<Compensated>;
    const double e_avg_t = double(compensated.average_single_scattering_albedo());
    const double average_t = cosine_average([&](double x) { return double(compensated.single_scattering_albedo(T(x))); });
    const double ms = (1 - double(compensated.single_scattering_albedo(T(mu)))) * (1 - average_t) / (1 - e_avg_t);
    return ss.albedo.x + ms;
}

// The acceptance table for one distribution: compensated in [0.99, 1.001] at every
// (alpha, mu), from the split estimate (standard error < 2e-4, asserted); the model's own
// sampler agrees with it within 4 of its standard errors (it is noisier: the mixture of
// visible normals and cosine, and the draws lost below the horizon); single scattering
// never above the compensated model, and below 0.99 at some view of every alpha.
template <class T, class Compensated, class Single, class Make>
void expect_white_furnace(const Make& make, std::size_t strata) {
    const rgb<T> one(1);
    for (const double alpha : alphas) {
        CAPTURE(alpha);
        const auto d = make(T(alpha));
        const Compensated compensated(d, shade::schlick<T>(one));
        const Single single(d, shade::schlick<T>(one));
        double lowest_single = 1;
        for (const double mu : view_cosines) {
            CAPTURE(mu);
            const auto s = furnace(single, mu, strata);
            const double total = split_furnace(compensated, s, mu);
            const double error = s.standard_error.x;
            CHECK(error < 2e-4);
            CHECK(total >= 0.99);
            CHECK(total <= 1.001);
            const auto own = furnace(compensated, mu, 128);
            CHECK(std::abs(own.albedo.x - total) < 4 * (own.standard_error.x + error));
            // Where single scattering loses nothing (Beckmann alpha = 0.05, steep views) the
            // two agree; otherwise single scattering is lower.
            CHECK(s.albedo.x <= total + 4 * error);
            lowest_single = std::min(lowest_single, s.albedo.x);
        }
        CHECK(lowest_single < 0.99);
    }
}

} // namespace

TEST_CASE_TEMPLATE("kulla_conty: compensated GGX with F = 1 reflects 0.99 to 1.001 of the light, single scattering less",
                   T, float, double) {
    expect_white_furnace<T, ggx_ms<T>, ggx_ss<T>>([](T a) { return shade::ggx<T>(a); }, 384);
}

TEST_CASE_TEMPLATE("kulla_conty: compensated Beckmann with F = 1 reflects 0.99 to 1.001 of the light, single scattering less",
                   T, float, double) {
    expect_white_furnace<T, beckmann_ms<T>, beckmann_ss<T>>([](T a) { return shade::beckmann<T>(a); }, 224);
}

TEST_CASE_TEMPLATE("kulla_conty: F_avg of Schlick is f0 + (1 - f0) / 21", T, float, double) {
    // 2 integral_0^1 (1 - mu)^5 mu dmu = 2 B(2, 6) = 2 * 1! 5! / 7! = 1/21.
    const rgb<T> f0(T(0), T(0.5), T(0.95));
    const auto f_avg = shade::detail::fresnel_average<T>(shade::schlick<T>(f0));
    const rgb<T> expected = f0 + (rgb<T>(1) - f0) / T(21);
    for (int c = 0; c < 3; ++c) CHECK(double(f_avg[c]) == doctest::Approx(double(expected[c])).epsilon(1e-6));
}

TEST_CASE_TEMPLATE("kulla_conty: F_avg of a dielectric is the quadrature of F mu", T, float, double) {
    // Reference: the midpoint rule with 200000 cells of 2 F(mu) mu, in double.
    const double eta = 1.5;
    double reference = 0;
    const int cells = 200000;
    for (int i = 0; i < cells; ++i) {
        const double mu = (i + 0.5) / cells;
        reference += 2 * shade::F_dielectric(mu, eta) * mu / cells;
    }
    const auto f_avg = shade::detail::fresnel_average<T>(shade::dielectric_fresnel<T>(T(eta)));
    CHECK(double(f_avg.x) == doctest::Approx(reference).epsilon(1e-5));
}

TEST_CASE_TEMPLATE("kulla_conty: F_ms is 1 for F_avg = 1 and the bounce series otherwise", T, float, double) {
    const T e_avg = T(0.7);
    CHECK(shade::detail::multiple_scattering_fresnel(rgb<T>(1), e_avg).x == doctest::Approx(1.0));
    // F_avg = 0.5: sum_{k>=2} 0.5^k 0.7 0.3^(k-1) / 0.3 = 0.7 * 0.25 / (1 - 0.15) = 0.2058824.
    CHECK(double(shade::detail::multiple_scattering_fresnel(rgb<T>(T(0.5)), e_avg).x) ==
          doctest::Approx(0.7 * 0.25 / 0.85).epsilon(1e-6));
}

TEST_CASE_TEMPLATE("kulla_conty: f = single scattering + k_s F_ms (1 - E_l)(1 - E_v) / (pi (1 - E_avg)) + k_d / pi", T,
                   float, double) {
    const rgb<T> f0(T(0.9), T(0.6), T(0.3)), k_s(T(0.8)), k_d(T(0.1), T(0.2), T(0.3));
    const ggx_ms<T> compensated(shade::ggx<T>(T(0.6)), shade::schlick<T>(f0), k_s, k_d);
    const ggx_ss<T> single(shade::ggx<T>(T(0.6)), shade::schlick<T>(f0), k_s, k_d);
    const auto at = flat<T>();
    const vec3<T> l = glm::normalize(vec3<T>(T(0.3), T(-0.4), T(0.6)));
    const vec3<T> v = glm::normalize(vec3<T>(T(-0.7), T(0.1), T(0.3)));
    const T e_l = compensated.single_scattering_albedo(l.z);
    const T e_v = compensated.single_scattering_albedo(v.z);
    const T e_avg = compensated.average_single_scattering_albedo();
    const rgb<T> f_avg = f0 + (rgb<T>(1) - f0) / T(21);
    const rgb<T> f_ms = f_avg * f_avg * e_avg / (rgb<T>(1) - f_avg * (T(1) - e_avg));
    const rgb<T> expected = single.f(l, v, at) + k_s * f_ms * (T(1) - e_l) * (T(1) - e_v) / (shade::pi<T> * (T(1) - e_avg));
    const rgb<T> got = compensated.f(l, v, at);
    for (int c = 0; c < 3; ++c) CHECK(double(got[c]) == doctest::Approx(double(expected[c])).epsilon(1e-5));
    const rgb<T> diffuse = compensated.f_diffuse(l, v, at);
    for (int c = 0; c < 3; ++c) {
        CHECK(double(diffuse[c]) == doctest::Approx(double(k_d[c] / shade::pi<T>)));
        CHECK(double(diffuse[c] + compensated.f_specular(l, v, at)[c]) == doctest::Approx(double(got[c])));
    }
    // E at alpha = 0.6 is well below 1 (GGX loses ~20 % at normal incidence), so the lobe is
    // not negligible.
    CHECK(e_avg < T(0.8));
}

TEST_CASE_TEMPLATE("kulla_conty: every property check passes on compensated GGX and Beckmann", T, float, double) {
    const rgb<T> one(1), gold(T(1.0), T(0.71), T(0.29));
    const auto run = [](const auto& model, const std::string& name) { expect_every_property(model, name, 36); };
    run(ggx_ms<T>(shade::ggx<T>(T(0.7)), shade::schlick<T>(one)), "compensated GGX alpha 0.7, F = 1");
    run(ggx_ms<T>(shade::ggx<T>(T(0.2), T(0.4)), shade::schlick<T>(gold)), "compensated GGX 0.2 x 0.4, gold");
    run(beckmann_ms<T>(shade::beckmann<T>(T(0.4)), shade::schlick<T>(one), rgb<T>(T(0.5)), rgb<T>(T(0.5))),
        "compensated Beckmann m 0.4, k_s = k_d = 0.5");
}

TEST_CASE_TEMPLATE("kulla_conty: f is exactly reciprocal and the compensation grows with roughness", T, float, double) {
    const rgb<T> one(1);
    const auto at = tilted<T>();
    const vec3<T> a = glm::normalize(at.shading.to_world(vec3<T>(T(0.5), T(0.2), T(0.4))));
    const vec3<T> b = glm::normalize(at.shading.to_world(vec3<T>(T(-0.3), T(0.6), T(0.2))));
    T previous_loss = 0;
    for (const double alpha : alphas) {
        const ggx_ms<T> model{shade::ggx<T>(T(alpha)), shade::schlick<T>(one)};
        CHECK(model.f(a, b, at) == model.f(b, a, at));
        const T loss = T(1) - model.average_single_scattering_albedo();
        CHECK(loss > previous_loss);
        previous_loss = loss;
    }
    // alpha = 1, F = 1, normal incidence: E = integral of G2 / (4 pi) over the hemisphere
    // with D = 1/pi and G2 = 2 mu / (1 + mu): integral_0^1 mu / (1 + mu) dmu = 1 - ln 2.
    const ggx_ms<T> rough(shade::ggx<T>(T(1)), shade::schlick<T>(one));
    CHECK(double(rough.single_scattering_albedo(T(1))) == doctest::Approx(1 - std::log(2.0)).epsilon(2e-3));
}

TEST_CASE_TEMPLATE("kulla_conty: with 10:1 anisotropy the geometric-mean roughness over-compensates some views", T, float,
                   double) {
    // The documented limit of the approximation (shade/brdf/multiple_scattering.hpp): GGX
    // 0.05 x 0.5 read at sqrt(0.025) ~ 0.16 reflects clearly more than 1 at grazing views
    // across its rough axis, and the energy check over 16 angles x 4 azimuths says so. (The
    // property test above, 0.2 x 0.4 with gold, passes because the check only looks for
    // excess beyond 1.01; with F = 1 that lobe spans 0.946 to 1.024 over azimuths.
    // kulla_conty_anisotropic holds at every azimuth: test_anisotropic_multiple_scattering.cpp.)
    namespace check = shade::check;
    const ggx_ms<T> model(shade::ggx<T>(T(0.05), T(0.5)), shade::schlick<T>(rgb<T>(1)));
    check::albedo_options albedo{.strata = 128, .view_angles = 16, .azimuths = 4,
                                 .estimator = check::albedo_estimator::own_sampler};
    albedo.model = "compensated GGX 0.05 x 0.5, F = 1";
    check::doctest_expect_failure(check::energy_conservation(model, flat<T>(), albedo));
}
