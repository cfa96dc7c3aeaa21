// The sampling checks of the property kit on BSDFs over the whole sphere
// (shade/check/sampling.hpp, shade/check/energy.hpp): shade's BSDFs passing
// sample_consistency, pdf_coverage and sampled_albedo from both sides, and each rule of
// sample_consistency catching a BSDF made wrong on purpose.
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/brdf/cook_torrance.hpp>
#include <shade/brdf/lambert.hpp>
#include <shade/brdf/metals.hpp>
#include <shade/brdf/microfacet.hpp>
#include <shade/bsdf/compensated_rough_dielectric.hpp>
#include <shade/bsdf/layer.hpp>
#include <shade/bsdf/mix.hpp>
#include <shade/bsdf/rough_dielectric.hpp>
#include <shade/bsdf/smooth_conductor.hpp>
#include <shade/bsdf/smooth_dielectric.hpp>
#include <shade/bsdf/thin_dielectric.hpp>
#include <shade/check/doctest.hpp>
#include <shade/check/energy.hpp>
#include <shade/check/sampling.hpp>

#include "check/model_point.hpp"

namespace {

using shade::rgb;
using shade::transport_mode;
using shade::vec2;
using shade::vec3;

enum class sample_flaw {
    weight_without_cosine,     ///< a glossy sample's weight is f / pdf
    inverted_eta,              ///< a transmission reports 1 / eta' instead of eta'
    inverted_eta_inside,       ///< a transmission from inside reports 1 / eta' (eta' from outside)
    reflection_flag,           ///< a transmission is flagged as a reflection
    importance_f_in_radiance,  ///< radiance-mode samples carry the adjoint f(v, l) (and its weight)
};

/// A rough dielectric (GGX 0.3, eta 1.5) whose sample() has one deliberate flaw.
template <class T>
struct broken_rough {
    using scalar_type = T;
    shade::rough_dielectric<shade::ggx<T>> model{shade::ggx<T>(T(0.3)), T(1.5)};
    sample_flaw kind;
    [[nodiscard]] rgb<T> f(const vec3<T>& l, const vec3<T>& v, const shade::surface_point<T>& at) const {
        return model.f(l, v, at);
    }
    [[nodiscard]] T pdf(const vec3<T>& l, const vec3<T>& v, const shade::surface_point<T>& at) const {
        return model.pdf(l, v, at);
    }
    [[nodiscard]] std::optional<shade::bsdf_sample<T>> sample(const vec3<T>& v, T uc, const vec2<T>& u,
                                                              const shade::surface_point<T>& at,
                                                              transport_mode mode) const {
        auto s = model.sample(v, uc, u, at, mode);
        if (!s) return s;
        const bool transmission = shade::is_transmission(s->flags);
        switch (kind) {
        case sample_flaw::weight_without_cosine: s->weight = s->f / s->pdf; break;
        case sample_flaw::inverted_eta:
            if (transmission) s->eta = T(1) / s->eta;
            break;
        case sample_flaw::inverted_eta_inside:
            if (transmission && glm::dot(at.n(), v) < T(0)) s->eta = T(1) / s->eta;
            break;
        case sample_flaw::reflection_flag:
            if (transmission) s->flags = shade::bsdf_flags::glossy_reflection;
            break;
        case sample_flaw::importance_f_in_radiance:
            if (mode == transport_mode::radiance) {
                s->f = model.f(v, s->l, at);
                s->weight = s->f * std::abs(glm::dot(at.n(), s->l)) / s->pdf;
            }
            break;
        }
        return s;
    }
};

enum class delta_flaw {
    mode_ignored,     ///< radiance-mode throughput in both modes
    bent_refraction,  ///< the refracted direction computed with eta' 1.05 times too large
};

/// The smooth dielectric (eta 1.5) with one deliberate flaw in its delta samples.
template <class T>
struct broken_smooth : shade::detail::delta_lobes<T> {
    shade::smooth_dielectric<T> model{T(1.5)};
    delta_flaw kind;
    [[nodiscard]] std::optional<shade::bsdf_sample<T>> sample(const vec3<T>& v, T uc, const vec2<T>& u,
                                                              const shade::surface_point<T>& at,
                                                              transport_mode mode) const {
        auto s = model.sample(v, uc, u, at, kind == delta_flaw::mode_ignored ? transport_mode::radiance : mode);
        if (!s || !shade::is_transmission(s->flags) || kind != delta_flaw::bent_refraction) return s;
        const bool outside = glm::dot(at.n(), v) > T(0);
        const auto bent = shade::refract(v, outside ? at.n() : -at.n(), T(1.05) * s->eta);
        if (!bent) return s;
        // Only the direction is wrong: f = throughput / |n.l| follows it.
        s->l = *bent;
        s->f = s->weight * s->pdf / std::max(std::abs(glm::dot(at.n(), s->l)), std::numeric_limits<T>::epsilon());
        return s;
    }
};

template <class T>
shade::check::sample_options consistency(const std::string& name, double eta_inside = 0) {
    shade::check::sample_options o{.views = 60, .samples_per_view = 20};
    o.model = name;
    o.eta_inside = eta_inside;
    return o;
}

} // namespace

