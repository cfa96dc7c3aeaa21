// Tests of the sampling checks (shade/check/sampling.hpp), their statistics
// (shade/check/chi2.hpp) and the sampler-based energy check, on small sampled BRDFs defined
// here whose densities are known in closed form, each with deliberate flaws to show that
// every check catches the flaw it is meant for. (tests/check/test_sampled_models.cpp runs
// every shipped sampler through them.)
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/check/doctest.hpp>
#include <shade/check/properties.hpp>
#include <shade/core/frame.hpp>
#include <shade/core/sampling.hpp>

namespace {

using shade::check::verdict;

template <class T>
shade::surface_point<T> tilted_point() {
    // Off the origin with a tilted normal, so the checks are seen to use the frame of `at`.
    return shade::surface_point<T>::at({T(1), T(-2), T(3)}, glm::normalize(shade::vec3<T>(1, 2, 2)));
}

/// The view at angle theta_deg from the normal of `at` (azimuth 0.7 rad from its tangent).
template <class T>
shade::vec3<T> view(const shade::surface_point<T>& at, double theta_deg) {
    const double theta = theta_deg * shade::pi<double> / 180;
    return glm::normalize(at.shading.to_world(shade::spherical_direction(T(theta), T(0.7))));
}

enum class flaw { none, pdf_scaled, narrow_support, weight_without_cosine, f_misreported, wrong_axis };

/// Lambert rho/pi with cosine-weighted sampling: pdf(l) = (n.l)/pi, weight = rho exactly.
/// Flaws: pdf_scaled reports 1.25 times the density in pdf() and in the sample (weight
/// consistent with it); narrow_support draws only within 60 degrees of n, with the density
/// renormalised there (cos/(pi sin^2 60)) and 0 beyond; weight_without_cosine leaves |n.l|
/// out of the weight; f_misreported puts 0.9 f in the sample (and the weight that goes
/// with it).
template <class T>
struct sampled_lambert {
    using scalar_type = T;
    T rho = 1;
    flaw kind = flaw::none;

    [[nodiscard]] shade::rgb<T> f(const shade::vec3<T>& l, const shade::vec3<T>& v,
                                  const shade::surface_point<T>& at) const {
        if (glm::dot(l, at.n()) <= 0 || glm::dot(v, at.n()) <= 0) return shade::rgb<T>(0);
        return shade::rgb<T>(rho / shade::pi<T>);
    }
    [[nodiscard]] T pdf(const shade::vec3<T>& l, const shade::vec3<T>& v, const shade::surface_point<T>& at) const {
        const T c = glm::dot(l, at.n());
        if (c <= 0 || glm::dot(v, at.n()) <= 0) return 0;
        if (kind == flaw::pdf_scaled) return T(1.25) * c / shade::pi<T>;
        if (kind == flaw::narrow_support) return c > T(0.5) ? c / (shade::pi<T> * T(0.75)) : T(0);
        return c / shade::pi<T>;
    }
    [[nodiscard]] std::optional<shade::brdf_sample<T>> sample(const shade::vec3<T>& v, T, const shade::vec2<T>& u,
                                                              const shade::surface_point<T>& at) const {
        if (glm::dot(v, at.n()) <= 0) return std::nullopt;
        shade::vec3<T> local = shade::square_to_cosine_hemisphere(u);
        if (kind == flaw::narrow_support) {
            // Malley's method on the disk of radius sin 60 deg: cos-weighted within the cone.
            const T r = std::sqrt(T(0.75));
            local = shade::vec3<T>(r * local.x, r * local.y, std::sqrt(std::max(T(0), T(1) - T(0.75) * (T(1) - local.z * local.z))));
        }
        const shade::vec3<T> l = glm::normalize(at.shading.to_world(local));
        const T n_dot_l = glm::dot(l, at.n());
        if (n_dot_l <= 0) return std::nullopt;
        shade::rgb<T> value = f(l, v, at);
        const T density = pdf(l, v, at);
        auto s = shade::detail::make_brdf_sample(l, value, density, n_dot_l);
        if (s && kind == flaw::weight_without_cosine) s->weight = value / density;
        if (s && kind == flaw::f_misreported) { // weight consistent with the wrong f
            s->f = T(0.9) * value;
            s->weight = T(0.9) * s->weight;
        }
        return s;
    }
};

/// The normalised Phong lobe around the mirror direction r_v of v,
///   f = (e+2)/(2 pi) max(r_v.l, 0)^e   (reciprocal: r_v.l = r_l.v),
/// sampled with the power lobe around r_v (Lafortune & Willems 1994, "Using the modified
/// Phong reflectance model for physically based rendering", CW 197): cos(a) = u.x^(1/(e+1)),
/// pdf(l) = (e+1)/(2 pi) (r_v.l)^e for l above the surface, nullopt below. At v = n,
/// a(n) = 1 (derivation in test_properties.cpp) and weight = (e+2)/(e+1) (n.l).
/// Flaw wrong_axis draws the lobe around n instead, reporting the density around r_v.
template <class T>
struct sampled_phong_lobe {
    using scalar_type = T;
    T e = 20;
    flaw kind = flaw::none;

