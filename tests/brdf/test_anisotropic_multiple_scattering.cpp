// shade::kulla_conty_anisotropic (shade/brdf/anisotropic_multiple_scattering.hpp): the white
// furnace of compensated anisotropic GGX and Beckmann conductors with F = 1 over view
// azimuths and cosines (issue #31: albedo in [0.99, 1.001] at every azimuth and mu >= 0.1,
// at 2:1 and 10:1), where kulla_conty (the tables read at sqrt(alpha_x alpha_y)) departs
// from 1 both ways; exact reciprocity; identical values to kulla_conty when isotropic;
// E_avg the average of the E(w) the lobe uses; and every check of the property kit.
//
// The white furnace is split into the two lobes of the compensated model, each estimated
// through f only: the single-scattering lobe's albedo E(v) with the visible-normal sampler of
// a separate single-scattering model (shade::check::sampled_albedo, 224^2 strata: its weight
// G2 / G1 is in [0, 1], and the standard error, a conservative collapsed-strata estimate, is
// about 1.2e-4 and below 2.5e-4 at every view, asserted), and the
// multiple-scattering lobe's albedo integral (f_compensated - f_single)(l, v) (n·l) dl by the
// midpoint rule in (sqrt(n·l), azimuth) on 64 x 64 cells, f_ms being smooth in l. The sum
// is the albedo with F = 1.

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/brdf/anisotropic_multiple_scattering.hpp>
#include <shade/brdf/cook_torrance.hpp>
#include <shade/check/energy.hpp>

#include "brdf/properties_support.hpp"
#include "brdf/support.hpp"

using namespace brdf_test;
namespace form = shade::cook_torrance_form;

namespace {

template <class D>
using compensated = shade::cook_torrance<D, shade::schlick<shade::scalar_of<D>>,
                                         shade::smith_height_correlated<shade::scalar_of<D>>, form::walter,
                                         shade::kulla_conty_anisotropic>;
template <class D>
using geometric_mean = shade::cook_torrance<D, shade::schlick<shade::scalar_of<D>>,
                                            shade::smith_height_correlated<shade::scalar_of<D>>, form::walter,
                                            shade::kulla_conty>;
template <class D>
using single = shade::cook_torrance<D, shade::schlick<shade::scalar_of<D>>,
                                    shade::smith_height_correlated<shade::scalar_of<D>>>;

static_assert(shade::sampled_brdf<compensated<shade::ggx<float>>> && shade::split_brdf<compensated<shade::beckmann<double>>>);

// integral (f(l, v) - f_single(l, v)) (n·l) dl over the hemisphere of l (local frame, v
// local): with mu = x^2, dl = 2 x dx dphi, the midpoint rule on 64 x 64 cells of
// (x, phi) in [0, 1] x [0, 2 pi).
template <class Model, class Single>
double multiple_scattering_albedo(const Model& model, const Single& single, const vec3<shade::scalar_of<Model>>& v) {
    using T = shade::scalar_of<Model>;
    const auto at = flat<T>();
    constexpr int cells = 64;
    double sum = 0;
    for (int i = 0; i < cells; ++i) {
        const double x = (i + 0.5) / cells, mu = x * x, s = std::sqrt((1 - mu) * (1 + mu));
        for (int k = 0; k < cells; ++k) {
            const double phi = (k + 0.5) / cells * 2 * shade::pi<double>;
            const vec3<T> l(T(s * std::cos(phi)), T(s * std::sin(phi)), T(mu));
            const double f_ms = double(model.f(l, v, at).x) - double(single.f(l, v, at).x);
            sum += f_ms * mu * 2 * x;
        }
    }
    return sum * (2 * shade::pi<double>) / (double(cells) * cells);
}

template <class T>
vec3<T> view(double mu, double phi_degrees) {
    const double phi = phi_degrees * shade::pi<double> / 180, s = std::sqrt((1 - mu) * (1 + mu));
    return glm::normalize(vec3<T>(T(s * std::cos(phi)), T(s * std::sin(phi)), T(mu)));
}

constexpr double furnace_cosines[] = {0.1, 0.3, 0.6, 1.0};
constexpr double furnace_azimuths[] = {0, 15, 30, 45, 60, 75, 90}; // degrees from t

// The acceptance of issue #31 for one lobe: albedo in [0.99, 1.001] at every azimuth and
// cosine; returns the lowest and highest albedo of kulla_conty (the geometric-mean tables)
// over the same views, which the caller compares.
template <class D>
std::pair<double, double> expect_white_furnace(const D& d) {
    using T = shade::scalar_of<D>;
    const shade::schlick<T> one(rgb<T>(1));
    const compensated<D> model(d, one);
    const geometric_mean<D> old(d, one);
    const single<D> lobe(d, one);
    double lowest = 2, highest = 0;
    for (const double mu : furnace_cosines)
        for (const double phi : furnace_azimuths) {
            if (mu == 1.0 && phi > 0) continue; // one view at the pole
            CAPTURE(mu);
            CAPTURE(phi);
            const vec3<T> v = view<T>(mu, phi);
            const auto e = shade::check::sampled_albedo(lobe, v, flat<T>(), 224, 11);
            CHECK(e.standard_error.x < 2.5e-4);
            const double total = e.albedo.x + multiple_scattering_albedo(model, lobe, v);
            CHECK(total >= 0.99);
            CHECK(total <= 1.001);
            const double total_old = e.albedo.x + multiple_scattering_albedo(old, lobe, v);
            lowest = std::min(lowest, total_old);
            highest = std::max(highest, total_old);
        }
    return {lowest, highest};
}

} // namespace

