// shade::openpbr_parameters (names, defaults, ranges of OpenPBR Surface 1.1) and the
// specification's closed-form pieces in shade::openpbr.

#include <cmath>
#include <limits>
#include <string>

#include <doctest/doctest.h>

#include <shade/brdf/fresnel.hpp>
#include <shade/core/error.hpp>
#include <shade/material/openpbr_parameters.hpp>

namespace {

using shade::rgb;

// 2 integral_0^1 F(mu, eta) mu dmu by the midpoint rule on 400000 cells, in double; for
// eta < 1 the cells below the critical cosine sqrt(1 - eta^2) have F = 1 exactly.
double fresnel_albedo_midpoint(double eta) {
    const int cells = 400000;
    double sum = 0;
    for (int i = 0; i < cells; ++i) {
        const double mu = (i + 0.5) / cells;
        sum += 2 * shade::F_dielectric(mu, eta) * mu / cells;
    }
    return sum;
}

template <class T>
bool close_enough(const rgb<T>& a, const rgb<T>& b) {
    for (int c = 0; c < 3; ++c)
        if (std::abs(double(a[c]) - double(b[c])) > 1e-5) return false;
    return true;
}

} // namespace

TEST_CASE_TEMPLATE("openpbr_parameters: the specification's defaults validate", T, float, double) {
    const shade::openpbr_parameters<T> p;
    CHECK_NOTHROW(p.validate());
    CHECK(p.base_color == rgb<T>(T(0.8)));
    CHECK(p.specular_roughness == T(0.3));
    CHECK(p.specular_ior == T(1.5));
    CHECK(p.coat_ior == T(1.6));
    CHECK(p.fuzz_roughness == T(0.5));
    CHECK(p.thin_film_thickness == T(0.5));
    CHECK(p.thin_film_ior == T(1.4));
    CHECK(p.subsurface_radius_scale == rgb<T>(T(1), T(0.5), T(0.25)));
    CHECK(p.transmission_dispersion_abbe_number == T(20));
    CHECK(p.coat_darkening == T(1));
    CHECK(p.geometry_opacity == T(1));
    CHECK(!p.geometry_thin_walled);
}

TEST_CASE_TEMPLATE("openpbr_parameters: a parameter outside its range is named", T, float, double) {
    const auto expect_named = [](const std::string& name, auto change) {
        shade::openpbr_parameters<T> p;
        change(p);
        CAPTURE(name);
        const std::string quoted = "'" + name + "'";
        CHECK_THROWS_WITH_AS(p.validate(), doctest::Contains(quoted.c_str()), shade::invalid_parameter);
    };
    using P = shade::openpbr_parameters<T>;
    expect_named("base_weight", [](P& p) { p.base_weight = T(1.5); });
    expect_named("base_color", [](P& p) { p.base_color = rgb<T>(T(0.5), T(-0.1), T(0.5)); });
    expect_named("base_metalness", [](P& p) { p.base_metalness = T(std::nan("")); });
    expect_named("specular_weight", [](P& p) { p.specular_weight = T(-1); });
    expect_named("specular_ior", [](P& p) { p.specular_ior = T(0); });
    expect_named("specular_roughness_anisotropy", [](P& p) { p.specular_roughness_anisotropy = T(2); });
    expect_named("transmission_depth", [](P& p) { p.transmission_depth = T(INFINITY); });
    expect_named("transmission_scatter_anisotropy", [](P& p) { p.transmission_scatter_anisotropy = T(-1.5); });
    expect_named("transmission_dispersion_abbe_number", [](P& p) { p.transmission_dispersion_abbe_number = T(0); });
    expect_named("subsurface_radius_scale", [](P& p) { p.subsurface_radius_scale = rgb<T>(T(2)); });
    expect_named("coat_color", [](P& p) { p.coat_color = rgb<T>(T(1.01)); });
    expect_named("coat_ior", [](P& p) { p.coat_ior = T(-1.6); });
    expect_named("coat_darkening", [](P& p) { p.coat_darkening = T(1.1); });
    expect_named("fuzz_roughness", [](P& p) { p.fuzz_roughness = T(-0.1); });
    expect_named("thin_film_thickness", [](P& p) { p.thin_film_thickness = T(-0.5); });
    expect_named("thin_film_ior", [](P& p) { p.thin_film_ior = T(0); });
    expect_named("emission_luminance", [](P& p) { p.emission_luminance = T(-1); });
    expect_named("emission_color", [](P& p) { p.emission_color = rgb<T>(T(1), T(-1), T(1)); });
    expect_named("geometry_opacity", [](P& p) { p.geometry_opacity = T(2); });
    // Values above 1 are allowed where the specification allows them.
    shade::openpbr_parameters<T> hdr;
    hdr.specular_weight = T(3);
    hdr.emission_color = rgb<T>(T(20));
    hdr.transmission_depth = T(5);
    CHECK_NOTHROW(hdr.validate());
}