    static shade::vec3<T> mirror(const shade::vec3<T>& v, const shade::vec3<T>& n) {
        return glm::normalize(T(2) * glm::dot(n, v) * n - v);
    }
    [[nodiscard]] shade::rgb<T> f(const shade::vec3<T>& l, const shade::vec3<T>& v,
                                  const shade::surface_point<T>& at) const {
        if (glm::dot(l, at.n()) <= 0 || glm::dot(v, at.n()) <= 0) return shade::rgb<T>(0);
        const T c = std::max(glm::dot(mirror(v, at.n()), l), T(0));
        return shade::rgb<T>((e + T(2)) / (T(2) * shade::pi<T>) * std::pow(c, e));
    }
    [[nodiscard]] T pdf(const shade::vec3<T>& l, const shade::vec3<T>& v, const shade::surface_point<T>& at) const {
        if (glm::dot(l, at.n()) <= 0 || glm::dot(v, at.n()) <= 0) return 0;
        const T c = std::max(glm::dot(mirror(v, at.n()), l), T(0));
        return (e + T(1)) / (T(2) * shade::pi<T>) * std::pow(c, e);
    }
    [[nodiscard]] std::optional<shade::brdf_sample<T>> sample(const shade::vec3<T>& v, T, const shade::vec2<T>& u,
                                                              const shade::surface_point<T>& at) const {
        if (glm::dot(v, at.n()) <= 0) return std::nullopt;
        // 1 - cos(a) = -expm1(ln(u.x) / (e + 1)) keeps its digits for large e.
        const double one_minus_cos = -std::expm1(std::log(std::max(double(u.x), 1e-300)) / (double(e) + 1));
        const double cos_a = 1 - one_minus_cos;
        const double sin_a = std::sqrt(std::max(0.0, one_minus_cos * (2 - one_minus_cos)));
        const double phi = 2 * shade::pi<double> * double(u.y);
        const shade::vec3<T> axis = kind == flaw::wrong_axis ? at.n() : mirror(v, at.n());
        const auto lobe = shade::frame<T>::from_normal(axis);
        const shade::vec3<T> l = glm::normalize(
            lobe.to_world(shade::vec3<T>(T(sin_a * std::cos(phi)), T(sin_a * std::sin(phi)), T(cos_a))));
        const T n_dot_l = glm::dot(l, at.n());
        if (n_dot_l <= 0) return std::nullopt;
        return shade::detail::make_brdf_sample(l, f(l, v, at), pdf(l, v, at), n_dot_l);
    }
};

// Every passing chi-square test of this file shares alpha = 0.01 (Šidák): at most 1 %
// chance that any of them rejects a correct sampler.
constexpr std::size_t chi2_family = 64;

template <class B>
shade::check::chi2_options chi2_settings(const char* name, std::size_t samples = 40000) {
    shade::check::chi2_options o;
    o.samples = samples;
    o.tests = chi2_family;
    o.model = name;
    return o;
}

} // namespace

