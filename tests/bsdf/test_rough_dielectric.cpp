// shade::rough_dielectric: the chi-square test of its sampler over the whole sphere (v on
// both sides), the pdf integral, adjoint reciprocity, energy, and the smooth limit.
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/brdf/microfacet/beckmann.hpp>
#include <shade/brdf/microfacet/ggx.hpp>
#include <shade/bsdf/rough_dielectric.hpp>
#include <shade/check/doctest.hpp>
#include <shade/check/sampling.hpp>
#include <shade/core/random.hpp>

#include "bsdf/support.hpp"

using namespace bsdf_test;
using brdf_test::close;
using shade::transport_mode;

static_assert(shade::bsdf_sampler<shade::rough_dielectric<shade::ggx<float>>>);
static_assert(shade::sampled_bsdf<shade::rough_dielectric<shade::beckmann<double>>>);
static_assert(!shade::sampled_brdf<shade::rough_dielectric<shade::ggx<double>>>);

namespace {

constexpr double etas[] = {1.33, 1.5, 2.4};
constexpr double views[] = {0, 30, 60, 85, 180, 150, 120, 95}; // outside, then inside

/// The chi-square test and the pdf integral of `model` at every view of `views`.
template <class B>
void expect_sampling_over_sphere(const B& model, const std::string& name, std::size_t family) {
    using T = shade::scalar_of<B>;
    const auto at = brdf_test::tilted<T>();
    for (const double deg : views) {
        CAPTURE(deg);
        shade::check::chi2_options chi2{.samples = 40000, .alpha = 1e-3, .tests = family};
        chi2.model = name;
        const auto v = view_deg(at, deg);
        shade::check::doctest_expect(shade::check::chi2_goodness_of_fit(model, v, at, chi2));
        shade::check::doctest_expect(shade::check::pdf_normalization(model, v, at, chi2));
    }
}

/// The index of refraction on the side of w: 1 outside, eta inside.
template <class T>
double index_on_side(const vec3<T>& w, const shade::surface_point<T>& at, double eta) {
    return glm::dot(at.n(), w) > T(0) ? 1.0 : eta;
}

} // namespace

TEST_CASE_TEMPLATE("rough_dielectric: sample draws l with the density pdf over the whole sphere, both sides", T, float,
                   double) {
    // GGX alpha 0.05, 0.3, 1 and 0.1 x 0.4, Beckmann 0.3 and 0.1 x 0.4, three etas, eight
    // views: 144 chi-square tests per scalar type at a family-wise level of 1e-3.
    const std::size_t family = 144;
    for (const double eta : etas) {
        const std::string e = " eta " + std::to_string(eta).substr(0, 4);
        for (const double alpha : {0.05, 0.3, 1.0}) {
            CAPTURE(alpha);
            expect_sampling_over_sphere(shade::rough_dielectric<shade::ggx<T>>{shade::ggx<T>(T(alpha)), T(eta)},
                                        "rough dielectric ggx " + std::to_string(alpha).substr(0, 4) + e, family);
        }
        expect_sampling_over_sphere(shade::rough_dielectric<shade::ggx<T>>{shade::ggx<T>(T(0.1), T(0.4)), T(eta)},
                                    "rough dielectric ggx 0.1 x 0.4" + e, family);
        expect_sampling_over_sphere(shade::rough_dielectric<shade::beckmann<T>>{shade::beckmann<T>(T(0.3)), T(eta)},
                                    "rough dielectric beckmann 0.3" + e, family);
        expect_sampling_over_sphere(
            shade::rough_dielectric<shade::beckmann<T>>{shade::beckmann<T>(T(0.1), T(0.4)), T(eta)},
            "rough dielectric beckmann 0.1 x 0.4" + e, family);
    }
}

TEST_CASE("rough_dielectric: adjoint reciprocity f(l, v) / eta_v^2 = f(v, l) / eta_l^2 to 1e-6 (double)") {
    using T = double;
    const auto at = brdf_test::tilted<T>();
    shade::rng random(17);
    double worst = 0;
    int compared = 0;
    for (const double eta : {1.33, 1.5, 2.4, 1 / 1.5}) {
        for (const double alpha : {0.05, 0.3, 1.0}) {
            const shade::rough_dielectric<shade::ggx<T>> model{shade::ggx<T>(alpha, 0.7 * alpha), eta};
            for (int i = 0; i < 4000; ++i) {
                vec2<T> u[2];
                for (auto& ui : u) { // drawn in sequence: the same pairs with every compiler
                    ui.x = random.uniform<T>();
                    ui.y = random.uniform<T>();
                }
                const vec3<T> l = shade::square_to_uniform_sphere(u[0]);
                const vec3<T> v = shade::square_to_uniform_sphere(u[1]);
                const double a = double(model.f(l, v, at).x) / shade::sqr(index_on_side(v, at, eta));
                const double b = double(model.f(v, l, at).x) / shade::sqr(index_on_side(l, at, eta));
                CHECK(std::isfinite(a));
                CHECK(a >= 0);
                // The importance-mode value is the radiance-mode value of the swapped pair.
                CHECK(shade::bsdf_f(model, l, v, at, transport_mode::importance) == model.f(v, l, at));
                if (std::max(a, b) < 1e-12) continue;
                ++compared;
                const double relative = std::abs(a - b) / std::max(a, b);
                worst = std::max(worst, relative);
                CHECK(relative <= 1e-6);
            }
        }
    }
    MESSAGE("adjoint reciprocity: worst relative difference " << worst << " over " << compared << " pairs");
    CHECK(compared > 10000);
}

