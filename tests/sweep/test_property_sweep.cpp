// The property kit over every shipped reflection model at many parameter sets and views:
// positivity, reciprocity, the sampling checks (chi-square of sample against pdf, pdf
// normalization, sample consistency, coverage) and, for the models that conserve energy,
// the energy check with the model's own sampler. tests/check/test_sampled_models.cpp runs
// the same checks at a few points in every script/test; this sweep covers the parameter
// ranges (roughness 0.01 to 1 and anisotropy, Phong exponents 1 to 10000, Oren-Nayar sigma
// 0 to 1 in both forms, measured metals, compensated lobes, plastics, sheen) and views from the
// normal to 89.5 degrees, so it runs only in script/test --all (tests/sweep/CMakeLists.txt).
//
// Verdicts: every sampling check and positivity/reciprocity must pass. The energy check must
// not fail: it may be inconclusive where the model's albedo lies within the estimate's error
// of the bound (1 + 0.01), which is how the kit reports a lobe that conserves energy
// exactly, and each model family must pass it somewhere (counted below), so a check that
// never decides cannot hide a regression. The compensated lobes are swept isotropic and at
// 2:1 anisotropy; at 10:1 the averaged-roughness compensation over-compensates, which
// tests/brdf/test_multiple_scattering.cpp shows.
#include <algorithm>
#include <concepts>
#include <cstddef>
#include <string>

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/brdf/aliases.hpp>
#include <shade/brdf/ashikhmin_shirley.hpp>
#include <shade/brdf/blinn_phong.hpp>
#include <shade/brdf/cook_torrance.hpp>
#include <shade/brdf/coupled_plastic.hpp>
#include <shade/brdf/lambert.hpp>
#include <shade/brdf/metals.hpp>
#include <shade/brdf/eon.hpp>
#include <shade/brdf/oren_nayar.hpp>
#include <shade/brdf/phong.hpp>
#include <shade/brdf/sheen.hpp>
#include <shade/check/doctest.hpp>
#include <shade/check/properties.hpp>
#include <shade/shading/checker.hpp>
#include <shade/shading/gradient.hpp>

#include "check/model_point.hpp"