TEST_CASE_TEMPLATE("kulla_conty_anisotropic: GGX at 2:1 and 10:1 with F = 1 reflects 0.99 to 1.001 at every azimuth", T,
                   float, double) {
    for (const auto& roughness : {std::pair{0.2, 0.4}, std::pair{0.4, 0.2}, std::pair{0.05, 0.5}}) {
        const double a_x = roughness.first, a_y = roughness.second;
        CAPTURE(a_x);
        CAPTURE(a_y);
        const auto [lowest, highest] = expect_white_furnace(shade::ggx<T>(T(a_x), T(a_y)));
        // kulla_conty at the geometric mean misses the window at these anisotropies, below
        // (views along the smoother axis) and above (across it): measured 0.946 to 1.024 at 2:1,
        // 0.85 to 1.027 at 10:1.
        CHECK(lowest < 0.99);
        CHECK(highest > 1.001);
    }
}

TEST_CASE_TEMPLATE("kulla_conty_anisotropic: Beckmann at 2:1 and 10:1 with F = 1 reflects 0.99 to 1.001 at every azimuth",
                   T, float, double) {
    for (const auto& roughness : {std::pair{0.2, 0.4}, std::pair{0.5, 0.05}}) {
        const double m_x = roughness.first, m_y = roughness.second;
        CAPTURE(m_x);
        CAPTURE(m_y);
        const auto [lowest, highest] = expect_white_furnace(shade::beckmann<T>(T(m_x), T(m_y)));
        CHECK(lowest < 0.99);
        CHECK(highest > 1.001);
    }
}

TEST_CASE_TEMPLATE("kulla_conty_anisotropic: beyond 20:1, to a 1-D rough surface, F = 1 reflects 0.99 to 1.001 at every azimuth",
                   T, float, double) {
    // The strong-anisotropy tables: GGX at 50:1 and 300:1, and OpenPBR's anisotropy 1
    // (openpbr::roughness_to_alpha: alpha_t = sqrt 2 r^2, alpha_b = 0, held at the smallest
    // alpha 1e-4) at roughness 0.5 and 1; Beckmann at 100:1. Before these tables the ratio was
    // read as 20:1 and, at anisotropy 1, roughness 1, the albedo fell to 0.38 at normal
    // incidence.
    for (const auto& roughness : {std::pair{0.6, 0.012}, std::pair{0.003, 0.9}, std::pair{0.3535533905932738, 1e-4},
                                  std::pair{1.4142135623730951, 1e-4}}) {
        const double a_x = roughness.first, a_y = roughness.second;
        CAPTURE(a_x);
        CAPTURE(a_y);
        // kulla_conty at the geometric mean reads a near-mirror's E_avg and loses most of the
        // energy the lobe does not reflect once.
        CHECK(expect_white_furnace(shade::ggx<T>(T(a_x), T(a_y))).first < 0.99);
    }
    CHECK(expect_white_furnace(shade::beckmann<T>(T(0.005), T(0.5))).first < 0.99);
}