TEST_CASE_TEMPLATE("openpbr::roughness_to_alpha keeps alpha_t^2 + alpha_b^2 = 2 r^4", T, float, double) {
    for (const double r : {0.0, 0.2, 0.5, 1.0})
        for (const double a : {0.0, 0.3, 0.9, 1.0}) {
            const auto alpha = shade::openpbr::roughness_to_alpha(T(r), T(a));
            CHECK(double(alpha.t * alpha.t + alpha.b * alpha.b) == doctest::Approx(2 * std::pow(r, 4)).epsilon(1e-6));
            CHECK(double(alpha.b) == doctest::Approx((1 - a) * double(alpha.t)).epsilon(1e-6));
        }
    // Isotropic: alpha = r^2 both ways. a = 1: all the variance along the tangent,
    // alpha_t = sqrt(2) r^2.
    const auto iso = shade::openpbr::roughness_to_alpha(T(0.5), T(0));
    CHECK(double(iso.t) == doctest::Approx(0.25));
    CHECK(double(iso.b) == doctest::Approx(0.25));
    const auto full = shade::openpbr::roughness_to_alpha(T(0.5), T(1));
    CHECK(double(full.t) == doctest::Approx(0.25 * std::sqrt(2.0)));
    CHECK(full.b == T(0));
}

TEST_CASE_TEMPLATE("openpbr::modulated_ior_ratio scales the normal-incidence reflectance by specular_weight", T, float,
                   double) {
    for (const double eta : {1.5, 1.33, 2.4, 0.7})
        for (const double xi : {0.0, 0.25, 0.5, 1.0, 2.0}) {
            CAPTURE(eta);
            CAPTURE(xi);
            const T modulated = shade::openpbr::modulated_ior_ratio(T(eta), T(xi));
            // F0 of the new ratio is xi times F0 of the old one (xi below 1 / F_s here).
            const double f_s = std::pow((1 - eta) / (1 + eta), 2);
            CHECK(double(shade::f0_from_ior(modulated)) == doctest::Approx(xi * f_s).epsilon(1e-5).scale(1));
            // The same side of 1 as eta (a denser medium stays denser).
            if (xi > 0) CHECK((double(modulated) - 1) * (eta - 1) > 0);
        }
    CHECK(shade::openpbr::modulated_ior_ratio(T(1.5), T(0)) == T(1));
    CHECK(double(shade::openpbr::modulated_ior_ratio(T(1.5), T(1))) == doctest::Approx(1.5));
    // xi F_s >= 1 is clamped: the largest index ratio, never infinite or NaN.
    const T huge = shade::openpbr::modulated_ior_ratio(T(1.5), T(1000));
    CHECK(std::isfinite(huge));
    CHECK(huge == shade::dielectric_eta_max<T>);
}