static_assert(shade::bsdf_sampler<broken_rough<float>>);
static_assert(shade::bsdf_sampler<broken_smooth<double>>);

TEST_CASE_TEMPLATE("sample_consistency: shade's BSDFs agree with f, pdf, flags and eta from both sides, both modes", T,
                   float, double) {
    namespace check = shade::check;
    const auto at = check_test::model_point<T>();
    const shade::rough_dielectric<shade::ggx<T>> glass(shade::ggx<T>(T(0.3)), T(1.5));
    check::doctest_expect(check::sample_consistency(glass, at, consistency<T>("rough glass", 1.5)));
    check::doctest_expect(check::sample_consistency(
        shade::rough_dielectric<shade::ggx<T>>(shade::ggx<T>(T(0.05)), T(2.4)), at, consistency<T>("ggx 0.05", 2.4)));
    check::doctest_expect(check::sample_consistency(
        shade::rough_dielectric<shade::beckmann<T>>(shade::beckmann<T>(T(0.1), T(0.4)), T(1) / T(1.33)), at,
        consistency<T>("beckmann 0.1 x 0.4, bubble", 1 / 1.33)));
    check::doctest_expect(check::sample_consistency(
        shade::compensated_rough_dielectric<T>(shade::ggx<T>(T(0.3)), T(1.33)), at, consistency<T>("compensated", 1.33)));
    const auto smooth = check::sample_consistency(shade::smooth_dielectric<T>(T(1.5)), at, consistency<T>("smooth", 1.5));
    check::doctest_expect(smooth);
    MESSAGE(smooth.message);
    // A thin pane has air on both sides: its transmissions cross eta 1.
    check::doctest_expect(check::sample_consistency(shade::thin_dielectric<T>(T(1.5)), at, consistency<T>("thin", 1)));
    check::doctest_expect(check::sample_consistency(
        shade::smooth_conductor<T>(shade::metals::gold<T>()), at, consistency<T>("mirror")));
    // Delta and glossy lobes in one model; the eta is learnt from the first transmission.
    const shade::mix frosted(glass, rgb<T>(T(0.5)), shade::smooth_dielectric<T>(T(1.5)), rgb<T>(T(0.5)));
    check::doctest_expect(check::sample_consistency(frosted, at, consistency<T>("mix rough + smooth glass")));
    const shade::layer paint(shade::cook_torrance<shade::ggx<T>, shade::dielectric_fresnel<T>,
                                                  shade::smith_height_correlated<T>>(shade::ggx<T>(T(0.2)),
                                                                                     shade::dielectric_fresnel<T>(T(1.5))),
                             shade::lambert<T>(rgb<T>(T(0.8))));
    check::doctest_expect(check::sample_consistency(paint, at, consistency<T>("layer")));
    // pdf covers f over the whole sphere.
    check::pair_options coverage{.pairs = 4000};
    coverage.model = "rough glass";
    check::doctest_expect(check::pdf_coverage(glass, at, coverage));
    check::doctest_expect(check::pdf_coverage(frosted, at, coverage));
}

