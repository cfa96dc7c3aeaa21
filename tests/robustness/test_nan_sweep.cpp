// The deterministic NaN sweep (docs/robustness.md): every reflection model, shader and
// combinator, evaluated on a fixed grid of directions that contains the degenerate cases
// (l = n, grazing l or v, l = v, l = -v, directions below the horizon, h parallel to n),
// with extreme but valid parameters (microfacet roughness 1e-4 and 1, exponents 0 and
// 1e4, reflectances 0 and 1, Fresnel f0 0 and 1, eta tiny, 1 and huge), in float and
// double. Every output must be finite and >= 0 in every channel, and a BRDF must be
// exactly 0 when l or v is not above the surface (shade/brdf/brdf.hpp).
//
// Where the fuzz targets (fuzz/) search the input space at random, this test pins the
// known-dangerous corners so that a regression fails the ordinary unit-test run.

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <tuple>
#include <vector>

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/brdf/ashikhmin_shirley.hpp>
#include <shade/brdf/blinn_phong.hpp>
#include <shade/brdf/cook_torrance.hpp>
#include <shade/brdf/fresnel.hpp>
#include <shade/brdf/lambert.hpp>
#include <shade/brdf/microfacet.hpp>
#include <shade/brdf/eon.hpp>
#include <shade/brdf/oren_nayar.hpp>
#include <shade/brdf/phong.hpp>
#include <shade/light/any_light.hpp>
#include <shade/shading/checker.hpp>
#include <shade/shading/gooch.hpp>
#include <shade/shading/gradient.hpp>
#include <shade/shading/shader.hpp>
#include <shade/shading/sum_over_lights.hpp>
#include <shade/shading/toon.hpp>

namespace {

template <class T>
using v3 = shade::vec3<T>;

/// The local directions of the grid (n = +z), each normalised, and their negatives. They
/// contain n itself, exact and nearly grazing directions (z = 0 and z = 1e-7 before
/// normalisation), directions below the horizon, and mirror pairs (x, y, z) / (-x, -y, z),
/// so that the pairs (l, v) of the grid include l = n, l = v, l = -v, grazing l and v,
/// l or v below the horizon and h = n.
template <class T>
std::vector<v3<T>> local_directions() {
    const std::vector<v3<T>> base{
        v3<T>(0, 0, 1),           v3<T>(1, 0, 0),          v3<T>(0, 1, 0),
        v3<T>(1, 0, T(1e-7)),     v3<T>(0, 1, T(-1e-7)),   v3<T>(T(0.6), 0, T(0.8)),
        v3<T>(T(-0.6), 0, T(0.8)), v3<T>(0, T(0.6), T(0.8)), v3<T>(T(0.48), T(0.64), T(0.6)),
        v3<T>(T(-0.48), T(-0.64), T(0.6)), v3<T>(1, 1, T(1e-4)), v3<T>(T(1e-4), 0, 1),
        v3<T>(1, 2, 3)};
    std::vector<v3<T>> out;
    for (const auto& d : base) {
        out.push_back(glm::normalize(d));
        out.push_back(-glm::normalize(d));
    }
    return out;
}

/// The shading frames of the sweep: the canonical one (n = +z) and a tilted one (n along
/// (1, 2, 3), tangent from Gram-Schmidt), so world-space rounding is exercised too.
template <class T>
std::vector<shade::surface_point<T>> points() {
    shade::surface_point<T> flat;
    shade::surface_point<T> tilted;
    tilted.p = v3<T>(T(0.25), T(-1.5), T(3));
    tilted.shading = shade::frame<T>::from_normal_tangent(v3<T>(1, 2, 3), v3<T>(1, 0, 0));
    return {flat, tilted};
}

template <class T>
bool finite_non_negative(const shade::rgb<T>& c) {
    return std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z) && c.x >= T(0) &&
           c.y >= T(0) && c.z >= T(0);
}