namespace {

using shade::rgb;

// Views from the normal to 89.5 degrees (cos 0.0087), at an azimuth between the tangent
// and the bitangent so anisotropic lobes are seen off their axes.
constexpr double view_angles[] = {0, 30, 60, 80, 87, 89.5};

// An upper bound on the number of chi-square tests in this file (models x views x 2 scalar
// types), so the family's chance of a false rejection stays below 1 % (Šidák).
constexpr std::size_t chi2_family = 4000;

/// What the sweep asserts of a model's energy: the check must not fail (conserving), must
/// fail (violates: a known offender, so the check is seen to catch it), or is not run.
enum class energy { conserving, violates, not_claimed };

/// Whether the model is Helmholtz-reciprocal (the classic forms divide by n·l, so are not).
enum class reciprocal { yes, no };

/// The float tolerance of a power lobe cos^s. Each unit vector (n, l, v) rounded to float has
/// a norm within about one ulp of 1, so the cosine carries a relative error up to ~4 eps
/// (eps = 2^-24) that need not average out, and cos^s carries s times it: 4 s eps (2.4e-3 at
/// s = 10000). The pdf's integral and f(l, v) against f(v, l) differ by that much through
/// rounding alone; the kit's defaults (1e-3) hold below s ~ 4000.
template <class T>
double power_lobe_tolerance(double s, double default_tolerance) {
    if constexpr (std::same_as<T, float>) return std::max(default_tolerance, 4 * s * 0x1p-24);
    return default_tolerance;
}

template <class T>
shade::vec3<T> view(const shade::surface_point<T>& at, double theta_deg) {
    const double theta = theta_deg * shade::pi<double> / 180;
    return glm::normalize(at.shading.to_world(shade::spherical_direction(T(theta), T(0.4))));
}

/// How often the energy check decided "pass" within one test case.
struct energy_tally {
    std::size_t passed = 0;
    std::size_t inconclusive = 0;
};

/// Runs every check of the kit on `model` at the tests' tilted point.
///
/// `exponent` is the model's largest power-lobe exponent (0 if none), which sets the float
/// tolerances (power_lobe_tolerance).
template <class B>
void sweep(const B& model, const std::string& name, energy claim, energy_tally& tally,
           reciprocal symmetric = reciprocal::yes, double exponent = 0) {
    static_assert(shade::sampled_brdf<B>);
    using T = shade::scalar_of<B>;
    namespace check = shade::check;
    INFO(name);
    const auto at = check_test::model_point<T>();

    check::pair_options pairs{.pairs = 3000};
    pairs.model = name;
    check::doctest_expect(check::positivity(model, at, pairs));
    pairs.relative_tolerance = power_lobe_tolerance<T>(exponent, check::default_reciprocity_tolerance<T>());
    const auto helmholtz = check::reciprocity(model, at, pairs);
    if (symmetric == reciprocal::yes) check::doctest_expect(helmholtz);
    else check::doctest_expect_failure(helmholtz);

    for (const double theta : view_angles) {
        CAPTURE(theta);
        check::chi2_options chi2{.samples = 20000, .tests = chi2_family};
        chi2.normalization_tolerance = power_lobe_tolerance<T>(exponent, chi2.normalization_tolerance);
        chi2.model = name;
        const auto v = view(at, theta);
        check::doctest_expect(check::chi2_goodness_of_fit(model, v, at, chi2));
        check::doctest_expect(check::pdf_normalization(model, v, at, chi2));
    }
    check::sample_options consistency{.views = 100, .samples_per_view = 20};
    consistency.model = name;
    check::doctest_expect(check::sample_consistency(model, at, consistency));
    check::pair_options coverage{.pairs = 2000};
    coverage.model = name;
    check::doctest_expect(check::pdf_coverage(model, at, coverage));

    if (claim != energy::not_claimed) {
        check::albedo_options albedo{.strata = 64, .view_angles = 6, .azimuths = 2,
                                     .estimator = check::albedo_estimator::own_sampler};
        albedo.model = name;
        const auto r = check::energy_conservation(model, at, albedo);
        if (claim == energy::violates) {
            check::doctest_expect_failure(r);
            return;
        }
        CHECK_MESSAGE(r.outcome != check::verdict::fail, r.message);
        if (r.outcome == check::verdict::pass) ++tally.passed;
        if (r.outcome == check::verdict::inconclusive) ++tally.inconclusive;
    }
}

std::string number(double x) {
    std::string s = std::to_string(x);
    while (s.size() > 1 && s.back() == '0') s.pop_back();
    if (!s.empty() && s.back() == '.') s.pop_back();
    return s;
}

constexpr double roughnesses[] = {0.01, 0.02, 0.05, 0.1, 0.2, 0.3, 0.5, 0.7, 1};
constexpr double anisotropic[][2] = {{0.05, 0.5}, {0.5, 0.05}, {0.2, 0.1}, {0.5, 1}};
constexpr double exponents[] = {1, 2, 5, 20, 100, 1000, 10000};

} // namespace