TEST_CASE_TEMPLATE("openpbr::specular_ior_ratio blends the ambient and coat ratios, never below 1 under a denser coat",
                   T, float, double) {
    // No coat: n_b / n_a. Full coat rarer than the base: n_b / n_c. Full coat denser than the
    // base (1.6 over 1.5): inverted to n_c / n_b = 1.0667 (no total internal reflection).
    CHECK(double(shade::openpbr::specular_ior_ratio(T(1.5), T(1), T(1.6), T(0))) == doctest::Approx(1.5));
    CHECK(double(shade::openpbr::specular_ior_ratio(T(1.5), T(1), T(1.2), T(1))) == doctest::Approx(1.25));
    CHECK(double(shade::openpbr::specular_ior_ratio(T(1.5), T(1), T(1.6), T(1))) == doctest::Approx(1.6 / 1.5));
    CHECK(double(shade::openpbr::specular_ior_ratio(T(1.5), T(1), T(1.6), T(0.5))) ==
          doctest::Approx(0.5 * 1.5 + 0.5 * 1.6 / 1.5));
}

TEST_CASE_TEMPLATE("openpbr::coat_roughened adds slope variances, the coat's twice", T, float, double) {
    CHECK(double(shade::openpbr::coat_roughened(T(0.3), T(0.5), T(0))) == doctest::Approx(0.3));
    CHECK(double(shade::openpbr::coat_roughened(T(0.3), T(0), T(1))) == doctest::Approx(0.3));
    // (0.3^4 + 2 * 0.5^4)^(1/4) = (0.0081 + 0.125)^(1/4) = 0.1331^(1/4).
    CHECK(double(shade::openpbr::coat_roughened(T(0.3), T(0.5), T(1))) == doctest::Approx(std::pow(0.1331, 0.25)));
    CHECK(double(shade::openpbr::coat_roughened(T(0.9), T(0.9), T(1))) == doctest::Approx(1.0));
    CHECK(double(shade::openpbr::coat_roughened(T(0.3), T(0.5), T(0.5))) ==
          doctest::Approx(0.5 * 0.3 + 0.5 * std::pow(0.1331, 0.25)));
}

TEST_CASE_TEMPLATE("dielectric_fresnel_average (E_F of OpenPBR's coat): the integral, its relation across 1, d'Eon's fit", T, float,
                   double) {
    for (const double eta : {1.0, 1.1, 1.33, 1.5, 2.0, 3.0, 0.8, 0.5}) {
        CAPTURE(eta);
        CHECK(double(shade::dielectric_fresnel_average(T(eta))) ==
              doctest::Approx(fresnel_albedo_midpoint(eta)).epsilon(2e-6).scale(1));
    }
    // d'Eon 2021's fit, accurate to 0.2 % for eta in [1, 3] (the specification's footnote
    // avg_fresnel): ln((10893 eta - 1438.2) / (-774.4 eta^2 + 10212 eta + 1)).
    for (const double eta : {1.2, 1.5, 2.0, 2.5, 3.0}) {
        const double fit = std::log((10893 * eta - 1438.2) / (-774.4 * eta * eta + 10212 * eta + 1));
        CHECK(double(shade::dielectric_fresnel_average(T(eta))) == doctest::Approx(fit).epsilon(2e-3));
    }
}