static_assert(shade::sampled_brdf<sampled_lambert<float>>);
static_assert(shade::sampled_brdf<sampled_phong_lobe<double>>);

TEST_CASE("regularized_gamma_q matches closed forms on both of its branches") {
    using shade::check::regularized_gamma_q;
    // Q(1, x) = e^-x and Q(1/2, x) = erfc(sqrt x) (A&S 6.5.17 with Γ(1/2, x) = sqrt(pi) erfc(sqrt x));
    // x < a + 1 takes the series, x >= a + 1 the continued fraction.
    for (const double x : {0.01, 0.5, 1.9, 2.0, 5.0, 30.0, 200.0}) {
        CHECK(regularized_gamma_q(1.0, x) == doctest::Approx(std::exp(-x)).epsilon(1e-12));
        CHECK(regularized_gamma_q(0.5, x) == doctest::Approx(std::erfc(std::sqrt(x))).epsilon(1e-12));
    }
    // Integer a = k: Q(k, x) = e^-x Σ_{j<k} x^j / j! (A&S 6.5.13). k = 5, x = 3 (series)
    // and x = 12 (continued fraction).
    const auto poisson_tail = [](int k, double x) {
        double term = 1, sum = 0;
        for (int j = 0; j < k; ++j) {
            sum += term;
            term *= x / (j + 1);
        }
        return std::exp(-x) * sum;
    };
    CHECK(regularized_gamma_q(5.0, 3.0) == doctest::Approx(poisson_tail(5, 3.0)).epsilon(1e-12));
    CHECK(regularized_gamma_q(5.0, 12.0) == doctest::Approx(poisson_tail(5, 12.0)).epsilon(1e-12));
    CHECK(regularized_gamma_q(2.0, 0.0) == 1.0);
    CHECK_THROWS_AS((void)regularized_gamma_q(0.0, 1.0), shade::invalid_parameter);
    CHECK_THROWS_AS((void)regularized_gamma_q(1.0, -1.0), shade::invalid_parameter);
}

TEST_CASE("chi2_p_value, sidak_significance and pearson_chi2 give hand-computed values") {
    using namespace shade::check;
    // With 2 dof the chi-square survival function is e^(-x/2): p(4.60517) = 0.1.
    CHECK(chi2_p_value(2 * std::log(10.0), 2) == doctest::Approx(0.1).epsilon(1e-12));
    // 1 dof: p = erfc(sqrt(x/2)); x = 3.841459 is the 5 % point.
    CHECK(chi2_p_value(3.841459, 1) == doctest::Approx(0.05).epsilon(1e-5));
    // Šidák: 1 - (1 - 0.19)^(1/2) = 1 - 0.9 = 0.1; one test keeps alpha.
    CHECK(sidak_significance(0.19, 2) == doctest::Approx(0.1).epsilon(1e-12));
    CHECK(sidak_significance(0.01, 1) == doctest::Approx(0.01).epsilon(1e-12));
    CHECK(sidak_significance(0.01, 1000000) == doctest::Approx(1.00503e-8).epsilon(1e-4));
    // Bins expecting (1, 2, 3, 50, 44) with observed (0, 4, 2, 55, 39): the first three
    // (expected < 5) pool into expected 6, observed 6; statistic
    // 0 + 25/50 + 25/44 = 1.0681818..., 3 bins, 2 dof.
    const std::vector<double> observed{0, 4, 2, 55, 39};
    const std::vector<double> expected{1, 2, 3, 50, 44};
    const auto s = pearson_chi2(observed, expected);
    CHECK(s.pooled == 3);
    CHECK(s.bins == 3);
    CHECK(s.dof == 2);
    CHECK(s.statistic == doctest::Approx(0.5 + 25.0 / 44).epsilon(1e-12));
    // A pool still below 5 takes in the next smallest bin: expected (1, 2, 6, 91) with
    // observed (1, 1, 8, 90) pools the first three (expected 9, observed 10): 1/9 + 1/91.
    const auto t = pearson_chi2(std::vector<double>{1, 1, 8, 90}, std::vector<double>{1, 2, 6, 91});
    CHECK(t.bins == 2);
    CHECK(t.statistic == doctest::Approx(1.0 / 9 + 1.0 / 91).epsilon(1e-12));
    // Counts where nothing is expected make the statistic infinite.
    const auto u = pearson_chi2(std::vector<double>{3, 97}, std::vector<double>{0, 100}, 0);
    CHECK(std::isinf(u.statistic));
}