TEST_CASE_TEMPLATE("rough_dielectric: samples agree with f and pdf; importance-mode throughput is at most 1", T, float,
                   double) {
    const auto at = brdf_test::tilted<T>();
    const T rel = sizeof(T) <= 4 ? T(2e-3) : T(1e-9);
    double lowest = 1, highest = 0;
    for (const double eta : etas) {
        for (const double alpha : {0.05, 0.3, 1.0}) {
            const shade::rough_dielectric<shade::ggx<T>> model{shade::ggx<T>(T(alpha)), T(eta)};
            for (const double deg : views) {
                CAPTURE(eta);
                CAPTURE(alpha);
                CAPTURE(deg);
                const auto v = view_deg(at, deg);
                shade::rng random(5);
                const int n = 4000;
                double sum = 0, sum2 = 0;
                for (int i = 0; i < n; ++i) {
                    const T uc = random.uniform<T>();
                    const T u0 = random.uniform<T>();
                    const T u1 = random.uniform<T>();
                    const auto s = model.sample(v, uc, vec2<T>(u0, u1), at, transport_mode::importance);
                    if (!s) continue;
                    check_sample(*s, v, at, rel);
                    CHECK(!shade::is_specular(s->flags));
                    CHECK(close(s->f.x, model.f(v, s->l, at).x, rel)); // importance: the adjoint
                    CHECK(close(s->pdf, model.pdf(s->l, v, at), rel));
                    if (shade::is_transmission(s->flags)) {
                        const auto r = model.sample(v, uc, vec2<T>(u0, u1), at, transport_mode::radiance);
                        REQUIRE(r);
                        CHECK(close(r->f.x, model.f(s->l, v, at).x, rel));
                        CHECK(close(r->weight.x * s->eta * s->eta, s->weight.x, rel));
                    }
                    sum += double(s->weight.x);
                    sum2 += double(s->weight.x) * double(s->weight.x);
                }
                const double mean = sum / n;
                const double se = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
                // Single scattering loses energy, never creates it.
                CHECK(mean <= 1 + 4 * se + 1e-3);
                CHECK(mean > 0.2);
                lowest = std::min(lowest, mean);
                highest = std::max(highest, mean);
            }
        }
    }
    MESSAGE("importance-mode albedo (R + T, 4000 samples per view): from " << lowest << " to " << highest);
}

TEST_CASE_TEMPLATE("rough_dielectric: nearly smooth, it reflects the Fresnel fraction", T, float, double) {
    const auto at = brdf_test::tilted<T>();
    const shade::rough_dielectric<shade::ggx<T>> model{shade::ggx<T>(T(1e-4)), T(1.5)};
    for (const double deg : {0.0, 45.0, 70.0, 160.0}) {
        CAPTURE(deg);
        const auto v = view_deg(at, deg);
        const T R = shade::F_dielectric_two_sided(glm::dot(at.n(), v), T(1.5));
        int reflected = 0, drawn = 0;
        for (int i = 0; i < 2000; ++i) {
            const auto s = model.sample(v, T((i + 0.5) / 2000), vec2<T>(T(0.3), T(0.6)), at);
            if (!s) continue;
            ++drawn;
            reflected += shade::is_reflection(s->flags) ? 1 : 0;
        }
        CHECK(drawn > 1990);
        CHECK(std::abs(T(reflected) / T(drawn) - R) <= T(0.01));
    }
}