TEST_CASE_TEMPLATE("openpbr::coat_darkening_factor", T, float, double) {
    const T eta_c = T(1.5);
    // A white base loses nothing: Delta = (1 - K) / (1 - K) = 1.
    CHECK(close_enough(shade::openpbr::coat_darkening_factor(rgb<T>(1), eta_c, T(0.7), T(0.5), T(1), T(1)), rgb<T>(1)));
    // No coat, or coat_darkening 0: factor 1.
    CHECK(close_enough(shade::openpbr::coat_darkening_factor(rgb<T>(T(0.3)), eta_c, T(0.7), T(0.5), T(0), T(1)),
                       rgb<T>(1)));
    CHECK(close_enough(shade::openpbr::coat_darkening_factor(rgb<T>(T(0.3)), eta_c, T(0.7), T(0.5), T(1), T(0)),
                       rgb<T>(1)));
    // A rough base (r_b = 1) under a full coat: K = K_r = 1 - (1 - E_F(1.5)) / 2.25, with
    // E_F(1.5) from the midpoint integral; Delta = (1 - K) / (1 - 0.3 K).
    const double k_r = 1 - (1 - fresnel_albedo_midpoint(1.5)) / 2.25;
    const double expected = (1 - k_r) / (1 - 0.3 * k_r);
    const rgb<T> rough = shade::openpbr::coat_darkening_factor(rgb<T>(T(0.3)), eta_c, T(0.7), T(1), T(1), T(1));
    CHECK(double(rough.x) == doctest::Approx(expected).epsilon(1e-5));
    // A smooth base: K = K_s = F(mu_o, eta_c); half coverage halves the change.
    const double k_s = shade::F_dielectric(0.7, 1.5);
    const rgb<T> smooth = shade::openpbr::coat_darkening_factor(rgb<T>(T(0.3)), eta_c, T(0.7), T(0), T(0.5), T(1));
    CHECK(double(smooth.y) == doctest::Approx(0.5 + 0.5 * (1 - k_s) / (1 - 0.3 * k_s)).epsilon(1e-5));
    // Darker bases darken more (Delta falls as E_b falls), and the factor stays in (0, 1].
    const rgb<T> graded =
        shade::openpbr::coat_darkening_factor(rgb<T>(T(0.9), T(0.5), T(0.1)), eta_c, T(0.7), T(1), T(1), T(1));
    CHECK(graded.x > graded.y);
    CHECK(graded.y > graded.z);
    CHECK(graded.z > T(0));
    // With K_s = F(mu_o, eta_c) and K_r given: the same numbers.
    const T k_r_t = shade::openpbr::coat_rough_reflection(eta_c);
    for (const T r_b : {T(0), T(0.4), T(1)})
        CHECK(shade::openpbr::coat_darkening_factor_of_reflectances(rgb<T>(T(0.9), T(0.5), T(0.1)),
                                                                    shade::F_dielectric(T(0.7), eta_c), k_r_t, r_b,
                                                                    T(1), T(0.8)) ==
              shade::openpbr::coat_darkening_factor(rgb<T>(T(0.9), T(0.5), T(0.1)), eta_c, T(0.7), r_b, T(1),
                                                    T(0.8)));
}

TEST_CASE_TEMPLATE("openpbr::base_roughness_estimate and coat_absorption", T, float, double) {
    // Metal: r. Dielectric with F_s = 0.04 at weight 1: lerp(1, r, 0.04).
    CHECK(double(shade::openpbr::base_roughness_estimate(T(0.2), T(1), T(1), T(1.5))) == doctest::Approx(0.2));
    CHECK(double(shade::openpbr::base_roughness_estimate(T(0.2), T(0), T(1), T(1.5))) ==
          doctest::Approx(1 + 0.04 * (0.2 - 1)));
    // Normal incidence: coat_color itself (T_coat^2).
    const rgb<T> color(T(0.9), T(0.5), T(0.2));
    CHECK(close_enough(shade::openpbr::coat_absorption(color, T(1), T(1), T(1.6)), color));
    // At mu = 0.5 through a coat of 1.6: mu^t = sqrt(1 - 0.75 / 2.56); both paths so the
    // exponent is 1 / mu^t.
    const double mu_t = std::sqrt(1 - 0.75 / 2.56);
    const rgb<T> slant = shade::openpbr::coat_absorption(color, T(0.5), T(0.5), T(1.6));
    CHECK(double(slant.y) == doctest::Approx(std::pow(0.5, 1 / mu_t)).epsilon(1e-5));
    CHECK(slant.z < color.z);
    // A clear coat absorbs nothing at any angle.
    CHECK(close_enough(shade::openpbr::coat_absorption(rgb<T>(1), T(0.01), T(0.3), T(1.6)), rgb<T>(1)));
}