TEST_CASE_TEMPLATE("kulla_conty_anisotropic: isotropic lobes give exactly kulla_conty's values", T, float, double) {
    const rgb<T> gold(T(1.0), T(0.71), T(0.29));
    const auto at = tilted<T>();
    const auto same = [&](const auto& a, const auto& b) {
        for (int i = 0; i < 200; ++i) {
            const vec3<T> l = direction(at, T(0.0075 * i), T(0.37 * i));
            const vec3<T> v = direction(at, T(1.5 - 0.007 * i), T(1.3 + 0.11 * i));
            CHECK(a.f(l, v, at) == b.f(l, v, at));
            CHECK(a.pdf(l, v, at) == b.pdf(l, v, at));
        }
        CHECK(a.average_single_scattering_albedo() == b.average_single_scattering_albedo());
    };
    for (const double alpha : {0.05, 0.3, 1.0}) {
        same(compensated<shade::ggx<T>>(shade::ggx<T>(T(alpha)), shade::schlick<T>(gold)),
             geometric_mean<shade::ggx<T>>(shade::ggx<T>(T(alpha)), shade::schlick<T>(gold)));
        same(compensated<shade::beckmann<T>>(shade::beckmann<T>(T(alpha)), shade::schlick<T>(gold)),
             geometric_mean<shade::beckmann<T>>(shade::beckmann<T>(T(alpha)), shade::schlick<T>(gold)));
    }
}

TEST_CASE_TEMPLATE("kulla_conty_anisotropic: f is exactly reciprocal, E_avg is the average of its E(w)", T, float,
                   double) {
    const rgb<T> one(1);
    const auto at = tilted<T>();
    for (const auto& roughness : {std::pair{0.05, 0.5}, std::pair{0.6, 0.15}, std::pair{0.3, 0.9}, std::pair{0.9, 0.01},
                                  std::pair{1e-4, 1.2}}) {
        const double a_x = roughness.first, a_y = roughness.second;
        CAPTURE(a_x);
        const compensated<shade::ggx<T>> model{shade::ggx<T>(T(a_x), T(a_y)), shade::schlick<T>(one)};
        for (int i = 0; i < 100; ++i) {
            const vec3<T> a = direction(at, T(0.015 * i), T(0.37 * i));
            const vec3<T> b = direction(at, T(1.5 - 0.014 * i), T(1.3 + 0.11 * i));
            CHECK(model.f(a, b, at) == model.f(b, a, at));
        }
        // (1 / pi) integral E(w) (n·w) dw over the hemisphere = (2 / pi) integral_0^(pi/2) dphi
        // 4 integral_0^1 E x^3 dx with mu = x^2, by the midpoint rule on 400 x 400 cells (E is
        // piecewise smooth; the rule's error is below 1e-5 here). The lobe's E_avg must match
        // to the float rounding of the table sums: otherwise the albedo at every view is off by
        // (1 - E(v)) times the mismatch over 1 - E_avg.
        double sum = 0;
        constexpr int cells = 400;
        for (int i = 0; i < cells; ++i) {
            const double phi = (i + 0.5) / cells * shade::pi<double> / 2;
            for (int k = 0; k < cells; ++k) {
                const double x = (k + 0.5) / cells, mu = x * x, s = std::sqrt((1 - mu) * (1 + mu));
                const vec3<T> w(T(s * std::cos(phi)), T(s * std::sin(phi)), T(mu));
                sum += double(model.single_scattering_albedo(w)) * 4 * x * x * x / cells / cells;
            }
        }
        CHECK(double(model.average_single_scattering_albedo()) == doctest::Approx(sum).epsilon(2e-5));
    }
}

TEST_CASE_TEMPLATE("kulla_conty_anisotropic: every property check passes on compensated anisotropic GGX and Beckmann", T,
                   float, double) {
    const rgb<T> one(1), gold(T(1.0), T(0.71), T(0.29));
    const auto run = [](const auto& model, const std::string& name) { expect_every_property(model, name, 36); };
    run(compensated<shade::ggx<T>>(shade::ggx<T>(T(0.1), T(0.5)), shade::schlick<T>(gold)), "GGX 0.1 x 0.5, gold");
    run(compensated<shade::ggx<T>>(shade::ggx<T>(T(0.4), T(0.2)), shade::schlick<T>(gold)), "GGX 0.4 x 0.2, gold");
    run(compensated<shade::beckmann<T>>(shade::beckmann<T>(T(0.2), T(0.4)), shade::schlick<T>(one), rgb<T>(T(0.5)),
                                        rgb<T>(T(0.5))),
        "Beckmann 0.2 x 0.4, k_s = k_d = 0.5");
}