TEST_CASE_TEMPLATE("sample_consistency: a BSDF sample with a wrong weight, eta, flag or mode fails, naming the rule", T,
                   float, double) {
    namespace check = shade::check;
    const auto at = check_test::model_point<T>();
    const auto expect_rule = [&](const auto& model, double eta_inside, const std::string& rule) {
        const auto r = check::sample_consistency(model, at, consistency<T>("broken", eta_inside));
        check::doctest_expect_failure(r);
        CHECK_MESSAGE(r.message.find(rule) != std::string::npos, r.message);
        return r;
    };
    // f / pdf misses |n.l| in (0, 1): the relative error 1 - |n.l| is large for most draws.
    const auto no_cosine = expect_rule(broken_rough<T>{.kind = sample_flaw::weight_without_cosine}, 1.5,
                                       "weight = f |n.l| / pdf");
    CHECK(no_cosine.worst > 0.9);
    // 1/eta' against eta': a relative error of 1 - 1/1.5^2 = 0.56 when eta_inside is
    // given. Without it, an eta inverted on both sides is an interface of eta 1/1.5 as far
    // as the samples tell; an eta inverted from one side only contradicts the other side
    // (the first transmission setting the value), by the same 0.56.
    const auto inverted = expect_rule(broken_rough<T>{.kind = sample_flaw::inverted_eta}, 1.5, "eta = eta_inside");
    CHECK(inverted.worst == doctest::Approx(1 - 1 / 2.25).epsilon(1e-3));
    check::doctest_expect(
        check::sample_consistency(broken_rough<T>{.kind = sample_flaw::inverted_eta}, at, consistency<T>("1/eta")));
    const auto one_side = expect_rule(broken_rough<T>{.kind = sample_flaw::inverted_eta_inside}, 0,
                                      "the same eta_inside for every transmission");
    CHECK(one_side.worst == doctest::Approx(1 - 1 / 2.25).epsilon(1e-3));
    // A transmission flagged as a reflection has l on the wrong side for its flag.
    expect_rule(broken_rough<T>{.kind = sample_flaw::reflection_flag}, 1.5, "a reflection's l on v's side");
    // The adjoint f in radiance mode: transmissions differ by eta'^2 (or reflections not
    // at all), so the radiance-mode f disagrees with f(l, v).
    expect_rule(broken_rough<T>{.kind = sample_flaw::importance_f_in_radiance}, 1.5, "f = f(l, v)");
    // A delta refraction whose importance weight carries 1/eta'^2 (radiance mode). From
    // inside, eta' = 1/1.5: the importance-mode throughput is 2.25 (1 - R), above 1 by
    // 2.25 0.96 - 1 = 1.16 at normal incidence, where R = 0.04 is smallest (Fresnel, Born
    // & Wolf 1999, eq. 1.5.(21)); hemisphere_pairs starts with v = n, mirrored inside.
    const auto ignored = expect_rule(broken_smooth<T>{{}, shade::smooth_dielectric<T>(T(1.5)), delta_flaw::mode_ignored},
                                     1.5, "importance-mode throughput weight pdf <= 1");
    CHECK(ignored.worst == doctest::Approx(2.25 * 0.96 - 1).epsilon(1e-4));
    // A refraction bent by Snell's law with 1.05 eta'.
    expect_rule(broken_smooth<T>{{}, shade::smooth_dielectric<T>(T(1.5)), delta_flaw::bent_refraction}, 1.5, "l = refract(v, n, eta)");
    // A negative eta_inside is refused by name.
    CHECK_THROWS_WITH_AS(
        (void)check::sample_consistency(shade::smooth_dielectric<T>(T(1.5)), at, consistency<T>("glass", -1)),
        doctest::Contains("eta_inside"), shade::invalid_parameter);
}