TEST_CASE("the three-way verdict follows the estimate and its error") {
    using namespace shade::check;
    CHECK(decide_at_most(0.99, 0.001, 1.01, 4) == verdict::pass);
    CHECK(decide_at_most(1.05, 0.001, 1.01, 4) == verdict::fail);
    CHECK(decide_at_most(1.00, 0.01, 1.01, 4) == verdict::inconclusive);
    CHECK(decide_at_most(1.03, 0.01, 1.01, 4) == verdict::inconclusive);
    CHECK(decide_at_most(std::nan(""), 0.0, 1.01, 4) == verdict::fail);
    CHECK(decide_at_most(0.5, std::nan(""), 1.01, 4) == verdict::inconclusive);
    CHECK(std::string(to_string(verdict::inconclusive)) == "inconclusive");
}

TEST_CASE_TEMPLATE("correct samplers pass every sampling check, down to grazing views", T, float, double) {
    const auto at = tilted_point<T>();
    for (const double theta : {0.0, 45.0, 80.0, 89.0}) {
        CAPTURE(theta);
        const auto v = view(at, theta);
        const sampled_lambert<T> lambert{};
        const auto chi2 = shade::check::chi2_goodness_of_fit(lambert, v, at, chi2_settings<T>("lambert"));
        shade::check::doctest_expect(chi2);
        // 10 rings x 20 sectors: little is pooled, except at grazing views, where the
        // lower half of the rings around the mirror direction is below the horizon.
        CHECK(chi2.dof > (theta < 60 ? 150u : 80u));
        CHECK(chi2.lost == 0);
        CHECK(chi2.pdf_integral == doctest::Approx(1.0).epsilon(1e-5));
        shade::check::doctest_expect(shade::check::pdf_normalization(lambert, v, at, chi2_settings<T>("lambert")));
        for (const T e : {T(1), T(30), T(10000)}) {
            CAPTURE(e);
            const sampled_phong_lobe<T> lobe{e};
            const auto c = shade::check::chi2_goodness_of_fit(lobe, v, at, chi2_settings<T>("phong lobe"));
            shade::check::doctest_expect(c);
            CHECK(c.dof > 100); // quantile rings resolve even the n = 10000 lobe
            shade::check::doctest_expect(shade::check::pdf_normalization(lobe, v, at, chi2_settings<T>("phong lobe")));
        }
    }
    shade::check::doctest_expect(shade::check::sample_consistency(sampled_lambert<T>{}, at));
    shade::check::doctest_expect(shade::check::sample_consistency(sampled_phong_lobe<T>{T(10000)}, at));
    shade::check::doctest_expect(shade::check::pdf_coverage(sampled_lambert<T>{}, at));
    shade::check::doctest_expect(shade::check::pdf_coverage(sampled_phong_lobe<T>{T(30)}, at));
}