template <class T>
std::string text(const v3<T>& w) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "(%.9g, %.9g, %.9g)", double(w.x), double(w.y), double(w.z));
    return buf;
}

/// Evaluates b (and its diffuse and specular parts, if split) on every (at, l, v) of the
/// grid. Counts the failures and reports the first, so one CHECK covers ~1300 evaluations.
template <class B>
void sweep_brdf(const B& b, const std::string& name) {
    using T = shade::scalar_of<B>;
    int failures = 0;
    std::string first;
    for (const auto& at : points<T>()) {
        for (const auto& l_local : local_directions<T>()) {
            for (const auto& v_local : local_directions<T>()) {
                const v3<T> l = at.shading.to_world(l_local);
                const v3<T> v = at.shading.to_world(v_local);
                const shade::rgb<T> f = b.f(l, v, at);
                bool ok = finite_non_negative(f);
                const bool below = !(glm::dot(at.n(), l) > T(0)) || !(glm::dot(at.n(), v) > T(0));
                if (below) ok = ok && f == shade::rgb<T>(0);
                if constexpr (shade::split_brdf<B>) {
                    ok = ok && finite_non_negative(b.f_diffuse(l, v, at)) &&
                         finite_non_negative(b.f_specular(l, v, at));
                }
                if (!ok && failures++ == 0)
                    first = "l = " + text(l) + ", v = " + text(v) + ", n = " + text(at.n()) +
                            ": f = " + text(f);
            }
        }
    }
    CAPTURE(name);
    CAPTURE(first);
    CHECK(failures == 0);
}

/// Shades with s for every (at, v) of the grid and a unit light sample toward every l of
/// the grid (colours 1, ambient 0.5), and also through sum_over_lights with one light of
/// each kind, one of them placed exactly at the shaded point. All finite and >= 0.
template <class S>
void sweep_shader(const S& s, const std::string& name) {
    using T = shade::scalar_of<S>;
    int failures = 0;
    std::string first;
    for (const auto& at : points<T>()) {
        for (const auto& l_local : local_directions<T>()) {
            for (const auto& v_local : local_directions<T>()) {
                shade::light_sample<T> sample;
                sample.l = at.shading.to_world(l_local);
                sample.distance = T(1);
                sample.ambient = shade::rgb<T>(T(0.5));
                sample.diffuse = shade::rgb<T>(1);
                sample.specular = shade::rgb<T>(1);
                const v3<T> v = at.shading.to_world(v_local);
                const shade::rgb<T> c = shade::shade_of(s, at, v, sample);
                if (!finite_non_negative(c) && failures++ == 0)
                    first = "l = " + text(sample.l) + ", v = " + text(v) + ": " + text(c);
            }
        }
        shade::emission<T> e;
        e.ambient = shade::rgb<T>(T(0.25));
        const std::tuple lights{
            shade::directional_light<T>(v3<T>(0, 0, 1), e),
            shade::point_light<T>(at.p, e), // at the shaded point: ambient only
            shade::point_light<T>(at.p + at.n(), e),
            shade::spot_light<T>(at.p + at.n() * T(2), -at.n(), T(0.1), T(0.5), e),
            shade::area_light<T>(at.p - v3<T>(1, 1, 0), v3<T>(2, 0, 0), v3<T>(0, 2, 0), e,
                                 shade::sidedness::two_sided)};
        for (const auto& v_local : local_directions<T>()) {
            const v3<T> v = at.shading.to_world(v_local);
            const shade::rgb<T> c = shade::sum_over_lights(s, at, v, lights);
            if (!finite_non_negative(c) && failures++ == 0)
                first = "sum_over_lights, v = " + text(v) + ": " + text(c);
        }
    }
    CAPTURE(name);
    CAPTURE(first);
    CHECK(failures == 0);
}

template <class T>
const shade::rgb<T> one{1, 1, 1};
template <class T>
const shade::rgb<T> zero{0, 0, 0};