TEST_CASE_TEMPLATE("sampled_albedo: a BSDF's radiance-mode albedo over the sphere, from both sides", T, float, double) {
    const auto at = check_test::model_point<T>();
    const shade::smooth_dielectric<T> glass(T(1.5));
    // Radiance mode from outside at normal incidence: R = 0.04 with weight 1, the
    // refraction with probability 0.96 and weight 1/eta'^2 = 1/2.25 (Fresnel, Born & Wolf
    // 1999, eq. 1.5.(21); shade/bsdf/smooth_dielectric.hpp). The mean weight is
    // 0.04 + 0.96 / 2.25 = 0.466667 up to the binomial spread of the lobe choice
    // (sqrt(0.04 0.96 / 4096) (1 - 1/2.25) = 1.7e-3 with 64^2 draws, so within 7e-3).
    const auto outside = shade::check::sampled_albedo(glass, at.n(), at, 64);
    CHECK(outside.albedo.x == doctest::Approx(0.04 + 0.96 / 2.25).epsilon(0.015));
    CHECK(outside.own_sampler);
    // From inside: refraction weight eta'^-2 = 2.25: 0.04 + 0.96 * 2.25 = 2.2 (no energy
    // is created: radiance gains what the solid angle loses).
    const auto inside = shade::check::sampled_albedo(glass, -at.n(), at, 64);
    CHECK(inside.albedo.x == doctest::Approx(0.04 + 0.96 * 2.25).epsilon(0.01));
}

namespace {

/// The rough dielectric GGX alpha 0.05, eta 1.5, whose sampler draws from alpha 0.045: both
/// lobes 10 % narrower than the pdf it reports. Each sample carries the alpha 0.05 model's
/// f and pdf at the drawn l (so sample_consistency cannot see the fault; only the
/// distribution of the draws shows it).
template <class T>
struct narrow_sampler {
    using scalar_type = T;
    shade::rough_dielectric<shade::ggx<T>> model{shade::ggx<T>(T(0.05)), T(1.5)};
    shade::rough_dielectric<shade::ggx<T>> narrow{shade::ggx<T>(T(0.05), T(0.045)), T(1.5)};
    [[nodiscard]] rgb<T> f(const vec3<T>& l, const vec3<T>& v, const shade::surface_point<T>& at) const {
        return model.f(l, v, at);
    }
    [[nodiscard]] T pdf(const vec3<T>& l, const vec3<T>& v, const shade::surface_point<T>& at) const {
        return model.pdf(l, v, at);
    }
    [[nodiscard]] std::optional<shade::bsdf_sample<T>> sample(const vec3<T>& v, T uc, const vec2<T>& u,
                                                              const shade::surface_point<T>& at,
                                                              transport_mode mode) const {
        auto s = narrow.sample(v, uc, u, at, mode);
        if (!s) return s;
        s->pdf = model.pdf(s->l, v, at);
        if (!(s->pdf > T(0))) return std::nullopt;
        s->f = shade::bsdf_f(model, s->l, v, at, mode);
        s->weight = s->f * std::abs(glm::dot(at.n(), s->l)) / s->pdf;
        return s;
    }
};

} // namespace

