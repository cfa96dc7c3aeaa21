// Every shade reflection model through every property check, with the expected outcome
// asserted both ways: the physically based models pass, and the known offenders are
// detected. A checker that cannot catch the offenders is broken; a model that fails a
// check it claims to pass is broken.
#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/brdf/ashikhmin_shirley.hpp>
#include <shade/brdf/blinn_phong.hpp>
#include <shade/brdf/cook_torrance.hpp>
#include <shade/brdf/eon.hpp>
#include <shade/brdf/lambert.hpp>
#include <shade/brdf/microfacet_reflection.hpp>
#include <shade/brdf/oren_nayar.hpp>
#include <shade/brdf/phong.hpp>
#include <shade/check/doctest.hpp>
#include <shade/check/properties.hpp>
#include <shade/shading/checker.hpp>
#include <shade/shading/gradient.hpp>

#include "model_point.hpp"

namespace {

using shade::rgb;

template <class T>
shade::surface_point<T> point() {
    return check_test::model_point<T>();
}

// Fewer strata than the default keep the suite quick; 128^2 stratified samples are still
// accurate to ~1e-3 for these smooth lobes (see test_properties.cpp for the accuracy test).
const shade::check::albedo_options quick_albedo{.strata = 128, .view_angles = 10, .azimuths = 3};

template <class B>
void expect_physical(const B& model, const char* name) {
    const auto at = point<shade::scalar_of<B>>();
    shade::check::pair_options pairs{.pairs = 4000};
    pairs.model = name;
    auto albedo = quick_albedo;
    albedo.model = name;
    shade::check::doctest_expect(shade::check::positivity(model, at, pairs));
    shade::check::doctest_expect(shade::check::reciprocity(model, at, pairs));
    shade::check::doctest_expect(shade::check::energy_conservation(model, at, albedo));
}

} // namespace

TEST_CASE_TEMPLATE("physically based models pass positivity, reciprocity and energy conservation", T, float, double) {
    using namespace shade;
    // Energy: each model's reflectances are chosen so that diffuse + specular <= 1.
    expect_physical(lambert<T>(rgb<T>(1)), "lambert (k_d = 1)");
    expect_physical(normalized_phong<T>(rgb<T>(T(0.5)), rgb<T>(T(0.5)), T(20)), "normalized phong");
    expect_physical(normalized_phong<T>(rgb<T>(0), rgb<T>(1), T(1)), "normalized phong, k_s = 1, n = 1");
    expect_physical(blinn_phong<T>(rgb<T>(T(0.5)), rgb<T>(T(0.5)), T(50)), "normalized blinn-phong");
    expect_physical(cook_torrance<beckmann<T>, schlick<T>, smith_beckmann<T>>(
                        beckmann<T>(T(0.3)), schlick<T>(rgb<T>(1)), rgb<T>(1)),
                    "cook-torrance beckmann/smith, F = 1");
    expect_physical(cook_torrance<ggx<T>, schlick<T>, smith_ggx<T>>(
                        ggx<T>(T(0.5)), schlick<T>(rgb<T>(1)), rgb<T>(1)),
                    "cook-torrance ggx/smith, F = 1");
    expect_physical(cook_torrance<beckmann<T>, dielectric_fresnel<T>, v_groove<T>>(
                        beckmann<T>(T(0.3)), dielectric_fresnel<T>(T(1.5)), rgb<T>(1)),
                    "cook-torrance beckmann/v-groove, glass Fresnel");
    expect_physical(microfacet_reflection<ggx<T>, conductor_fresnel<T>, smith_height_correlated<T>>(
                        ggx<T>(T(0.4)), conductor_fresnel<T>(rgb<T>(T(0.2), T(0.9), T(1.1)), rgb<T>(T(3.9), T(2.4), T(2.2)))),
                    "microfacet reflection lobe, ggx/height-correlated smith, conductor");
    // A diffuse base is only energy conserving when k_d + k_s <= 1: the diffuse term is not
    // reduced by the Fresnel reflectance, which tends to 1 at grazing.
    expect_physical(cook_torrance<ggx<T>, schlick<T>, smith_ggx<T>>(
                        ggx<T>(T(0.3)), schlick<T>(rgb<T>(T(0.04))), rgb<T>(T(0.5)), rgb<T>(T(0.5))),
                    "cook-torrance ggx/smith, k_s = k_d = 0.5");
    expect_physical(oren_nayar<T>(rgb<T>(T(0.8)), T(0.3)), "oren-nayar (rho 0.8, sigma 0.3)");
    expect_physical(eon<T>(rgb<T>(1), T(1)), "eon (rho 1, r 1)");
    expect_physical(eon<T, eon_albedo::approximate>(rgb<T>(1), T(1)), "eon, fitted albedo (rho 1, r 1)");
    expect_physical(ashikhmin_shirley<T>(rgb<T>(T(0.8)), rgb<T>(T(0.2)), T(10), T(200)),
                    "ashikhmin-shirley");
    // Combinators of physical BRDFs stay physical (convex blends).
    expect_physical(checker<lambert<T>, normalized_phong<T>>(
                        lambert<T>(rgb<T>(1)), normalized_phong<T>(rgb<T>(0), rgb<T>(1), T(10)), T(1)),
                    "checker of lambert and normalized phong");
    expect_physical(gradient<lambert<T>, blinn_phong<T>>(
                        lambert<T>(rgb<T>(1)), blinn_phong<T>(rgb<T>(0), rgb<T>(1), T(10)),
                        vec3<T>(0, 0, 1), T(3)),
                    "gradient of lambert and blinn-phong");
}