TEST_CASE_TEMPLATE("openpbr::transmission_medium: Beer's law at transmission_depth, grey shift of negative absorption",
                   T, float, double) {
    shade::openpbr_parameters<T> p;
    CHECK(!shade::openpbr::transmission_medium(p).present); // depth 0: no medium
    p.transmission_color = rgb<T>(T(0.5), T(0.8), T(1));
    p.transmission_depth = T(2);
    const auto clear = shade::openpbr::transmission_medium(p);
    REQUIRE(clear.present);
    // exp(-sigma_t * depth) = transmission_color: white light has that colour at that depth.
    for (int c = 0; c < 3; ++c)
        CHECK(std::exp(-double(clear.sigma_t[c]) * 2) == doctest::Approx(double(p.transmission_color[c])).epsilon(1e-6));
    CHECK(clear.albedo == rgb<T>(0));
    // Scattering S = 0.5 in a channel whose extinction is only ln(1/0.8)/2 = 0.1116: sigma_a
    // would be 0.1116 - 0.25 < 0 in green and 0 - 0.25 in blue; every channel is shifted up by
    // 0.25 (the blue deficit), then sigma_t = sigma_a + sigma_s. (Colours after a depth of 2:
    // red ln 2 / 2 - 0.25 + 0.25 of absorption plus 0.25 of scattering.)
    p.transmission_scatter = rgb<T>(T(0.5));
    p.transmission_scatter_anisotropy = T(0.3);
    const auto murky = shade::openpbr::transmission_medium(p);
    const double sigma_s = 0.25, shift = 0.25;
    const double sigma_t_red = std::log(2.0) / 2 - sigma_s + shift + sigma_s;
    CHECK(double(murky.sigma_t.x) == doctest::Approx(sigma_t_red).epsilon(1e-6));
    // Blue: sigma_a = 0 - 0.25 + shift = 0, so sigma_t = sigma_s = 0.25 and the albedo is 1.
    CHECK(double(murky.sigma_t.z) == doctest::Approx(sigma_s).epsilon(1e-6));
    CHECK(double(murky.albedo.z) == doctest::Approx(1.0).epsilon(1e-6));
    CHECK(double(murky.albedo.x) == doctest::Approx(sigma_s / sigma_t_red).epsilon(1e-6));
    CHECK(murky.g == T(0.3));
    // Black transmission_color: a finite, huge extinction, no NaN.
    p.transmission_color = rgb<T>(0);
    const auto black = shade::openpbr::transmission_medium(p);
    for (int c = 0; c < 3; ++c) {
        CHECK(std::isfinite(black.sigma_t[c]));
        CHECK(black.sigma_t[c] > T(10));
        CHECK(black.albedo[c] >= T(0));
    }
}

TEST_CASE_TEMPLATE("openpbr::subsurface_medium inverts van de Hulst's relation", T, float, double) {
    shade::openpbr_parameters<T> p;
    p.subsurface_radius = T(0.5);
    for (const double g : {0.0, 0.5, -0.3})
        for (const double color : {0.05, 0.3, 0.8, 0.99}) {
            p.subsurface_color = rgb<T>(T(color));
            p.subsurface_scatter_anisotropy = T(g);
            const auto m = shade::openpbr::subsurface_medium(p);
            // Forward: C = (1 - s)(1 - 0.139 s) / (1 + 1.17 s), s = sqrt((1 - a) / (1 - a g)); the
            // inversion's constants are the quadratic's roots to 6 digits.
            const double a = double(m.albedo.x);
            const double s = std::sqrt((1 - a) / (1 - a * g));
            CHECK((1 - s) * (1 - 0.139 * s) / (1 + 1.17 * s) == doctest::Approx(color).epsilon(2e-4).scale(1));
        }
    // Mean free paths radius * scale = (0.5, 0.25, 0.125): sigma_t = (2, 4, 8).
    const auto m = shade::openpbr::subsurface_medium(p);
    CHECK(double(m.sigma_t.x) == doctest::Approx(2));
    CHECK(double(m.sigma_t.z) == doctest::Approx(8));
    p.subsurface_radius = T(0);
    CHECK(std::isfinite(shade::openpbr::subsurface_medium(p).sigma_t.x));
}