TEST_CASE_TEMPLATE("chi2_goodness_of_fit: the zoomed grid catches a sharp lobe 10 % too narrow that the whole-sphere grid misses",
                   T, float, double) {
    // The view 60 degrees from the normal in the plane of the tangent, so the sampler's
    // lobe is 10 % narrower than its pdf across the plane of incidence only. The
    // whole-sphere grid cuts the refraction lobe in bands of c around the mirror direction
    // (which resolve its width in the plane of incidence, where it is right) and in 20
    // sectors of 18 degrees (which do not resolve it across); the zoomed grid bins the
    // side of the refraction in rings and 16 sectors around that lobe's own centre. 20000 draws; the family of this test is
    // 8 (alpha 1e-3): the whole-sphere grid alone rejects below 1.25e-4, each grid of the
    // zoomed test below 6.25e-5. Measured: whole-sphere p 0.018 (float), 0.0058 (double);
    // zoomed p 3.9e-19, 1.3e-17.
    namespace check = shade::check;
    const auto at = check_test::model_point<T>();
    const narrow_sampler<T> narrow;
    const double t = 60 * shade::pi<double> / 180;
    const vec3<T> v = glm::normalize(at.shading.to_world(shade::spherical_direction(T(t), T(0))));
    check::chi2_options coarse{.samples = 20000, .alpha = 1e-3, .tests = 8, .zoom_below_degrees = 0};
    coarse.model = "10 % narrow sampler, whole-sphere grid only";
    const auto c = check::chi2_goodness_of_fit(narrow, v, at, coarse);
    check::doctest_expect(c);
    CHECK(!c.zoomed);
    check::chi2_options zoomed{.samples = 20000, .alpha = 1e-3, .tests = 8};
    zoomed.model = "10 % narrow sampler";
    const auto z = check::chi2_goodness_of_fit(narrow, v, at, zoomed);
    check::doctest_expect_failure(z);
    MESSAGE(c.message);
    MESSAGE(z.message);
    CHECK(z.zoomed);
    CHECK(z.zoom_p_value < z.significance);
    CHECK(z.statistic == c.statistic); // the same draws on the same whole-sphere grid
    CHECK(z.message.find("zoomed grid") != std::string::npos);
    // The right sampler passes both grids, and the zoomed quadrature agrees with the
    // whole-sphere one where the latter resolves the lobe.
    zoomed.model = "GGX 0.05, eta 1.5";
    const auto right = check::chi2_goodness_of_fit(narrow.model, v, at, zoomed);
    check::doctest_expect(right);
    CHECK(right.zoomed);
    const auto plain = check::pdf_normalization(narrow.model, v, at, coarse);
    CHECK(std::abs(right.pdf_integral - plain.worst) <= 4 * (right.integration_error + plain.error) + 1e-5);
}

TEST_CASE_TEMPLATE("density_part: a model with a delta lobe passes through its density, fails without it", T, float,
                   double) {
    // A mix of a smooth conductor (delta lobe, chosen with p_a = 0.3 / (0.3 + 0.7) = 0.3) and
    // Lambert (density (1 - p_a) cos / pi): the density integrates to 1 - p_a = 0.7 over
    // the sphere, and the nullopt bin of density_part expects N p_a, the delta draws. The
    // model itself puts 30 % of its draws at the mirror direction, where pdf is 0: the
    // same test on it fails. 2 scalar types x 2 views x 2 tests: family 8 at 1e-3.
    namespace check = shade::check;
    const auto at = check_test::model_point<T>();
    const shade::smooth_conductor<T> metal(rgb<T>(T(0.2), T(0.9), T(1.1)), rgb<T>(T(3.9), T(2.4), T(2.2)));
    const shade::mix m(metal, rgb<T>(T(0.3)), shade::lambert<T>(rgb<T>(T(0.6))), rgb<T>(T(0.7)));
    const check::density_part density{m};
    for (const double deg : {0.0, 60.0}) {
        CAPTURE(deg);
        const double t = deg * shade::pi<double> / 180;
        const vec3<T> v = glm::normalize(at.shading.to_world(shade::spherical_direction(T(t), T(0))));
        check::chi2_options options{.samples = 20000, .alpha = 1e-3, .tests = 8};
        options.model = "smooth conductor 0.3 + Lambert 0.7, density part";
        const auto d = check::chi2_goodness_of_fit(density, v, at, options);
        check::doctest_expect(d);
        CHECK(d.pdf_integral == doctest::Approx(0.7).epsilon(1e-3));
        // Expected nullopt count N p_a = 6000, standard deviation sqrt(N p (1 - p)) = 65.
        CHECK(std::abs(double(d.lost) - 6000.0) <= 5 * 65.0);
        options.model = "smooth conductor 0.3 + Lambert 0.7, whole model";
        check::doctest_expect_failure(check::chi2_goodness_of_fit(m, v, at, options));
    }
    // Draws of the density part are the model's draws, the delta ones removed.
    const vec3<T> v = at.n();
    for (int i = 0; i < 64; ++i) {
        const T uc = T(i) / T(64);
        const auto s = m.sample(v, uc, vec2<T>(T(0.3), T(0.7)), at);
        const auto d = density.sample(v, uc, vec2<T>(T(0.3), T(0.7)), at);
        REQUIRE(s.has_value());
        CHECK(d.has_value() == !shade::is_specular(s->flags));
        if (d) CHECK(d->l == s->l);
    }
}
