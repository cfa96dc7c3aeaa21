// shade::compensated_rough_dielectric over GGX and Beckmann: energy (R + T = 1 within the
// tables' accuracy, both sides), the chi-square test of its sampler and the pdf integral,
// sample/f/pdf/weight consistency, adjoint reciprocity, and the share of the lost energy it
// transmits.
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/brdf/microfacet/beckmann.hpp>
#include <shade/brdf/microfacet/ggx.hpp>
#include <shade/bsdf/compensated_rough_dielectric.hpp>
#include <shade/check/doctest.hpp>
#include <shade/check/sampling.hpp>
#include <shade/core/frame.hpp>
#include <shade/core/random.hpp>
#include <shade/core/sampling.hpp>

#include "bsdf/compensated_energy.hpp"
#include "bsdf/dielectric_albedo.hpp"
#include "bsdf/support.hpp"

// Every member of both instantiations compiles (an explicit instantiation instantiates the
// non-template members a program may not call; the Beckmann one did not compile while a
// GGX-only helper lacked its constraint).
template class shade::compensated_rough_dielectric<float, shade::ggx<float>>;
template class shade::compensated_rough_dielectric<double, shade::beckmann<double>>;

using namespace bsdf_test;
using brdf_test::close;
using shade::transport_mode;

static_assert(shade::bsdf_sampler<shade::compensated_rough_dielectric<float>>);
static_assert(shade::sampled_bsdf<shade::compensated_rough_dielectric<double>>);
static_assert(shade::sampled_bsdf<shade::compensated_rough_dielectric<float, shade::beckmann<float>>>);


TEST_CASE("compensated_rough_dielectric: R + T in [0.99, 1.001] for alpha <= 1, mu >= 0.05, eta in [1.05, 3], both sides") {
    // The same views over Beckmann, and between that table's nodes, run in tests/sweep
    // (script/test --all): its estimator takes about three times as long.
    expect_energy_conserved(
        [](double alpha, double eta) { return shade::compensated_rough_dielectric<double>{shade::ggx<double>(alpha), eta}; },
        "GGX", 1.001);
}

TEST_CASE("compensated_rough_dielectric over Beckmann: R + T in [0.99, 1.001] at random views between the nodes") {
    // 40 views, uniform in log(eta - 1), sqrt(m) and mu over the domain, either side (fixed
    // seed; tests/sweep runs 600 more, and issue #31's lattice of views with the views between
    // the nodes): the envelope is checked on a lattice of points, and
    // these fall anywhere between them.
    const auto make = [](double m, double eta) {
        return shade::compensated_rough_dielectric<double, shade::beckmann<double>>{shade::beckmann<double>(m), eta};
    };
    expect_energy_conserved_at(make, "Beckmann, random views", 1.001, random_views(31, 40));
}

TEST_CASE("compensated_rough_dielectric above eta_hat 3: R + T in [0.99, 1.001] over the continuation tables") {
    // eta_hat 3.5 to 200 (OpenPBR's specular_ior above 3 with transmission), both sides,
    // GGX and Beckmann: E_s is read from the continuations (dielectric_albedo_beyond_grid).
    // Reading the main tables' end at eta_hat 3 instead gave R + T 0.77-0.99 at normal
    // views and up to 1.014 at mu 0.1 from outside, up to 1.042 from inside (eta 10).
    bsdf_test::view_set set;
    set.etas = {3.5, 6.0, 20.0, 200.0};
    set.alphas = {0.02, 0.3, 1.0};
    set.mus = {0.1, 0.5, 0.9};
    expect_energy_conserved(
        [](double alpha, double eta) { return shade::compensated_rough_dielectric<double>{shade::ggx<double>(alpha), eta}; },
        "GGX above eta_hat 3", 1.001, set);
    expect_energy_conserved(
        [](double m, double eta) {
            return shade::compensated_rough_dielectric<double, shade::beckmann<double>>{shade::beckmann<double>(m), eta};
        },
        "Beckmann above eta_hat 3", 1.001, set);
}