TEST_CASE_TEMPLATE("rough_dielectric: no NaN on degenerate pairs; bad eta throws", T, float, double) {
    const auto at = brdf_test::tilted<T>();
    const shade::rough_dielectric<shade::ggx<T>> model{shade::ggx<T>(T(0.3)), T(1.5)};
    const vec3<T> n = at.n();
    const vec3<T> t = at.shading.t;
    for (const vec3<T>& l : {n, -n, t, glm::normalize(t + T(1e-6) * n), glm::normalize(t - T(1e-6) * n)})
        for (const vec3<T>& v : {n, -n, t, glm::normalize(t + T(1e-6) * n), glm::normalize(t - T(1e-6) * n)}) {
            CHECK(brdf_test::finite_non_negative(model.f(l, v, at)));
            const T p = model.pdf(l, v, at);
            CHECK((std::isfinite(p) && p >= T(0)));
        }
    for (const auto& p : brdf_test::degenerate_pairs(at)) {
        CHECK(brdf_test::finite_non_negative(model.f(p.l, p.v, at)));
        CHECK(brdf_test::finite_non_negative(model.f(-p.l, p.v, at)));
        CHECK(brdf_test::finite_non_negative(model.f(p.l, -p.v, at)));
    }
    for (const T eta : {T(1), T(0), T(-1.5), T(2e4), std::numeric_limits<T>::quiet_NaN()})
        brdf_test::check_throws_naming([&] { (void)shade::rough_dielectric<shade::ggx<T>>(shade::ggx<T>(T(0.3)), eta); },
                                       "eta");
}

TEST_CASE_TEMPLATE("rough_dielectric: draw is sample's direction; f_and_pdf is f and pdf, both sides", T, float, double) {
    // draw() and f_and_pdf() serve a mixture that evaluates the whole model at the drawn
    // direction (shade::openpbr_surface): they must give what sample(), f() and pdf() give.
    // The same arithmetic on the same inputs: equal to rounding (1e-6 float, 1e-13 double,
    // relative), allowing for a compiler that contracts a product into a fused multiply-add
    // in one inlined copy and not in the other.
    const auto at = brdf_test::tilted<T>();
    const T rel = sizeof(T) <= 4 ? T(1e-6) : T(1e-13);
    int drawn = 0;
    for (const double eta : etas) {
        const shade::rough_dielectric<shade::ggx<T>> model{shade::ggx<T>(T(0.4)), T(eta)};
        for (const double deg : views) {
            CAPTURE(eta);
            CAPTURE(deg);
            const auto v = view_deg(at, deg);
            shade::rng random(21);
            for (int i = 0; i < 200; ++i) {
                const T uc = random.uniform<T>();
                const vec2<T> u(random.uniform<T>(), random.uniform<T>());
                const auto s = model.sample(v, uc, u, at);
                const auto l = model.draw(v, uc, u, at);
                if (s) REQUIRE(l); // sample() fails wherever its direction does
                if (!s) continue;
                ++drawn;
                CHECK(glm::length(*l - s->l) <= rel);
                const auto both = model.f_and_pdf(s->l, v, at);
                CHECK(close(both.f.x, model.f(s->l, v, at).x, rel));
                CHECK(close(both.pdf, model.pdf(s->l, v, at), rel));
                // The shading-frame forms: the same direction and values.
                const auto l_local = model.draw_local(at.shading.to_local(v), uc, u);
                REQUIRE(l_local);
                CHECK(glm::length(at.shading.to_world(*l_local) - *l) <= rel);
                const auto local_both = model.f_and_pdf_local(at.shading.to_local(s->l), at.shading.to_local(v));
                CHECK(close(local_both.f.x, both.f.x, rel));
                CHECK(close(local_both.pdf, both.pdf, rel));
            }
        }
    }
    CHECK(drawn > 3000);
}

TEST_CASE_TEMPLATE("rough_dielectric: f and pdf stay finite for grazing directions with subnormal cosines", T, float,
                   double) {
    // l and v in the surface's plane up to a subnormal cosine (n tilted by that amount off
    // +z), on opposite sides (a transmission) and on the same side: the product of the two
    // cosines underflows to 0, and without the floor at machine epsilon f was inf or NaN
    // (0 / 0 once G underflows too). The value itself is tiny, the masking function ~0.
    const T tiny = std::numeric_limits<T>::denorm_min() * T(1000);
    shade::surface_point<T> at;
    at.shading = shade::frame<T>::from_normal_tangent(shade::vec3<T>(tiny, tiny, 1), shade::vec3<T>(-1, 0, 0));
    for (const T alpha : {T(0.01), T(0.3), T(1)})
        for (const T eta : {T(1.5), T(0.7)}) {
            const shade::rough_dielectric<shade::ggx<T>> glass(shade::ggx<T>(alpha), eta);
            for (const shade::vec3<T>& l : {shade::vec3<T>(-1, 0, 0), shade::vec3<T>(0, 1, 0)}) {
                const shade::vec3<T> v(1, 0, 0);
                CAPTURE(alpha);
                CAPTURE(eta);
                const auto f = glass.f(l, v, at);
                const T pdf = glass.pdf(l, v, at);
                CHECK((std::isfinite(f.x) && f.x >= T(0)));
                CHECK((std::isfinite(pdf) && pdf >= T(0)));
            }
        }
}