TEST_CASE_TEMPLATE("Lambert, Oren-Nayar (sigma 0 to 1, both forms), EON and FON (roughness 0 to 1)", T, float, double) {
    using namespace shade;
    energy_tally tally;
    sweep(lambert<T>(rgb<T>(1)), "lambert k_d = 1", energy::conserving, tally);
    sweep(lambert<T>(rgb<T>(T(0.2), T(0.5), T(0.9))), "lambert coloured", energy::conserving, tally);
    for (const double s : {0.0, 0.1, 0.3, 0.5, 1.0}) {
        sweep(oren_nayar<T>(rgb<T>(1), T(s)), "oren-nayar rho = 1, sigma = " + number(s), energy::conserving, tally);
        // The course form's larger A reflects more than the light received at grazing views
        // when rho = 1 (the qualitative form does not); it is caught at sigma = 0.3.
        sweep(oren_nayar<T, oren_nayar_evaluation::trig_free, oren_nayar_form::course>(rgb<T>(1), T(s)),
              "oren-nayar (course form) rho = 1, sigma = " + number(s),
              s == 0.3 ? energy::violates : energy::not_claimed, tally);
        sweep(oren_nayar_trig<T>(rgb<T>(T(0.8)), T(s)), "oren-nayar (trig) rho = 0.8, sigma = " + number(s),
              energy::conserving, tally);
    }
    for (const double r : {0.0, 0.1, 0.3, 0.5, 1.0}) {
        sweep(eon<T>(rgb<T>(1), T(r)), "eon rho = 1, roughness = " + number(r), energy::conserving, tally);
        sweep(eon<T, eon_albedo::approximate>(rgb<T>(1), T(r)), "eon (fitted albedo) rho = 1, roughness = " + number(r),
              energy::conserving, tally);
        sweep(fujii_oren_nayar<T>(rgb<T>(T(0.8)), T(r)), "fujii oren-nayar rho = 0.8, roughness = " + number(r),
              energy::conserving, tally);
    }
    CHECK(tally.passed > 0);
}

TEST_CASE_TEMPLATE("Zeltner sheen (not reciprocal) and its reciprocal variant, roughness 0 to 1", T, float, double) {
    using namespace shade;
    energy_tally tally;
    for (const double r : {0.0, 0.05, 0.1, 0.3, 0.5, 1.0}) {
        sweep(zeltner_sheen<T>(rgb<T>(1), T(r)), "zeltner sheen F = 1, roughness = " + number(r), energy::conserving,
              tally, reciprocal::no);
        sweep(zeltner_sheen_reciprocal<T>(rgb<T>(1), T(r)), "zeltner sheen reciprocal F = 1, roughness = " + number(r),
              energy::conserving, tally);
    }
    CHECK(tally.passed > 0);
}

TEST_CASE_TEMPLATE("Phong, exponents 1 to 10000", T, float, double) {
    using namespace shade;
    energy_tally tally;
    const rgb<T> one(1), half(T(0.5)), zero(0);
    for (const double s : exponents) {
        const std::string e = number(s);
        sweep(normalized_phong<T>(zero, one, T(s)), "normalized phong k_s = 1, s = " + e, energy::conserving, tally,
              reciprocal::yes, s);
        sweep(normalized_phong<T>(half, half, T(s)), "normalized phong k_d = k_s = 0.5, s = " + e,
              energy::conserving, tally, reciprocal::yes, s);
        sweep(classic_phong<T>(zero, one, T(s)), "classic phong, s = " + e, energy::not_claimed, tally,
              reciprocal::no, s);
        sweep(modified_phong<T>(zero, one, T(s)), "modified phong, s = " + e, energy::not_claimed, tally,
              reciprocal::yes, s);
    }
    CHECK(tally.passed > 0);
}

TEST_CASE_TEMPLATE("Blinn-Phong, exponents 1 to 10000", T, float, double) {
    using namespace shade;
    energy_tally tally;
    const rgb<T> one(1), half(T(0.5)), zero(0);
    for (const double s : exponents) {
        const std::string e = number(s);
        sweep(blinn_phong<T>(zero, one, T(s)), "normalized blinn-phong k_s = 1, s = " + e, energy::conserving, tally,
              reciprocal::yes, s);
        sweep(blinn_phong<T>(half, half, T(s)), "normalized blinn-phong k_d = k_s = 0.5, s = " + e,
              energy::conserving, tally, reciprocal::yes, s);
        sweep(blinn_phong<T, blinn_phong_form::classic>(zero, one, T(s)), "classic blinn-phong, s = " + e, energy::not_claimed, tally,
              reciprocal::no, s);
    }
    CHECK(tally.passed > 0);
}