TEST_CASE_TEMPLATE("the classic Phong with the division by n.l is caught as not reciprocal", T, float, double) {
    const auto at = point<T>();
    const shade::classic_phong<T> phong(rgb<T>(0), rgb<T>(1), T(10));
    const auto r = shade::check::reciprocity(phong, at, {.pairs = 4000, .model = "classic phong"});
    shade::check::doctest_expect_failure(r);
    // f(l,v)/f(v,l) = (n.v)/(n.l) for this lobe ((r_l.v) = (r_v.l) by symmetry of the
    // mirror), so a large relative difference must be found among the hard pairs.
    CHECK(r.worst > 0.5);
    // The same lobe without the division (Lewis 1994's modified Phong) is reciprocal.
    shade::check::doctest_expect(shade::check::reciprocity(shade::modified_phong<T>(rgb<T>(0), rgb<T>(1), T(10)), at));
}

TEST_CASE_TEMPLATE("an unnormalized specular lobe with k_s = 1 is caught creating energy", T, float, double) {
    const auto at = point<T>();
    // Modified Phong k_s (r.v)^n at v = n: albedo = k_s ∫ cos^n cos dw = 2 pi k_s / (n + 2),
    // which is pi/2 ~ 1.571 for n = 2: 57% more than it receives.
    const shade::modified_phong<T> lobe(rgb<T>(0), rgb<T>(1), T(2));
    const auto r = shade::check::energy_conservation(lobe, at, quick_albedo);
    shade::check::doctest_expect_failure(r);
    CHECK(r.worst == doctest::Approx(shade::pi<double> / 2).epsilon(0.01));
    // Its normalized form (n+2)/(2 pi) brings the same lobe to exactly 1 at normal view.
    const auto s = shade::check::directional_albedo(shade::normalized_phong<T>(rgb<T>(0), rgb<T>(1), T(2)), at.n(), at);
    CHECK(s.albedo.x == doctest::Approx(1.0).epsilon(0.003));
}

TEST_CASE_TEMPLATE("the course-slide Cook-Torrance with F = 1 exceeds albedo 1 near normal incidence", T, float, double) {
    using namespace shade;
    const auto at = point<T>();
    using slide = cook_torrance<beckmann<T>, schlick<T>, v_groove<T>, cook_torrance_form::course>;
    using consistent = cook_torrance<beckmann<T>, schlick<T>, v_groove<T>, cook_torrance_form::walter>;
    const slide s(beckmann<T>(T(0.2)), schlick<T>(rgb<T>(1)));
    const consistent c(beckmann<T>(T(0.2)), schlick<T>(rgb<T>(1)));
    const auto slide_albedo = check::directional_albedo(s, at.n(), at);
    const auto walter_albedo = check::directional_albedo(c, at.n(), at);
    // The slide form is exactly 4/pi times the consistent one, so its albedo is too.
    CHECK(slide_albedo.albedo.x == doctest::Approx(walter_albedo.albedo.x * 4 / pi<double>).epsilon(1e-4));
    // The consistent form's albedo at normal view is 1 - (lobe mass lost below the
    // horizon and to masking) ~ 0.9999 for m = 0.2: allow the estimator's own error.
    CHECK(walter_albedo.albedo.x <= 1.0 + 3 * walter_albedo.standard_error.x);
    CHECK(slide_albedo.albedo.x > 1.02);
    // Near normal incidence (views within 30 degrees) the check must catch it.
    auto near_normal = quick_albedo;
    near_normal.max_theta_degrees = 30;
    near_normal.model = "course-slide cook-torrance, F = 1";
    const auto r = check::energy_conservation(s, at, near_normal);
    check::doctest_expect_failure(r);
    CHECK(r.worst > 1.02);
    // The consistent form passes the same check.
    check::doctest_expect(check::energy_conservation(c, at, near_normal));
}