/// Cook-Torrance with distribution D (roughness r), masking G and form F, for every
/// Fresnel term of the sweep.
template <class D, class G, class Form, class T>
void sweep_cook_torrance(T roughness, const std::string& name) {
    const D d(roughness);
    for (const T f0 : {T(0), T(1)}) {
        const shade::cook_torrance<D, shade::schlick<T>, G, Form> b(
            d, shade::schlick<T>(shade::rgb<T>(f0)), one<T>, one<T>);
        sweep_brdf(b, name + ", schlick f0 = " + std::to_string(f0));
    }
    for (const T eta : {std::numeric_limits<T>::min(), T(1e-3), T(1), T(1.5), T(1e4),
                        std::numeric_limits<T>::max()}) {
        const shade::cook_torrance<D, shade::dielectric_fresnel<T>, G, Form> b(
            d, shade::dielectric_fresnel<T>(eta), one<T>, zero<T>);
        sweep_brdf(b, name + ", dielectric eta = " + std::to_string(eta));
    }
}

template <class D, class Smith, class T>
void sweep_cook_torrance_all(const std::string& name) {
    using namespace shade::cook_torrance_form;
    for (const T r : {T(1e-4), T(1)}) {
        const std::string rn = name + " r = " + std::to_string(r);
        sweep_cook_torrance<D, shade::v_groove<T>, walter>(r, rn + ", v_groove, walter");
        sweep_cook_torrance<D, shade::v_groove<T>, course>(r, rn + ", v_groove, course");
        sweep_cook_torrance<D, shade::v_groove<T>, paper_1982>(r, rn + ", v_groove, 1982");
        sweep_cook_torrance<D, Smith, walter>(r, rn + ", smith, walter");
        sweep_cook_torrance<D, Smith, course>(r, rn + ", smith, course");
        sweep_cook_torrance<D, Smith, paper_1982>(r, rn + ", smith, 1982");
    }
}

} // namespace

TEST_CASE_TEMPLATE("NaN sweep: Lambert", T, float, double) {
    sweep_brdf(shade::lambert<T>(zero<T>), "lambert k_d = 0");
    sweep_brdf(shade::lambert<T>(one<T>), "lambert k_d = 1");
}

TEST_CASE_TEMPLATE("NaN sweep: Phong, every form, shininess 0 and 1e4", T, float, double) {
    for (const T n : {T(0), T(1e4)}) {
        const std::string s = " shininess " + std::to_string(n);
        sweep_brdf(shade::phong<T, shade::phong_form::classic>(one<T>, one<T>, n), "classic" + s);
        sweep_brdf(shade::phong<T, shade::phong_form::modified>(one<T>, one<T>, n), "modified" + s);
        sweep_brdf(shade::phong<T, shade::phong_form::normalized>(one<T>, one<T>, n), "normalized" + s);
    }
}

TEST_CASE_TEMPLATE("NaN sweep: Blinn-Phong, every form, shininess 0 and 1e4", T, float, double) {
    using namespace shade::blinn_phong_form;
    for (const T n : {T(0), T(1e4)}) {
        const std::string s = " shininess " + std::to_string(n);
        sweep_brdf(shade::blinn_phong<T, classic>(one<T>, one<T>, n), "classic" + s);
        sweep_brdf(shade::blinn_phong<T, modified>(one<T>, one<T>, n), "modified" + s);
        sweep_brdf(shade::blinn_phong<T, normalized_rtr>(one<T>, one<T>, n), "normalized_rtr" + s);
        sweep_brdf(shade::blinn_phong<T, normalized_exact>(one<T>, one<T>, n), "normalized_exact" + s);
    }
}

TEST_CASE_TEMPLATE("NaN sweep: Cook-Torrance, every composition, roughness 1e-4 and 1", T, float,
                   double) {
    sweep_cook_torrance_all<shade::beckmann<T>, shade::smith_beckmann<T>, T>("beckmann");
    sweep_cook_torrance_all<shade::ggx<T>, shade::smith_ggx<T>, T>("ggx");
}