TEST_CASE("compensated_rough_dielectric: the uncompensated model loses energy where the compensated one does not") {
    // The check above would fail rough_dielectric itself: at alpha = 1, seen from inside
    // glass near the normal, single scattering keeps well under 0.99.
    const shade::compensated_rough_dielectric<double> model{shade::ggx<double>(1.0), 1.5};
    const energy e = energy_of(model, 0.9, true);
    CHECK(e.single < 0.9);
    CHECK(e.total() == doctest::Approx(1.0).epsilon(1e-2));
}

TEST_CASE("compensated_rough_dielectric: the rarer side transmits 1 - F_avg of the lost energy") {
    // The cosine-weighted hemispherical reflectance of a smooth interface of relative index
    // 1.5 seen from the rarer side is 0.0918 (e.g. Walter et al. 2007's setting; the
    // closed form of Stern 1964, "Transmission of Isotropic Radiation Across an Interface
    // Between Two Dielectrics", Applied Optics 3(1), gives 0.09160... for n = 1.5): the
    // outside shares 1 - 0.0916 = 0.908 of its lost energy with the inside.
    const shade::compensated_rough_dielectric<double> model{shade::ggx<double>(0.5), 1.5};
    CHECK(model.transmitted_share(false) == doctest::Approx(1 - 0.0916).epsilon(1e-3));
    // Seen from the denser side (eta = 1 / 1.5 puts the glass outside), the roles swap.
    const shade::compensated_rough_dielectric<double> swapped{shade::ggx<double>(0.5), 1 / 1.5};
    CHECK(swapped.transmitted_share(true) == doctest::Approx(model.transmitted_share(false)).epsilon(1e-6));
    CHECK(swapped.transmitted_share(false) == doctest::Approx(model.transmitted_share(true)).epsilon(1e-6));
    CHECK(model.transmitted_share(true) > 0);
    CHECK(model.transmitted_share(true) <= 1);
}

TEST_CASE_TEMPLATE("compensated_rough_dielectric: sample draws l with the density pdf over the whole sphere, both sides", T,
                   float, double) {
    // GGX alpha 0.3 and 1 and 0.1 x 0.4, Beckmann m 0.3, eta 1.5 and 1 / 1.33, six views: 48
    // chi-square tests per scalar type at a family-wise level of 1e-3.
    const std::size_t family = 48;
    const auto at = brdf_test::tilted<T>();
    for (const double eta : {1.5, 1 / 1.33}) {
        const auto run = [&](const auto& model, const std::string& name) {
            for (const double deg : {0.0, 60.0, 85.0, 180.0, 120.0, 95.0}) {
                CAPTURE(eta);
                CAPTURE(name);
                CAPTURE(deg);
                shade::check::chi2_options chi2{.samples = 40000, .alpha = 1e-3, .tests = family};
                chi2.model = "compensated rough dielectric " + name;
                const auto v = view_deg(at, deg);
                shade::check::doctest_expect(shade::check::chi2_goodness_of_fit(model, v, at, chi2));
                shade::check::doctest_expect(shade::check::pdf_normalization(model, v, at, chi2));
            }
        };
        run(shade::compensated_rough_dielectric<T>{shade::ggx<T>(T(0.3)), T(eta)}, "ggx 0.3");
        run(shade::compensated_rough_dielectric<T>{shade::ggx<T>(T(1)), T(eta)}, "ggx 1");
        run(shade::compensated_rough_dielectric<T>{shade::ggx<T>(T(0.1), T(0.4)), T(eta)}, "ggx 0.1 x 0.4");
        run(shade::compensated_rough_dielectric<T, shade::beckmann<T>>{shade::beckmann<T>(T(0.3)), T(eta)}, "beckmann 0.3");
    }
}