TEST_CASE_TEMPLATE("Ashikhmin-Shirley, isotropic and anisotropic exponents", T, float, double) {
    using namespace shade;
    energy_tally tally;
    const double pairs[][2] = {{1, 1}, {10, 10}, {10, 200}, {200, 10}, {100, 1000}, {1000, 1000}, {10000, 100}};
    for (const auto& p : pairs) {
        const std::string e = number(p[0]) + " x " + number(p[1]);
        const double largest = std::max(p[0], p[1]);
        sweep(ashikhmin_shirley<T>(rgb<T>(T(0.8)), rgb<T>(T(0.2)), T(p[0]), T(p[1])),
              "ashikhmin-shirley R_d = 0.8, R_s = 0.2, " + e, energy::conserving, tally, reciprocal::yes, largest);
        sweep(ashikhmin_shirley<T>(rgb<T>(0), rgb<T>(1), T(p[0]), T(p[1])), "ashikhmin-shirley R_s = 1, " + e,
              energy::not_claimed, tally, reciprocal::yes, largest);
    }
    CHECK(tally.passed > 0);
}

TEST_CASE_TEMPLATE("Cook-Torrance with GGX, alpha 0.01 to 1 and anisotropic", T, float, double) {
    using namespace shade;
    energy_tally tally;
    const rgb<T> one(1);
    for (const double a : roughnesses) {
        const std::string p = number(a);
        sweep(cook_torrance<ggx<T>, schlick<T>, smith_ggx<T>>(ggx<T>(T(a)), schlick<T>(one)),
              "ggx/smith alpha = " + p + ", F = 1", energy::conserving, tally);
        sweep(ggx_conductor<T>(ggx<T>(T(a)), schlick<T>(one)), "ggx/height-correlated alpha = " + p + ", F = 1",
              energy::conserving, tally);
    }
    for (const auto& a : anisotropic) {
        const std::string p = number(a[0]) + " x " + number(a[1]);
        sweep(cook_torrance<ggx<T>, schlick<T>, smith_ggx<T>>(ggx<T>(T(a[0]), T(a[1])), schlick<T>(one)),
              "ggx/smith alpha = " + p + ", F = 1", energy::conserving, tally);
        sweep(ggx_conductor<T>(ggx<T>(T(a[0]), T(a[1])), schlick<T>(one)),
              "ggx/height-correlated alpha = " + p + ", F = 1", energy::conserving, tally);
    }
    CHECK(tally.passed > 0);
}

TEST_CASE_TEMPLATE("Cook-Torrance with Beckmann, m 0.01 to 1 and anisotropic", T, float, double) {
    using namespace shade;
    energy_tally tally;
    const rgb<T> one(1);
    for (const double a : roughnesses) {
        const std::string p = number(a);
        sweep(cook_torrance<beckmann<T>, schlick<T>, smith_beckmann<T>>(beckmann<T>(T(a)), schlick<T>(one)),
              "beckmann/smith m = " + p + ", F = 1", energy::conserving, tally);
        sweep(cook_torrance<beckmann<T>, schlick<T>, smith_separable<T>>(beckmann<T>(T(a)), schlick<T>(one)),
              "beckmann/exact separable smith m = " + p + ", F = 1", energy::conserving, tally);
        sweep(cook_torrance<beckmann<T>, dielectric_fresnel<T>, v_groove<T>>(beckmann<T>(T(a)),
                                                                           dielectric_fresnel<T>(T(1.5))),
              "beckmann/v-groove m = " + p + ", glass", energy::conserving, tally);
    }
    for (const auto& a : anisotropic) {
        const std::string p = number(a[0]) + " x " + number(a[1]);
        sweep(beckmann_conductor<T>(beckmann<T>(T(a[0]), T(a[1])), schlick<T>(one)),
              "beckmann/height-correlated m = " + p + ", F = 1", energy::conserving, tally);
    }
    CHECK(tally.passed > 0);
}