TEST_CASE_TEMPLATE("NaN sweep: Oren-Nayar, both evaluations, sigma 0 to 100", T, float, double) {
    for (const T sigma : {T(0), T(1e-4), T(1), T(100)}) {
        const std::string s = " sigma " + std::to_string(sigma);
        sweep_brdf(shade::oren_nayar<T>(one<T>, sigma), "trig_free" + s);
        sweep_brdf(shade::oren_nayar_trig<T>(one<T>, sigma), "trig" + s);
    }
}

TEST_CASE_TEMPLATE("NaN sweep: EON and FON, roughness 0 to 1, rho 0 and 1", T, float, double) {
    for (const T r : {T(0), T(1e-4), T(0.5), T(1)})
        for (const T rho : {T(0), T(1)}) {
            const std::string s = " roughness " + std::to_string(r) + " rho " + std::to_string(rho);
            sweep_brdf(shade::eon<T>(shade::rgb<T>(rho), r), "eon" + s);
            sweep_brdf(shade::eon<T, shade::eon_albedo::approximate>(shade::rgb<T>(rho), r), "eon (fit)" + s);
            sweep_brdf(shade::fujii_oren_nayar<T>(shade::rgb<T>(rho), r), "fon" + s);
        }
}

TEST_CASE_TEMPLATE("NaN sweep: Ashikhmin-Shirley, exponents 0 and 1e4, R_s 0 and 1", T, float,
                   double) {
    for (const T p_u : {T(0), T(1e4)})
        for (const T p_v : {T(0), T(1e4)})
            for (const T r_s : {T(0), T(1)})
                sweep_brdf(shade::ashikhmin_shirley<T>(one<T>, shade::rgb<T>(r_s), p_u, p_v),
                           "p_u " + std::to_string(p_u) + " p_v " + std::to_string(p_v) +
                               " r_s " + std::to_string(r_s));
}

TEST_CASE_TEMPLATE("NaN sweep: shaders (lit, toon, Gooch) and combinators (checker, gradient)", T,
                   float, double) {
    for (const T n : {T(1e-4), T(1e4)}) {
        const std::string s = " shininess " + std::to_string(n);
        sweep_shader(shade::lit{shade::blinn_phong<T>(one<T>, one<T>, n), shade::rgb<T>(T(0.5))},
                     "lit blinn_phong" + s);
        shade::toon_params<T> tp;
        tp.shininess = n;
        tp.diffuse_levels = 2;
        tp.specular_levels = 2;
        tp.ambient = one<T>;
        sweep_shader(shade::toon<T>(tp), "toon" + s);
        shade::gooch_params<T> gp;
        gp.shininess = n;
        gp.highlight = one<T>;
        sweep_shader(shade::gooch<T>(gp), "gooch" + s);
        sweep_shader(shade::checker(shade::lambert<T>(one<T>), shade::toon<T>(tp), T(0.5)),
                     "checker(lambert, toon)" + s);
        sweep_shader(shade::gradient(shade::gooch<T>(gp), shade::blinn_phong<T>(one<T>, one<T>, n),
                                     v3<T>(1, 1, 0), T(2)),
                     "gradient(gooch, blinn_phong)" + s);
        // A gradient of two BRDFs is a BRDF: sweep it as one, too.
        sweep_brdf(shade::gradient(shade::lambert<T>(one<T>), shade::blinn_phong<T>(one<T>, one<T>, n),
                                   v3<T>(0, 0, 1), T(1e-3)),
                   "gradient(lambert, blinn_phong) as a BRDF" + s);
    }
    using ct = shade::cook_torrance<shade::ggx<T>, shade::schlick<T>, shade::smith_ggx<T>>;
    sweep_shader(shade::lit{ct(shade::ggx<T>(T(1e-4)), shade::schlick<T>(one<T>), one<T>, one<T>)},
                 "lit cook_torrance ggx 1e-4");
}