TEST_CASE_TEMPLATE("a pdf off by a factor fails chi-square and the normalization check", T, float, double) {
    const auto at = tilted_point<T>();
    const sampled_lambert<T> scaled{1, flaw::pdf_scaled};
    const auto v = view(at, 30);
    const auto chi2 = shade::check::chi2_goodness_of_fit(scaled, v, at, chi2_settings<T>("pdf x 1.25"));
    shade::check::doctest_expect_failure(chi2);
    CHECK(chi2.p_value < 1e-10);
    CHECK(chi2.pdf_integral == doctest::Approx(1.25).epsilon(1e-5));
    CHECK(chi2.message.find("pdf x 1.25") != std::string::npos);
    const auto normalization = shade::check::pdf_normalization(scaled, v, at);
    shade::check::doctest_expect_failure(normalization);
    CHECK(normalization.worst == doctest::Approx(1.25).epsilon(1e-5));
    // Its samples agree with its own f and pdf: only the distribution is wrong.
    shade::check::doctest_expect(shade::check::sample_consistency(scaled, at));
}

TEST_CASE_TEMPLATE("a lobe sampled around the wrong axis fails chi-square", T, float, double) {
    const auto at = tilted_point<T>();
    // Drawn around n, reported around the mirror direction: at 40 degrees the two lobes
    // (exponent 30, about 15 degrees wide) barely overlap.
    const sampled_phong_lobe<T> wrong{T(30), flaw::wrong_axis};
    const auto chi2 = shade::check::chi2_goodness_of_fit(wrong, view(at, 40), at, chi2_settings<T>("wrong axis"));
    shade::check::doctest_expect_failure(chi2);
    CHECK(chi2.p_value < 1e-10);
    // At v = n the two axes coincide, and the same sampler is correct.
    shade::check::doctest_expect(shade::check::chi2_goodness_of_fit(wrong, at.n(), at, chi2_settings<T>("n axis")));
    // The fault is 1 degree off at 2.5 degrees of view for an exponent-10000 lobe (about
    // 1.2 degrees wide): still caught, because the rings follow the sampled lobe.
    const sampled_phong_lobe<T> sharp{T(10000), flaw::wrong_axis};
    shade::check::doctest_expect_failure(
        shade::check::chi2_goodness_of_fit(sharp, view(at, 0.5), at, chi2_settings<T>("sharp, wrong axis")));
}

TEST_CASE_TEMPLATE("a sample that misreports f or its weight fails the consistency check", T, float, double) {
    const auto at = tilted_point<T>();
    const auto no_cosine = shade::check::sample_consistency(sampled_lambert<T>{1, flaw::weight_without_cosine}, at,
                                                            {.model = "weight without cosine"});
    shade::check::doctest_expect_failure(no_cosine);
    CHECK(no_cosine.message.find("weight = f |n.l| / pdf") != std::string::npos);
    const auto wrong_f = shade::check::sample_consistency(sampled_lambert<T>{1, flaw::f_misreported}, at);
    shade::check::doctest_expect_failure(wrong_f);
    CHECK(wrong_f.worst == doctest::Approx(0.1).epsilon(1e-3));
    CHECK(wrong_f.message.find("f = f(l, v)") != std::string::npos);
}

TEST_CASE_TEMPLATE("a sampler that never draws where f reflects fails the coverage check", T, float, double) {
    const auto at = tilted_point<T>();
    const sampled_lambert<T> narrow{1, flaw::narrow_support};
    const auto coverage = shade::check::pdf_coverage(narrow, at, {.pairs = 4000, .model = "60 degree cone"});
    shade::check::doctest_expect_failure(coverage);
    // Pairs with n.l < cos 60 deg have f = 1/pi and pdf 0.
    CHECK(coverage.value.x == doctest::Approx(1 / shade::pi<double>).epsilon(1e-6));
    CHECK(double(glm::dot(coverage.l, at.n())) <= 0.5 + 1e-6);
    // The chi-square test cannot see this: sample and pdf agree with each other.
    shade::check::doctest_expect(shade::check::chi2_goodness_of_fit(narrow, view(at, 20), at, chi2_settings<T>("cone")));
}