TEST_CASE_TEMPLATE("measured metals, compensated conductors", T, float, double) {
    using namespace shade;
    energy_tally tally;
    for (const double a : {0.05, 0.3, 1.0}) {
        const std::string p = number(a);
        using metal_ggx = cook_torrance<ggx<T>, conductor_fresnel<T>, smith_height_correlated<T>>;
        sweep(metal_ggx(ggx<T>(T(a)), metals::gold<T>()), "gold ggx alpha = " + p, energy::conserving, tally);
        sweep(metal_ggx(ggx<T>(T(a)), metals::silver<T>()), "silver ggx alpha = " + p, energy::conserving, tally);
        sweep(metal_ggx(ggx<T>(T(a)), metals::copper<T>()), "copper ggx alpha = " + p, energy::conserving, tally);
        sweep(metal_ggx(ggx<T>(T(a)), metals::aluminium<T>()), "aluminium ggx alpha = " + p, energy::conserving,
              tally);
    }
    const rgb<T> one(1), gold_f0(T(1), T(0.71), T(0.29));
    for (const double a : {0.05, 0.25, 0.5, 0.75, 1.0}) {
        const std::string p = number(a);
        sweep(compensated_ggx_conductor<T>(ggx<T>(T(a)), schlick<T>(one)),
              "compensated ggx alpha = " + p + ", F = 1", energy::conserving, tally);
        sweep(compensated_ggx_conductor<T>(ggx<T>(T(a)), schlick<T>(gold_f0)),
              "compensated ggx alpha = " + p + ", gold f0", energy::conserving, tally);
        sweep(compensated_beckmann_conductor<T>(beckmann<T>(T(a)), schlick<T>(one)),
              "compensated beckmann m = " + p + ", F = 1", energy::conserving, tally);
    }
    sweep(compensated_ggx_conductor<T>(ggx<T>(T(0.2), T(0.4)), schlick<T>(one)),
          "compensated ggx alpha = 0.2 x 0.4, F = 1", energy::conserving, tally);
    sweep(compensated_beckmann_conductor<T>(beckmann<T>(T(0.5), T(0.25)), schlick<T>(one)),
          "compensated beckmann m = 0.5 x 0.25, F = 1", energy::conserving, tally);
    CHECK(tally.passed > 0);
}

TEST_CASE_TEMPLATE("plastics and the checker and gradient combinators", T, float, double) {
    using namespace shade;
    energy_tally tally;
    const rgb<T> one(1), zero(0), half(T(0.5));
    for (const double a : {0.05, 0.25, 0.5, 0.75, 1.0}) {
        const std::string p = number(a);
        sweep(coupled_plastic<T>(ggx<T>(T(a)), one), "coupled plastic alpha = " + p + ", k_d = 1", energy::conserving,
              tally);
        sweep(coupled_plastic<T>(ggx<T>(T(a)), rgb<T>(T(0.1), T(0.5), T(0.9))),
              "coupled plastic alpha = " + p + ", coloured k_d", energy::conserving, tally);
        sweep(make_rough_plastic<T>(T(a), half), "rough plastic (uncoupled) alpha = " + p + ", k_d = 0.5",
              energy::not_claimed, tally);
    }
    sweep(checker<lambert<T>, normalized_phong<T>>(lambert<T>(one), normalized_phong<T>(zero, one, T(100)), T(1)),
          "checker of lambert and phong", energy::conserving, tally, reciprocal::yes, 100);
    sweep(gradient<oren_nayar<T>, ggx_conductor<T>>(oren_nayar<T>(one, T(0.5)),
                                                   ggx_conductor<T>(ggx<T>(T(0.1)), schlick<T>(one)),
                                                   vec3<T>(0, 0, 1), T(3)),
          "gradient of oren-nayar and ggx", energy::conserving, tally);
    CHECK(tally.passed > 0);
}