TEST_CASE_TEMPLATE("openpbr::dispersed_ior follows Cauchy through n_d with the Abbe number", T, float, double) {
    shade::openpbr_parameters<T> p;
    CHECK(std::isinf(shade::openpbr::abbe_number(p))); // scale 0: no dispersion
    CHECK(shade::openpbr::dispersed_ior(T(1.5), shade::openpbr::abbe_number(p), T(450)) == T(1.5));
    p.transmission_dispersion_scale = T(0.5);
    const T v = shade::openpbr::abbe_number(p);
    CHECK(double(v) == doctest::Approx(40));
    const double n_d = double(shade::openpbr::dispersed_ior(T(1.5), v, T(587.6)));
    const double n_f = double(shade::openpbr::dispersed_ior(T(1.5), v, T(486.1)));
    const double n_c = double(shade::openpbr::dispersed_ior(T(1.5), v, T(656.3)));
    CHECK(n_d == doctest::Approx(1.5).epsilon(1e-6));
    CHECK((n_d - 1) / (n_f - n_c) == doctest::Approx(40).epsilon(1e-3));
    CHECK(n_f > n_d); // normal dispersion: blue bends more
}

TEST_CASE_TEMPLATE("openpbr::transmission_medium at a subnormal depth: capped extinction, exact albedo, no NaN", T,
                   float, double) {
    // transmission_color 1, scatter 0.5, depth lambda subnormal: sigma_t lambda = -ln 1 = 0,
    // sigma_s lambda = 0.5, sigma_a lambda = -0.5 shifted to 0, so sigma_t = 0.5 / lambda
    // (beyond the largest T: capped there) and the albedo sigma_s / sigma_t = 1 exactly.
    // Dividing by lambda first gave sigma_a = 0 - inf and a shift of inf - inf: NaN.
    shade::openpbr_parameters<T> p;
    p.transmission_weight = T(1);
    p.transmission_color = rgb<T>(1);
    p.transmission_scatter = rgb<T>(T(0.5));
    p.transmission_depth = std::numeric_limits<T>::denorm_min() * T(64);
    const auto m = shade::openpbr::transmission_medium(p);
    CHECK(m.present);
    for (int c = 0; c < 3; ++c) {
        CHECK(m.sigma_t[c] == std::numeric_limits<T>::max());
        CHECK(m.albedo[c] == T(1));
    }
    // Colour 0.5, scatter 0: sigma_t lambda = ln 2, albedo 0; at lambda 1e-3 sigma_t = 693.1.
    p.transmission_color = rgb<T>(T(0.5));
    p.transmission_scatter = rgb<T>(0);
    p.transmission_depth = T(1e-3);
    const auto n = shade::openpbr::transmission_medium(p);
    CHECK(double(n.sigma_t.x) == doctest::Approx(std::log(2.0) / 1e-3).epsilon(1e-6));
    CHECK(n.albedo.x == T(0));
}

TEST_CASE_TEMPLATE("openpbr::dispersed_ior stays in [1e-4, 1e4] for an extreme Abbe number", T, float, double) {
    // V_d 1e-6: B = 0.5 / (1e-6 (486.1^-2 - 656.3^-2)) ~ 2.6e11 nm^2, so Cauchy's n(780 nm) =
    // 1.5 - B (587.6^-2 - 780^-2) ~ -3e5: clamped to 1e-4; n(380 nm) ~ +1e6: clamped to 1e4.
    CHECK(shade::openpbr::dispersed_ior(T(1.5), T(1e-6), T(780)) == T(1e-4));
    CHECK(shade::openpbr::dispersed_ior(T(1.5), T(1e-6), T(380)) == T(1e4));
    // n_d at the d line itself, in double (float's 587.6 is 2.4e-5 nm off it, where the
    // slope -2 B / lambda^3 is -2.6e3 per nm).
    CHECK(shade::openpbr::dispersed_ior(1.5, 1e-6, 587.6) == doctest::Approx(1.5).epsilon(1e-6));
}