TEST_CASE_TEMPLATE("compensated_rough_dielectric: samples agree with f and pdf; importance-mode throughput is 1", T, float,
                   double) {
    const auto at = brdf_test::tilted<T>();
    const T rel = sizeof(T) <= 4 ? T(2e-3) : T(1e-9);
    double lowest = 2, highest = 0;
    for (const double eta : {1.33, 2.4, 1 / 1.5}) {
        for (const double alpha : {0.1, 0.5, 1.0}) {
            const shade::compensated_rough_dielectric<T> model{shade::ggx<T>(T(alpha)), T(eta)};
            for (const double deg : {0.0, 45.0, 75.0, 180.0, 135.0, 105.0}) {
                CAPTURE(eta);
                CAPTURE(alpha);
                CAPTURE(deg);
                const auto v = view_deg(at, deg);
                shade::rng random(9);
                const int n = 8000;
                double sum = 0, sum2 = 0;
                for (int i = 0; i < n; ++i) {
                    const T uc = random.uniform<T>();
                    const T u0 = random.uniform<T>();
                    const T u1 = random.uniform<T>();
                    const auto s = model.sample(v, uc, vec2<T>(u0, u1), at, transport_mode::importance);
                    if (!s) continue;
                    check_sample(*s, v, at, rel);
                    CHECK(!shade::is_specular(s->flags));
                    CHECK(close(s->f.x, model.f(v, s->l, at).x, T(10) * rel)); // importance: the adjoint
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
                // The sampler's estimate of R + T: 1 within its noise (and the table's 1e-2).
                CHECK(mean <= 1.001 + 4 * se);
                CHECK(mean >= 0.99 - 4 * se);
                lowest = std::min(lowest, mean);
                highest = std::max(highest, mean);
            }
        }
    }
    MESSAGE("importance-mode R + T of the compensated sampler (8000 samples per view): from " << lowest << " to "
                                                                                               << highest);
}

TEST_CASE("compensated_rough_dielectric: adjoint reciprocity f(l, v) / eta_v^2 = f(v, l) / eta_l^2 to 1e-6 (double)") {
    using T = double;
    const auto at = brdf_test::tilted<T>();
    shade::rng random(23);
    double worst = 0;
    int compared = 0;
    const auto pairs = [&](const auto& model, double eta, int count) {
        for (int i = 0; i < count; ++i) {
            vec2<T> u[2];
            for (auto& ui : u) {
                ui.x = random.uniform<T>();
                ui.y = random.uniform<T>();
            }
            const vec3<T> l = shade::square_to_uniform_sphere(u[0]);
            const vec3<T> v = shade::square_to_uniform_sphere(u[1]);
            const double eta_v = glm::dot(at.n(), v) > 0 ? 1.0 : eta;
            const double eta_l = glm::dot(at.n(), l) > 0 ? 1.0 : eta;
            const double a = double(model.f(l, v, at).x) / (eta_v * eta_v);
            const double b = double(model.f(v, l, at).x) / (eta_l * eta_l);
            CHECK(std::isfinite(a));
            CHECK(a >= 0);
            if (std::max(a, b) < 1e-12) continue;
            ++compared;
            const double relative = std::abs(a - b) / std::max(a, b);
            worst = std::max(worst, relative);
            CHECK(relative <= 1e-6);
        }
    };
    for (const double eta : {1.33, 1.5, 2.4, 1 / 1.5})
        for (const double alpha : {0.05, 0.3, 1.0}) {
            pairs(shade::compensated_rough_dielectric<T>{shade::ggx<T>(alpha, 0.7 * alpha), eta}, eta, 3000);
            pairs(shade::compensated_rough_dielectric<T, shade::beckmann<T>>{shade::beckmann<T>(alpha), eta}, eta, 500);
        }
    MESSAGE("compensated adjoint reciprocity: worst relative difference " << worst << " over " << compared << " pairs");
    // f_ms is nonzero for every pair of directions off the surface.
    CHECK(compared > 30000);
}

TEST_CASE_TEMPLATE("compensated_rough_dielectric: single scattering kept; no NaN on degenerate pairs; bad eta throws", T,
                   float, double) {
    const auto at = brdf_test::tilted<T>();
    const shade::compensated_rough_dielectric<T> model{shade::ggx<T>(T(0.3)), T(1.5)};
    const shade::rough_dielectric<shade::ggx<T>> single{shade::ggx<T>(T(0.3)), T(1.5)};
    const vec3<T> n = at.n();
    const vec3<T> t = at.shading.t;
    for (const vec3<T>& l : {n, -n, t, glm::normalize(t + T(1e-6) * n), glm::normalize(t - T(1e-6) * n)})
        for (const vec3<T>& v : {n, -n, t, glm::normalize(t + T(1e-6) * n), glm::normalize(t - T(1e-6) * n)}) {
            CHECK(brdf_test::finite_non_negative(model.f(l, v, at)));
            const T p = model.pdf(l, v, at);
            CHECK((std::isfinite(p) && p >= T(0)));
            // The single-scattering part is rough_dielectric's, value for value.
            CHECK(model.single_scattering().f(l, v, at) == single.f(l, v, at));
            CHECK(model.f(l, v, at).x >= single.f(l, v, at).x);
        }
    for (const auto& p : brdf_test::degenerate_pairs(at)) {
        CHECK(brdf_test::finite_non_negative(model.f(p.l, p.v, at)));
        CHECK(brdf_test::finite_non_negative(model.f(-p.l, p.v, at)));
        CHECK(brdf_test::finite_non_negative(model.f(p.l, -p.v, at)));
    }
    // A nearly smooth interface loses almost nothing: its compensation is off or tiny.
    const shade::compensated_rough_dielectric<T> smooth{shade::ggx<T>(T(1e-4)), T(1.5)};
    const auto l = view_deg(at, 150);
    const auto v = view_deg(at, 20);
    CHECK(double(smooth.f(l, v, at).x) <= 1e-3);
    for (const T eta : {T(1), T(0), T(-1.5), T(2e4), std::numeric_limits<T>::quiet_NaN()})
        brdf_test::check_throws_naming(
            [&] { (void)shade::compensated_rough_dielectric<T>(shade::ggx<T>(T(0.3)), eta); }, "eta");
}

TEST_CASE_TEMPLATE("compensated_rough_dielectric: the multiple-scattering reflection alone", T, float, double) {
    // multiple_scattering_reflection(l, view, at) is f_ms for l on v's side: f less the
    // single-scattering f there (to rounding), 0 for l across; and, by the class comment's
    // product form, its integral against |n·l| over v's side is (1 - tau_s)(1 - E_s(v))
    // (the lobe's E_s,avg is the cosine average of the same E_s). Integrated here with 256^2
    // stratified cosine-weighted directions (f |n·l| / pdf = pi f), within 1 % of that
    // (the 8-point average of E_s against the table row, and the quadrature).
    const auto at = brdf_test::tilted<T>();
    const T rel = sizeof(T) <= 4 ? T(1e-5) : T(1e-12);
    for (const double eta : {1.5, 1 / 1.5, 2.4}) {
        for (const shade::ggx<T>& d : {shade::ggx<T>(T(0.6)), shade::ggx<T>(T(0.7), T(0.2))}) {
            const shade::compensated_rough_dielectric<T> model{d, T(eta)};
            for (const double deg : {10.0, 60.0, 170.0, 120.0}) {
                CAPTURE(eta);
                CAPTURE(deg);
                const auto v = view_deg(at, deg);
                const auto view = model.prepare(v, at);
                REQUIRE(view.valid);
                const bool inside = glm::dot(v, at.n()) < T(0);
                const vec3<T> side = inside ? -at.n() : at.n();
                const shade::frame<T> hemisphere = shade::frame<T>::from_normal(side);
                constexpr int n = 256;
                double integral = 0;
                bool finite = true;
                for (int i = 0; i < n; ++i)
                    for (int j = 0; j < n; ++j) {
                        const vec2<T> u(T((i + 0.5) / n), T((j + 0.5) / n));
                        const vec3<T> l = hemisphere.to_world(shade::square_to_cosine_hemisphere(u));
                        const T ms = model.multiple_scattering_reflection(l, view, at);
                        finite = finite && std::isfinite(ms);
                        integral += double(ms) * shade::pi<double>;
                        // f less single scattering, and nothing across.
                        if (i % 37 == 0 && j % 41 == 0) {
                            const T rest = model.f(l, v, at).x - model.single_scattering().f(l, v, at).x;
                            CHECK(std::abs(double(rest - ms)) <= double(rel) * (1 + double(model.f(l, v, at).x)));
                            CHECK(model.multiple_scattering_reflection(-l, view, at) == T(0));
                        }
                    }
                integral /= double(n) * n;
                const double expected =
                    (1 - double(model.transmitted_share(inside))) * (1 - double(view.albedo));
                INFO("integral ", integral, " expected ", expected);
                CHECK(finite);
                CHECK(expected > 1e-3);
                CHECK(std::abs(integral - expected) <= 0.01 * expected);
            }
        }
    }
    // An invalid view or a compensation that is off: 0.
    const shade::compensated_rough_dielectric<T> smooth{shade::ggx<T>(T(1e-4)), T(1.5)};
    const auto v = view_deg(at, 30);
    CHECK(smooth.multiple_scattering_reflection(view_deg(at, 50), smooth.prepare(v, at), at) == T(0));
}

TEST_CASE_TEMPLATE("compensated_rough_dielectric: draw and the prepared view give sample's direction, f and pdf", T,
                   float, double) {
    // draw(), prepare() and f_and_pdf() serve a mixture that evaluates the whole model at
    // the drawn direction (shade::openpbr_surface): they must give what sample(), f(),
    // pdf() and single_scattering_albedo() give. Equal to rounding (1e-6 float, 1e-13
    // double, relative: a compiler may contract a product into a fused multiply-add in one
    // inlined copy and not in the other). Isotropic and anisotropic, both sides.
    const auto at = brdf_test::tilted<T>();
    const T rel = sizeof(T) <= 4 ? T(1e-6) : T(1e-13);
    int drawn = 0;
    for (const double eta : {1.33, 2.4, 1 / 1.5}) {
        for (const shade::ggx<T>& d : {shade::ggx<T>(T(0.5)), shade::ggx<T>(T(0.6), T(0.1))}) {
            const shade::compensated_rough_dielectric<T> model{d, T(eta)};
            for (const double deg : {0.0, 45.0, 75.0, 180.0, 135.0, 105.0}) {
                CAPTURE(eta);
                CAPTURE(deg);
                const auto v = view_deg(at, deg);
                const auto view = model.prepare(v, at);
                REQUIRE(view.valid);
                CHECK(close(view.albedo, model.single_scattering_albedo(v, at), rel));
                shade::rng random(22);
                for (int i = 0; i < 200; ++i) {
                    const T uc = random.uniform<T>();
                    const vec2<T> u(random.uniform<T>(), random.uniform<T>());
                    const auto s = model.sample(v, uc, u, at);
                    const auto l = model.draw(v, uc, u, at);
                    const auto l_prepared = model.draw(view, uc, u, at);
                    REQUIRE(l.has_value() == l_prepared.has_value());
                    if (s) REQUIRE(l); // sample() fails wherever its direction does
                    if (!s) continue;
                    ++drawn;
                    CHECK(glm::length(*l - s->l) <= rel);
                    CHECK(glm::length(*l_prepared - s->l) <= rel);
                    const auto both = model.f_and_pdf(s->l, view, at);
                    CHECK(close(both.f.x, model.f(s->l, v, at).x, rel));
                    CHECK(close(both.pdf, model.pdf(s->l, v, at), rel));
                    CHECK(close(both.pdf, s->pdf, rel));
                    const auto plain = model.f_and_pdf(s->l, v, at);
                    CHECK(close(plain.f.x, both.f.x, rel));
                    CHECK(close(plain.pdf, both.pdf, rel));
                }
            }
        }
    }
    CHECK(drawn > 6000);
    // A view on the surface (exactly: the frame of n = +z): nothing prepared, drawn or
    // evaluated.
    const shade::compensated_rough_dielectric<T> model{shade::ggx<T>(T(0.5)), T(1.5)};
    shade::surface_point<T> flat;
    flat.shading = shade::frame<T>::from_normal_tangent({0, 0, 1}, {1, 0, 0});
    const vec3<T> on_surface(1, 0, 0);
    CHECK(!model.prepare(on_surface, flat).valid);
    CHECK(!model.draw(on_surface, T(0.5), vec2<T>(T(0.5)), flat));
    const auto none = model.f_and_pdf(vec3<T>(0, 0, 1), on_surface, flat);
    CHECK(none.pdf == T(0));
    CHECK(none.f == rgb<T>(0));
}