TEST_CASE_TEMPLATE("the energy check uses the model's sampler, with a three-way verdict", T, float, double) {
    const auto at = tilted_point<T>();
    // Cosine sampling of Lambert: every weight is rho, so the estimate is exact and its
    // standard error 0.
    const auto white = shade::check::energy_conservation(sampled_lambert<T>{1}, at, {.strata = 32});
    shade::check::doctest_expect(white);
    CHECK(white.worst == doctest::Approx(1.0).epsilon(1e-6));
    CHECK(white.error == doctest::Approx(0.0));
    CHECK(white.message.find("its own sampler") != std::string::npos);
    const auto bright = shade::check::energy_conservation(sampled_lambert<T>{T(1.02)}, at, {.strata = 32});
    shade::check::doctest_expect_failure(bright);
    CHECK(bright.worst == doctest::Approx(1.02).epsilon(1e-6));
    // The exponent-10000 lobe at v = n: a(n) = 1, weight = (e+2)/(e+1) (n.l) <= 1.0001;
    // passes with its own sampler at 64^2 samples per view.
    shade::check::doctest_expect(
        shade::check::energy_conservation(sampled_phong_lobe<T>{T(10000)}, at, {.strata = 64, .view_angles = 6, .azimuths = 2}));
    const auto s = shade::check::sampled_albedo(sampled_phong_lobe<T>{T(10000)}, at.n(), at, 64);
    CHECK(s.albedo.x == doctest::Approx(1.0).epsilon(2e-4));
    CHECK(s.own_sampler);
    // The cosine/lobe mixture cannot resolve that lobe: with the mixture forced it must not
    // claim a verdict its error does not support. (It is not a pass: the mixture misses
    // most of the lobe at some views.)
    const auto mixture = shade::check::energy_conservation(
        sampled_phong_lobe<T>{T(10000)}, at,
        {.strata = 64, .view_angles = 6, .azimuths = 2, .estimator = shade::check::albedo_estimator::mixture});
    CHECK(mixture.outcome != verdict::fail);
    CHECK(mixture.message.find("mixture") != std::string::npos);
}

TEST_CASE_TEMPLATE("too few samples give an inconclusive energy verdict, never a false one", T, float, double) {
    const auto at = tilted_point<T>();
    // strata 2 = 4 samples per view (below min_albedo_samples): even the exact sampler and
    // the mixture's wild estimates are inconclusive, and the message names the minimum.
    for (const auto estimator : {shade::check::albedo_estimator::own_sampler, shade::check::albedo_estimator::mixture}) {
        const auto r = shade::check::energy_conservation(sampled_lambert<T>{1}, at, {.strata = 2, .estimator = estimator});
        shade::check::doctest_expect_inconclusive(r);
        CHECK(r.message.find("at least 16") != std::string::npos);
    }
    // A gross violation is still a fail at few samples: albedo 1.5 everywhere, exactly.
    shade::check::doctest_expect_failure(
        shade::check::energy_conservation(sampled_lambert<T>{T(1.5)}, at, {.strata = 16}));
}

TEST_CASE_TEMPLATE("bad sampling-check settings are rejected by name", T, float, double) {
    const auto at = tilted_point<T>();
    const sampled_lambert<T> lambert{};
    const shade::vec3<T> below = -at.n();
    CHECK_THROWS_WITH_AS((void)shade::check::chi2_goodness_of_fit(lambert, below, at), doctest::Contains("'v'"),
                         shade::invalid_parameter);
    CHECK_THROWS_WITH_AS((void)shade::check::chi2_goodness_of_fit(lambert, at.n(), at, {.samples = 10}),
                         doctest::Contains("'samples'"), shade::invalid_parameter);
    CHECK_THROWS_WITH_AS((void)shade::check::chi2_goodness_of_fit(lambert, at.n(), at, {.alpha = 2}),
                         doctest::Contains("'alpha'"), shade::invalid_parameter);
    CHECK_THROWS_WITH_AS((void)shade::check::energy_conservation(lambert, at, {.strata = 16, .sigmas = 0}),
                         doctest::Contains("'sigmas'"), shade::invalid_parameter);
}
