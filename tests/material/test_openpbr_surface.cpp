// shade::openpbr_surface: its value as the specification's mixture of the public lobes
// (built here by hand from the lobes), the white furnace of the specification's list, the
// chi-square test and the sample consistency at 28 parameter points covering every lobe,
// delta lobes at roughness 0, thin-walled symmetry, emission, the interior medium and bad
// parameters.
#include <cmath>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/brdf/eon.hpp>
#include <shade/brdf/microfacet/cosine_weights.hpp>
#include <shade/brdf/sheen.hpp>
#include <shade/bsdf/dielectric_anisotropic_reflection_albedo.hpp>
#include <shade/bsdf/dielectric_reflection_albedo.hpp>
#include <shade/check/bsdf_energy.hpp>
#include <shade/check/bsdf_reciprocity.hpp>
#include <shade/check/chi2.hpp>
#include <shade/check/doctest.hpp>
#include <shade/check/sampling.hpp>
#include <shade/core/error.hpp>
#include <shade/core/random.hpp>
#include <shade/material/openpbr_surface.hpp>

#include "bsdf/dielectric_albedo.hpp"
#include "bsdf/support.hpp"
#include "check/model_point.hpp"
#include "full.hpp"
#include "material/openpbr_film.hpp"

namespace {

using shade::rgb;
using shade::vec2;
using shade::vec3;
template <class T>
using params = shade::openpbr_parameters<T>;
template <class T>
using surface = shade::openpbr_surface<T>;

// A parameter point of the sampling tests: its name, the parameters and the index the
// sample consistency check expects across a transmission (1 for a thin wall).
template <class T>
struct point {
    std::string name;
    params<T> p;
    double eta_inside;
};

template <class T>
params<T> white() {
    params<T> p;
    p.base_color = rgb<T>(1);
    return p;
}

// 28 points: every lobe alone and in company, rough and smooth, isotropic and anisotropic,
// thin-walled and solid.
template <class T>
std::vector<point<T>> sampling_points() {
    std::vector<point<T>> out;
    const auto add = [&](std::string name, params<T> p) {
        const double eta = p.geometry_thin_walled || p.transmission_weight == T(0) ? 1.0 : double(p.specular_ior);
        out.push_back({std::move(name), p, eta});
    };
    params<T> p;
    add("default", p);
    p.base_diffuse_roughness = T(1);
    p.specular_roughness = T(0.8);
    add("rough diffuse (EON r = 1)", p);
    p = {};
    p.base_metalness = T(1);
    p.base_color = rgb<T>(T(0.95), T(0.7), T(0.3));
    p.specular_color = rgb<T>(T(0.9), T(0.8), T(0.6));
    add("gold F82", p);
    p.specular_roughness = T(0.5);
    p.specular_roughness_anisotropy = T(0.8);
    add("brushed metal (anisotropic)", p);
    p.specular_roughness = T(0);
    p.specular_roughness_anisotropy = T(0);
    add("mirror metal (delta)", p);
    p = {};
    p.coat_weight = T(1);
    p.coat_roughness = T(0.1);
    p.base_color = rgb<T>(T(0.8), T(0.1), T(0.1));
    add("coated plastic", p);
    p.coat_roughness = T(0);
    add("smooth coat (delta) over plastic", p);
    p = {};
    p.base_metalness = T(1);
    p.base_color = rgb<T>(T(0.7), T(0.1), T(0.1));
    p.coat_weight = T(1);
    p.coat_roughness = T(0.2);
    p.coat_roughness_anisotropy = T(0.5);
    p.coat_color = rgb<T>(T(0.9), T(0.8), T(0.8));
    add("car paint", p);
    p = {};
    p.fuzz_weight = T(1);
    p.fuzz_roughness = T(0.6);
    p.fuzz_color = rgb<T>(T(0.9), T(0.3), T(0.5));
    p.base_color = rgb<T>(T(0.5), T(0.1), T(0.2));
    add("velvet (fuzz)", p);
    p = {};
    p.thin_film_weight = T(1);
    p.thin_film_thickness = T(0.4);
    p.specular_roughness = T(0.2);
    add("thin film over dielectric", p);
    p.base_metalness = T(1);
    add("thin film over metal", p);
    p = {};
    p.transmission_weight = T(1);
    p.specular_roughness = T(0);
    add("glass (delta)", p);
    p.specular_roughness = T(0.3);
    add("frosted glass", p);
    p.specular_roughness = T(0.9);
    p.specular_roughness_anisotropy = T(0.6);
    add("rough anisotropic glass", p);
    p.specular_roughness = T(0.2);
    p.specular_roughness_anisotropy = T(0);
    p.transmission_color = rgb<T>(T(0.6), T(0.9), T(0.7));
    p.specular_color = rgb<T>(T(0.8), T(0.9), T(1));
    p.specular_weight = T(0.6);
    add("tinted glass, modulated specular", p);
    p = {};
    p.transmission_weight = T(1);
    p.geometry_thin_walled = true;
    p.specular_roughness = T(0.4);
    add("thin-walled rough glass", p);
    p.specular_roughness = T(0);
    p.thin_film_weight = T(1);
    p.thin_film_thickness = T(0.3);
    add("soap bubble (thin film, thin-walled, delta)", p);
    p = {};
    p.subsurface_weight = T(1);
    p.subsurface_color = rgb<T>(T(0.9), T(0.8), T(0.6));
    add("subsurface (wax)", p);
    p.geometry_thin_walled = true;
    p.subsurface_scatter_anisotropy = T(0.3);
    add("thin-walled subsurface (paper)", p);
    p = {};
    p.geometry_opacity = T(0.5);
    add("half opacity", p);
    p = {};
    p.base_metalness = T(0.3);
    p.transmission_weight = T(0.4);
    p.subsurface_weight = T(0.5);
    p.coat_weight = T(0.6);
    p.coat_roughness = T(0.3);
    p.fuzz_weight = T(0.5);
    p.thin_film_weight = T(0.5);
    add("every lobe at once", p);
    p.specular_roughness = T(0);
    p.coat_roughness = T(0);
    add("every lobe at once, smooth", p);
    // A pass-through crosses with eta 1 and a refraction with specular_ior, so partial
    // opacity with transmission is checked on a thin wall, where both have eta 1.
    p.specular_roughness = T(0.3);
    p.geometry_thin_walled = true;
    p.geometry_opacity = T(0.7);
    add("every lobe at once, thin-walled, partly transparent", p);
    p = {};
    p.specular_roughness = T(1);
    p.coat_weight = T(1);
    p.coat_roughness = T(1);
    p.fuzz_weight = T(1);
    p.fuzz_roughness = T(1);
    add("everything at roughness 1", p);
    p = {};
    p.transmission_weight = T(1);
    p.specular_roughness = T(0.25);
    p.coat_weight = T(1);
    p.coat_roughness = T(0.05);
    add("coated rough glass", p);
    p = {};
    p.base_metalness = T(1);
    p.specular_roughness = T(0.35);
    p.fuzz_weight = T(0.8);
    p.fuzz_roughness = T(0.3);
    add("fuzz over rough metal", p);
    p = {};
    p.specular_ior = T(1.0);
    p.transmission_weight = T(1);
    p.specular_roughness = T(0.3);
    add("index-matched interface", p);
    p = {};
    p.specular_ior = T(1) / T(1.5);
    p.transmission_weight = T(1);
    p.specular_roughness = T(0.3);
    add("rough glass of index ratio below 1 (the interface drawn whole)", p);
    return out;
}

// The white-furnace reading of the material at view v: the mean, over strata^2
// stratified draws in radiance mode, of weight * eta^2. In a uniform environment of
// radiance L outside a solid of index eta, the radiance inside is eta^2 L (Veach 1997,
// sec. 5.2: L / eta^2 is invariant), so a camera looking along v sees L times this; 1 is
// invisible. A reflection has eta = 1. Returns the mean and its standard error.
template <class T>
std::pair<double, double> furnace(const surface<T>& m, const vec3<T>& v, const shade::surface_point<T>& at,
                                  int strata = 128) {
    shade::rng random(11);
    double sum = 0, sum2 = 0;
    const int n = strata * strata;
    // uc stratified on its own too, its n strata dealt to the strata of u in a random
    // order (Latin hypercube sampling), so the lobe choice adds little variance.
    std::vector<int> order(std::size_t(n), 0);
    for (int i = 0; i < n; ++i) order[std::size_t(i)] = i;
    for (int i = n - 1; i > 0; --i) std::swap(order[std::size_t(i)], order[random.next_u32() % std::uint32_t(i + 1)]);
    for (int i = 0; i < n; ++i) {
        const vec2<T> u(T((i % strata + random.uniform<double>()) / strata),
                        T((i / strata + random.uniform<double>()) / strata));
        const T uc = T((order[std::size_t(i)] + random.uniform<double>()) / n);
        const auto s = m.sample(v, uc < T(1) ? uc : T(0), u, at);
        const double w = s ? double(s->weight.x) * double(s->eta) * double(s->eta) : 0.0;
        sum += w;
        sum2 += w * w;
    }
    const double mean = sum / n;
    return {mean, std::sqrt(std::max(sum2 / n - mean * mean, 0.0) / (n - 1))};
}

// The readings (mean, standard error) of a white-furnace test, each checked against the
// band [0.99, 1.001] within 4 standard errors of its estimate, and their range.
struct furnace_band {
    double low = 2, high = 0;
    void check(const std::pair<double, double>& reading) {
        CHECK(reading.first >= 0.99 - 4 * reading.second);
        CHECK(reading.first <= 1.001 + 4 * reading.second);
        low = std::min(low, reading.first);
        high = std::max(high, reading.first);
    }
};

// The white-furnace albedo of a model without delta lobes for v (outside, above at.n()),
// as an energy fraction: integral over the sphere of f(l, v) |n·l|, f in radiance mode
// times eta_across^2 for l on the far side (undoing the (1 / eta')^2 of radiance across
// the interface, Veach 1997, "Robust Monte Carlo Methods for Light Transport Simulation",
// eq. 5.14). An estimate whose error bar is small enough to test a band of 1e-3 at a sharp
// transmission lobe: u stratified in n^2 strata and, in each, the lobe choice integrated
// out over k_choice strata of uc (one sample() each, one random offset per u stratum),
// combined by the balance heuristic with k_cosine cosine-weighted directions over the
// sphere in sub-strata of the u stratum (Veach, Guibas 1995, "Optimally Combining Sampling
// Techniques for Monte Carlo Rendering", SIGGRAPH, the multi-sample model, eq. 4: each
// sample contributes f |n·l| / (k_choice pdf(l) + k_cosine |n·l| / (2 pi)) per u stratum),
// so the directions the model rarely draws (its diffuse-like multiple-scattering
// transmission at grazing) add no heavy tail. Returns the mean and the collapsed-strata
// standard error (neighbouring u strata paired). k_cosine a square.
template <class M, class T = shade::scalar_of<M>>
std::pair<double, double> furnace_stratified(const M& model, const vec3<T>& v, const shade::surface_point<T>& at,
                                             double eta_across, int n, int k_choice, int k_cosine) {
    shade::rng random(17);
    const vec3<T> normal = at.n();
    const int side = int(std::lround(std::sqrt(double(k_cosine))));
    const auto energy = [&](const vec3<T>& l, double f_radiance) {
        return glm::dot(normal, l) < T(0) ? f_radiance * eta_across * eta_across : f_radiance;
    };
    double sum = 0, pairs = 0, previous = 0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const vec2<T> u(T((i + random.uniform<double>()) / n), T((j + random.uniform<double>()) / n));
            double x = 0;
            const double offset = random.uniform<double>();
            for (int k = 0; k < k_choice; ++k) {
                const auto s = model.sample(v, T((k + offset) / k_choice), u, at);
                if (!s) continue;
                const double cos_l = std::abs(double(glm::dot(normal, s->l)));
                x += energy(s->l, double(s->f.x)) * cos_l /
                     (k_choice * double(s->pdf) + k_cosine * cos_l / (2 * shade::pi<double>));
            }
            for (int c = 0; c < k_cosine; ++c) {
                // Sub-stratum c of the u stratum; its x in [0, 1/2) draws above, [1/2, 1) below.
                const double wx = (i + (c % side + random.uniform<double>()) / side) / n;
                const double wy = (j + (c / side + random.uniform<double>()) / side) / n;
                const bool below = wx >= 0.5;
                vec3<T> local = shade::square_to_cosine_hemisphere(vec2<T>(T(below ? 2 * wx - 1 : 2 * wx), T(wy)));
                if (below) local.z = -local.z;
                const vec3<T> l = glm::normalize(at.shading.to_world(local));
                const double cos_l = std::abs(double(glm::dot(normal, l)));
                if (!(cos_l > 0)) continue;
                x += energy(l, double(model.f(l, v, at).x)) * cos_l /
                     (k_choice * double(model.pdf(l, v, at)) + k_cosine * cos_l / (2 * shade::pi<double>));
            }
            sum += x;
            if (j % 2 == 1) pairs += (x - previous) * (x - previous);
            previous = x;
        }
    const double strata = double(n) * double(n);
    return {sum / strata, std::sqrt(pairs) / strata};
}

// True when every draw of the model at v is a delta lobe's (no density to test).
template <class M, class T = shade::scalar_of<M>>
bool only_delta(const M& model, const vec3<T>& v, const shade::surface_point<T>& at) {
    shade::rng random(13);
    for (int i = 0; i < 2000; ++i) {
        const auto s = model.sample(v, random.uniform<T>(), vec2<T>(random.uniform<T>(), random.uniform<T>()), at);
        if (s && !shade::is_specular(s->flags)) return false;
    }
    return true;
}

template <class T>
vec3<T> view_at_cosine(const shade::surface_point<T>& at, double mu, double phi = 0.4) {
    const double s = std::sqrt(std::max(0.0, 1 - mu * mu));
    return glm::normalize(at.shading.to_world(vec3<T>(T(s * std::cos(phi)), T(s * std::sin(phi)), T(mu))));
}

} // namespace

TEST_CASE_TEMPLATE("openpbr_surface: the default material is the specification's mixture of its public lobes", T,
                   float, double) {
    // With no coat, fuzz, metal, transmission or subsurface, the reduction of the
    // specification (section "Reduction to a mixture of lobes") is
    //     f = f_spec + (1 - E_spec(v)) f_diffuse,
    // f_spec the GGX reflection with specular_color times the exact Fresnel of the index
    // specular_ior (specular_weight 1 leaves it), E_spec its albedo
    // (dielectric_reflection_albedo times specular_color), f_diffuse EON of base_weight
    // base_color. Built here from the lobes directly.
    params<T> p;
    p.base_color = rgb<T>(T(0.7), T(0.5), T(0.3));
    p.specular_color = rgb<T>(T(1), T(0.9), T(0.8));
    p.specular_roughness = T(0.4);
    p.base_diffuse_roughness = T(0.5);
    const surface<T> m(p);
    const auto at = check_test::model_point<T>();
    const T alpha = T(0.16);
    const shade::microfacet_reflection<shade::ggx<T>, shade::dielectric_fresnel<T>,
                                       shade::smith_height_correlated<T>>
        spec(shade::ggx<T>(alpha), shade::dielectric_fresnel<T>(T(1.5)));
    const shade::eon<T> diffuse(p.base_color, T(0.5));
    shade::rng random(3);
    const T tol = sizeof(T) == 4 ? T(2e-5) : T(1e-12);
    for (int i = 0; i < 200; ++i) {
        const vec3<T> l = view_at_cosine(at, 0.02 + 0.98 * random.uniform<double>(), 6.28 * random.uniform<double>());
        const vec3<T> v = view_at_cosine(at, 0.02 + 0.98 * random.uniform<double>(), 6.28 * random.uniform<double>());
        const T mu_v = glm::dot(at.n(), v);
        const rgb<T> e_spec = p.specular_color * shade::dielectric_reflection_albedo(mu_v, alpha, T(1.5));
        const rgb<T> expected = p.specular_color * spec.f(l, v, at) + (rgb<T>(1) - e_spec) * diffuse.f(l, v, at);
        const rgb<T> got = m.f(l, v, at);
        for (int c = 0; c < 3; ++c) CHECK(std::abs(got[c] - expected[c]) <= tol * (T(1) + expected[c]));
        // Transmission is absent: nothing below the surface.
        CHECK(m.f(-l, v, at) == rgb<T>(0));
    }
}

TEST_CASE_TEMPLATE("openpbr_surface: fuzz and coat layer by albedo scaling, a metal is its lobe", T, float, double) {
    const auto at = check_test::model_point<T>();
    shade::rng random(5);
    const T tol = sizeof(T) == 4 ? T(5e-5) : T(1e-11);
    // A full metal with no coat or fuzz: exactly the metal lobe (F82-tint, compensated).
    params<T> metal = white<T>();
    metal.base_metalness = T(1);
    metal.base_color = rgb<T>(T(0.9), T(0.6), T(0.4));
    metal.specular_roughness = T(0.5);
    const surface<T> m(metal);
    const typename surface<T>::metal_lobe lobe(
        shade::ggx<T>(T(0.25)), shade::openpbr::surface_fresnel<T>::metal(
                                    shade::f82_tint<T>(metal.base_color, rgb<T>(1), T(1)), T(0),
                                    shade::thin_film_fresnel<T>::over_dielectric(T(1.5), T(1.4), T(500))));
    // Fuzz over it: F f_fuzz + (1 - F E_fuzz(v)) f_metal (section "Fuzz", the albedo scaling
    // with the fuzz's white albedo).
    params<T> fuzzy = metal;
    fuzzy.fuzz_weight = T(0.7);
    fuzzy.fuzz_color = rgb<T>(T(0.5), T(0.9), T(0.2));
    fuzzy.fuzz_roughness = T(0.4);
    const surface<T> fz(fuzzy);
    const shade::zeltner_sheen<T> sheen(fuzzy.fuzz_color, T(0.4));
    for (int i = 0; i < 200; ++i) {
        const vec3<T> l = view_at_cosine(at, 0.02 + 0.98 * random.uniform<double>(), 6.28 * random.uniform<double>());
        const vec3<T> v = view_at_cosine(at, 0.02 + 0.98 * random.uniform<double>(), 6.28 * random.uniform<double>());
        const rgb<T> expected = lobe.f(l, v, at);
        const rgb<T> got = m.f(l, v, at);
        for (int c = 0; c < 3; ++c) CHECK(std::abs(got[c] - expected[c]) <= tol * (T(1) + expected[c]));
        const T keep = T(1) - T(0.7) * sheen.albedo(glm::dot(at.n(), v));
        const rgb<T> layered = T(0.7) * sheen.f(l, v, at) + keep * expected;
        const rgb<T> got_fuzz = fz.f(l, v, at);
        for (int c = 0; c < 3; ++c) CHECK(std::abs(got_fuzz[c] - layered[c]) <= tol * (T(1) + layered[c]));
    }
}

TEST_CASE_TEMPLATE("openpbr_surface: white furnace over the specification's energy-conserving configurations", T,
                   float, double) {
    // Section "White furnace testing": with white colours and no absorption the material
    // disappears. Each layer passes on exactly what its top lobe does not reflect (1 - E),
    // so the reading is 1 up to the albedo tables; the issue's band is [0.99, 1.001] for
    // mu >= 0.1 at roughness 0 to 1. Allowed: the band widened by 4 standard errors of
    // the 128^2-draw estimate.
    const auto at = check_test::model_point<T>();
    struct config {
        std::string name;
        params<T> p;
    };
    std::vector<config> configs;
    const auto add = [&](std::string name, params<T> p) { configs.push_back({std::move(name), p}); };
    params<T> base = white<T>();
    add("diffuse", base);
    params<T> p = base;
    p.base_metalness = T(1);
    add("metal", p);
    p = base;
    p.subsurface_weight = T(1);
    p.subsurface_color = rgb<T>(1);
    add("subsurface", p);
    p = base;
    p.transmission_weight = T(1);
    add("translucent", p);
    p = base;
    p.transmission_weight = T(1);
    p.transmission_depth = T(1);
    p.transmission_color = rgb<T>(T(0.3));
    p.transmission_scatter = rgb<T>(1);
    add("translucent with white scatter (surface part)", p);
    p = base;
    p.base_metalness = T(0.4);
    p.transmission_weight = T(0.5);
    p.subsurface_weight = T(0.5);
    p.subsurface_color = rgb<T>(1);
    add("a mix of all bases", p);
    const std::size_t bases = configs.size();
    for (std::size_t i = 0; i < bases; ++i) {
        params<T> c = configs[i].p;
        c.coat_weight = T(1);
        add(configs[i].name + " + coat", c);
        c.fuzz_weight = T(1);
        add(configs[i].name + " + coat + fuzz", c);
    }
    p = base;
    p.transmission_weight = T(1);
    p.geometry_thin_walled = true;
    add("thin-walled translucent", p);
    p = base;
    p.geometry_opacity = T(0.4);
    p.coat_weight = T(0.5);
    add("partly transparent coated diffuse", p);

    double lowest = 2, highest = 0;
    std::string worst;
    for (const auto& c : configs) {
        for (const T r : {T(0), T(0.1), T(0.4), T(1)}) {
            params<T> q = c.p;
            q.specular_roughness = r;
            q.base_diffuse_roughness = r;
            q.coat_roughness = r;
            q.fuzz_roughness = r;
            const surface<T> m(q);
            for (const double mu : {1.0, 0.5, 0.2, 0.1}) {
                const auto reading = furnace(m, view_at_cosine(at, mu), at);
                const double mean = reading.first, error = reading.second;
                INFO(c.name, " roughness ", double(r), " mu ", mu, ": ", mean, " +- ", error);
                CHECK(mean >= 0.99 - 4 * error);
                CHECK(mean <= 1.001 + 4 * error);
                lowest = std::min(lowest, mean);
                if (mean > highest) {
                    highest = mean;
                    worst = c.name + " roughness " + std::to_string(double(r)) + " mu " + std::to_string(mu) +
                            " +- " + std::to_string(error);
                }
            }
        }
    }
    MESSAGE("white furnace: ", configs.size(), " configurations x 4 roughnesses x 4 views in [", lowest, ", ",
            highest, "], the highest at ", worst);
}

TEST_CASE_TEMPLATE("openpbr_surface: white furnace of an opaque dielectric beyond the tables' index 3", T, float,
                   double) {
    // specular_ior above 3, or specular_weight above 1 (which raises the index ratio: at
    // specular_ior 2.5 and weight 2, F0 0.37, eta'_s 4.1), put the specular lobe beyond the
    // reflection table's eta_hat 3. Over a white diffuse base, with and without a white coat,
    // the furnace is 1 + E_true - E_read (albedo scaling), the band [0.99, 1.001] within 4
    // standard errors of 96^2 draws. Reading the table's difference at 3 plus the exact F of
    // the true index gave 1.05-1.38 at mu 0.1-0.2 and 0.55-0.96 at normal views here.
    const auto at = check_test::model_point<T>();
    furnace_band band;
    for (const double ior : {3.5, 6.0}) {
        for (const double weight : {1.0, 2.0}) {
            for (const double coat : {0.0, 1.0}) {
                params<T> p = white<T>();
                p.specular_ior = T(ior);
                p.specular_weight = T(weight);
                p.coat_weight = T(coat);
                for (const T r : {T(0.4), T(1)}) {
                    p.specular_roughness = r;
                    p.coat_roughness = r;
                    const surface<T> m(p);
                    for (const double mu : {1.0, 0.5, 0.2, 0.1}) {
                        const auto reading = furnace(m, view_at_cosine(at, mu), at, 96);
                        INFO("ior ", ior, " weight ", weight, " coat ", coat, " roughness ", double(r), " mu ", mu,
                             ": ", reading.first, " +- ", reading.second);
                        band.check(reading);
                    }
                }
            }
        }
    }
    MESSAGE("white furnace beyond index 3: " << band.low << " to " << band.high);
}

TEST_CASE_TEMPLATE("openpbr_surface: white furnace of an anisotropic opaque dielectric beyond the tables' index 3", T,
                   float, double) {
    // An anisotropic specular lobe at an index ratio above 3 (specular_ior 3.5 and 6; and
    // specular_ior 0.4 under a coat of 2.5, whose TIR fix puts the ratio at 6.25) reads E_spec
    // from detail::anisotropic_reflection_albedo_grid; the correction table read at 3 gave
    // 0.77-1.10 here (1.10 at specular_ior 20, mu 0.5). Over a white diffuse base, views at
    // four azimuths, the furnace band [0.99, 1.001] within 4 standard errors of 96^2 draws.
    const auto at = check_test::model_point<T>();
    furnace_band band;
    struct point {
        double ior, coat;
    };
    for (const point& q : {point{3.5, 0.0}, point{6.0, 0.0}, point{0.4, 1.0}}) {
        for (const double anisotropy : {0.5, 0.9}) {
            for (const T r : {T(0.4), T(1)}) {
                params<T> p = white<T>();
                p.specular_ior = T(q.ior);
                p.coat_weight = T(q.coat);
                p.coat_ior = T(2.5);
                p.specular_roughness = r;
                p.specular_roughness_anisotropy = T(anisotropy);
                const surface<T> m(p);
                for (const std::pair<double, double>& view : {std::pair{1.0, 0.0}, std::pair{0.5, 0.3},
                                                               std::pair{0.2, 1.2}, std::pair{0.1, 2.4}}) {
                    const double mu = view.first, phi = view.second;
                    const auto reading = furnace(m, view_at_cosine(at, mu, phi), at, 96);
                    INFO("ior ", q.ior, " coat ", q.coat, " anisotropy ", anisotropy, " roughness ", double(r), " mu ",
                         mu, " phi ", phi, ": ", reading.first, " +- ", reading.second);
                    band.check(reading);
                }
            }
        }
    }
    MESSAGE("white furnace, anisotropic, beyond index 3: " << band.low << " to " << band.high);
}

TEST_CASE_TEMPLATE("openpbr_surface: sample draws l with the density pdf at 24 parameter points with a density", T,
                   float, double) {
    // The points with a density (all but the four whose lobes are all delta lobes: smooth
    // glass and mirror metal, the smooth soap bubble and the index-matched interface, checked
    // by the sample consistency test instead) x 2 views x 2 scalar types = 96 chi-square
    // tests at a family-wise level of 1e-3 (shade::check::chi2_goodness_of_fit over the
    // sphere, zoomed for sharp lobes; delta draws fall into the nullopt bin, whose expected
    // count is what the density leaves, see shade::check::density_part), and the pdf integral (<= 1 + 1e-3).
    const auto at = check_test::model_point<T>();
    int tested = 0;
    for (const auto& pt : sampling_points<T>()) {
        INFO(pt.name);
        const surface<T> m(pt.p);
        const shade::check::density_part density{m};
        for (const double deg : {25.0, 70.0}) {
            CAPTURE(deg);
            const vec3<T> v = bsdf_test::view_deg(at, deg);
            if (only_delta(m, v, at)) continue;
            ++tested;
            shade::check::chi2_options chi2{.samples = 40000, .alpha = 1e-3, .tests = 96};
            chi2.model = pt.name;
            shade::check::doctest_expect(shade::check::chi2_goodness_of_fit(density, v, at, chi2));
            shade::check::doctest_expect(shade::check::pdf_normalization(m, v, at, chi2));
        }
    }
    CHECK(tested == 48);
}

TEST_CASE_TEMPLATE("openpbr_surface: below an index ratio of 1 the transmission lobe's crossings are not rare heavy draws",
                   T, float, double) {
    // specular_ior 1/1.5 seen from outside: below the critical cosine 0.745 the interface
    // transmits a few per cent. A transmission lobe chosen with a probability ~ T(v) whose
    // draw crosses with a probability ~ T(v) again would give its crossings weights ~ 1 / T(v);
    // drawing the interface whole with half the specular lobe's probability as well makes
    // them several times more frequent, and a lobe whose f carries the interface's
    // multiple-scattering reflection too (so that its shape integrates to 1 - R_ss, the
    // energy it carries) leaves no weight far above 1 / (its probability).
    // Asserted: the largest weight (radiance mode times eta^2, the white furnace's reading of
    // a draw) over 2^16 draws at roughness 0.3, at most 30 at mu 0.5 and 0.2 (measured 19-20;
    // 42-44 and 113 when the lobe carried only the interface's transmission, 97-161 and
    // 540-560 when it also drew only crossings), and the mean within 1 % of 1 (the furnace;
    // its standard error here is below 2e-3).
    const auto at = check_test::model_point<T>();
    params<T> p = white<T>();
    p.specular_ior = T(1) / T(1.5);
    p.transmission_weight = T(1);
    p.specular_roughness = T(0.3);
    const surface<T> m(p);
    for (const double mu : {0.5, 0.2}) {
        CAPTURE(mu);
        const vec3<T> v = view_at_cosine(at, mu);
        shade::rng random(3);
        double largest = 0, sum = 0;
        constexpr int n = 1 << 16;
        for (int i = 0; i < n; ++i) {
            const auto s =
                m.sample(v, random.uniform<T>(), vec2<T>(random.uniform<T>(), random.uniform<T>()), at);
            if (!s) continue;
            const double w = double(s->weight.x) * double(s->eta) * double(s->eta);
            largest = std::max(largest, w);
            sum += w;
        }
        MESSAGE("index ratio 1/1.5, mu " << mu << ": largest weight " << largest << ", mean " << sum / n);
        CHECK(largest <= 30.0);
        CHECK(std::abs(sum / n - 1) <= 0.01);
    }
}

TEST_CASE_TEMPLATE("openpbr_surface: below an index ratio of 1, an anisotropic interface whose tables disagree is not scaled by their difference",
                   T, float, double) {
    // specular_ior 1/3 and 1/2, roughness 0.42, anisotropy 0.84, mu 0.5: near the
    // total-reflection kink the anisotropic total-albedo table reads e_s below the
    // anisotropic reflection table's R_ss (0.9288 < 0.9352 at 1/3, azimuth 0.93 rad). Read as
    // the single-scattering transmittance (floored at 1e-6), their difference scaled the
    // transmission lobe by ~1e5 and the white furnace read 130-300; divided by the
    // transmittance e_s - R_ss + tau (1 - e_s) where that is small but positive, it read
    // 1.21 +- 0.015 at azimuth 0.4. The lobe now also carries the interface's
    // multiple-scattering reflection and is divided by 1 - R_ss, read from the table E_spec
    // reads: no difference of two tables divides. Asserted: the furnace band's upper end
    // (1.001 within 4 standard errors) and at least 0.98 (measured 0.986-0.994 +- 0.001: the
    // anisotropic tables read high near the kink, so the furnace errs low).
    const auto at = check_test::model_point<T>();
    for (const double ior : {1.0 / 3.0, 0.5}) {
        for (const double phi : {0.4, 0.93}) {
            CAPTURE(ior);
            CAPTURE(phi);
            params<T> p = white<T>();
            p.specular_ior = T(ior);
            p.transmission_weight = T(1);
            p.specular_roughness = T(0.42);
            p.specular_roughness_anisotropy = T(0.84);
            const surface<T> m(p);
            const auto reading = furnace(m, view_at_cosine(at, 0.5, phi), at, 256);
            MESSAGE("index ratio " << ior << ", anisotropy 0.84, azimuth " << phi << ": white furnace "
                                   << reading.first << " +- " << reading.second);
            CHECK(reading.first <= 1.001 + 4 * reading.second);
            CHECK(reading.first >= 0.98);
        }
    }
}

TEST_CASE_TEMPLATE("openpbr_surface: below an index ratio of 1 under a coat, what the interface cannot transmit is reflected",
                   T, float, double) {
    // Under a denser coat the specular lobe's E_spec is read at the specification's TIR-fixed
    // ratio (above 1), while the transmission lobe refracts at specular_ior < 1: beyond its
    // critical angle the interface transmits nothing, and the 1 - E_spec the lobe carried was
    // lost (white furnace 0.70-0.87 with a smooth base and coat; 0.83-0.92 with a coat of
    // roughness 0.02, which makes the base a nearly smooth rough lobe; 1.04 +- 0.05 with a
    // rough base). Now the rough lobe takes the interface's reflection to carry the rest and
    // the smooth one sends it along the mirror direction. Asserted: the furnace band.
    const auto at = check_test::model_point<T>();
    struct point {
        double ior, transmission, coat, coat_ior, coat_roughness, roughness;
    };
    furnace_band band;
    for (const point& q : {point{0.768, 0.54, 0.81, 2.89, 0.0, 0.0}, point{0.349, 0.27, 0.49, 2.179, 0.02, 0.0},
                           point{0.5, 1.0, 1.0, 1.6, 0.0, 0.3}}) {
        params<T> p = white<T>();
        p.specular_ior = T(q.ior);
        p.transmission_weight = T(q.transmission);
        p.coat_weight = T(q.coat);
        p.coat_ior = T(q.coat_ior);
        p.coat_roughness = T(q.coat_roughness);
        p.specular_roughness = T(q.roughness);
        const surface<T> m(p);
        for (const double mu : {1.0, 0.5, 0.2, 0.1}) {
            const auto reading = furnace(m, view_at_cosine(at, mu), at, 96);
            INFO("ior ", q.ior, " coat ", q.coat, " roughness ", q.roughness, " mu ", mu, ": ", reading.first, " +- ",
                 reading.second);
            band.check(reading);
        }
    }
    MESSAGE("white furnace below an index ratio of 1 under a coat: " << band.low << " to " << band.high);
}

TEST_CASE_TEMPLATE("openpbr_surface: every sample agrees with f, pdf and weight, from both sides and in both modes",
                   T, float, double) {
    const auto at = check_test::model_point<T>();
    for (const auto& pt : sampling_points<T>()) {
        INFO(pt.name);
        const surface<T> m(pt.p);
        shade::check::sample_options options{.views = 60, .samples_per_view = 20};
        options.model = pt.name;
        options.eta_inside = pt.eta_inside;
        shade::check::doctest_expect(shade::check::sample_consistency(m, at, options));
        shade::check::pair_options coverage{.pairs = 1000};
        coverage.model = pt.name;
        shade::check::doctest_expect(shade::check::pdf_coverage(m, at, coverage));
    }
}

TEST_CASE_TEMPLATE("openpbr_surface: roughness 0 gives exact delta lobes", T, float, double) {
    const auto at = check_test::model_point<T>();
    const vec3<T> v = view_at_cosine(at, 0.6);
    // A smooth white metal: every draw is the mirror direction with weight F82 = 1 and f
    // is 0 for any given pair.
    params<T> p = white<T>();
    p.base_metalness = T(1);
    p.specular_roughness = T(0);
    const surface<T> mirror(p);
    shade::rng random(1);
    for (int i = 0; i < 100; ++i) {
        const auto s = mirror.sample(v, random.uniform<T>(), vec2<T>(random.uniform<T>(), random.uniform<T>()), at);
        REQUIRE(s);
        CHECK(shade::is_specular(s->flags));
        CHECK(glm::dot(s->l + v, at.n()) == doctest::Approx(2 * glm::dot(v, at.n())).epsilon(1e-5));
        CHECK(double(s->weight.x) == doctest::Approx(1).epsilon(1e-5));
        CHECK(mirror.f(s->l, v, at) == rgb<T>(0));
        CHECK(mirror.pdf(s->l, v, at) == T(0));
    }
    // Smooth glass: reflection with probability proportional to F(mu) (the mixture's
    // choice by energy), refraction otherwise; weights sum in expectation to the Fresnel
    // split: reflection weight * probability = F(0.6, 1.5).
    params<T> g = white<T>();
    g.transmission_weight = T(1);
    g.specular_roughness = T(0);
    const surface<T> glass(g);
    const T F = shade::F_dielectric(T(0.6), T(1.5));
    const T p_reflect = glass.lobe_probability(surface<T>::lobe::specular, v, at);
    CHECK(double(p_reflect) == doctest::Approx(double(F)).epsilon(1e-4));
    const auto r = glass.sample(v, p_reflect * T(0.5), vec2<T>(T(0.5)), at);
    REQUIRE(r);
    CHECK(shade::is_reflection(r->flags));
    CHECK(double(r->weight.x * r->pdf) == doctest::Approx(double(F)).epsilon(1e-5));
    const auto t = glass.sample(v, (T(1) + p_reflect) * T(0.5), vec2<T>(T(0.5)), at);
    REQUIRE(t);
    CHECK(shade::is_transmission(t->flags));
    CHECK(double(t->eta) == doctest::Approx(1.5));
    // Radiance mode: the refraction carries (1 - F) / eta^2 over its probability 1 - F.
    CHECK(double(t->weight.x * t->pdf) == doctest::Approx(double((T(1) - F) / T(2.25))).epsilon(1e-4));
}

TEST_CASE_TEMPLATE("openpbr_surface: a thin wall looks the same from both sides", T, float, double) {
    params<T> p;
    p.geometry_thin_walled = true;
    p.transmission_weight = T(0.5);
    p.subsurface_weight = T(0.5);
    p.specular_roughness = T(0.3);
    p.coat_weight = T(0.5);
    const surface<T> m(p);
    const auto at = shade::surface_point<T>::at(vec3<T>(0), vec3<T>(0, 0, 1));
    shade::rng random(9);
    for (int i = 0; i < 100; ++i) {
        const vec3<T> l = view_at_cosine(at, 0.05 + 0.9 * random.uniform<double>(), 6.28 * random.uniform<double>());
        const vec3<T> v = view_at_cosine(at, 0.05 + 0.9 * random.uniform<double>(), 6.28 * random.uniform<double>());
        // Seen from below, the mirror images of a pair seen from above: the components
        // along the normal and the bitangent negated (the frame of the far side is
        // (t, -b, -n), so the local coordinates, azimuth included, are the same).
        const auto below_of = [&](const vec3<T>& w) {
            return w - T(2) * glm::dot(w, at.shading.b) * at.shading.b - T(2) * glm::dot(w, at.n()) * at.n();
        };
        const vec3<T> l_below = below_of(l), v_below = below_of(v);
        const rgb<T> above = m.f(l, v, at);
        const rgb<T> below = m.f(l_below, v_below, at);
        for (int c = 0; c < 3; ++c) CHECK(double(below[c]) == doctest::Approx(double(above[c])).epsilon(1e-5));
        const rgb<T> through = m.f(-l, v, at);
        const rgb<T> through_below = m.f(-l_below, v_below, at);
        for (int c = 0; c < 3; ++c)
            CHECK(double(through_below[c]) == doctest::Approx(double(through[c])).epsilon(1e-5));
    }
}

TEST_CASE_TEMPLATE("openpbr_surface: emission through coat and fuzz, and the interior medium", T, float, double) {
    const auto at = shade::surface_point<T>::at(vec3<T>(0), vec3<T>(0, 0, 1));
    params<T> p;
    p.emission_luminance = T(100);
    p.emission_color = rgb<T>(T(1), T(0.5), T(2));
    const surface<T> bare(p);
    // No coat, no fuzz, opaque: luminance times colour, the same in every direction above.
    CHECK(bare.emission(view_at_cosine(at, 0.3), at) == T(100) * p.emission_color);
    CHECK(bare.emission(-at.n(), at) == rgb<T>(0));
    // A coat of colour c at normal incidence: the base's light crosses the coat once,
    // transmittance sqrt(c) (T_coat^2 = coat_color), and the coat reflects E_coat(1) =
    // F(1, 1.6) = (0.6 / 2.6)^2 of what reaches it back down.
    p.coat_weight = T(1);
    p.coat_roughness = T(0);
    p.coat_color = rgb<T>(T(0.64));
    const surface<T> coated(p);
    const double f0 = (0.6 / 2.6) * (0.6 / 2.6);
    const rgb<T> e = coated.emission(at.n(), at);
    CHECK(double(e.x) == doctest::Approx(100 * 0.8 * (1 - f0)).epsilon(1e-5));
    // The interior: none for an opaque material, the translucent base's medium otherwise.
    CHECK_FALSE(bare.interior().present);
    params<T> glass;
    glass.transmission_weight = T(1);
    glass.transmission_depth = T(2);
    glass.transmission_color = rgb<T>(T(0.5));
    const auto medium = surface<T>(glass).interior();
    CHECK(medium.present);
    // Extinction -ln(color) / depth (openpbr::transmission_medium).
    CHECK(double(medium.sigma_t.x) == doctest::Approx(std::log(2.0) / 2).epsilon(1e-5));
    glass.geometry_thin_walled = true;
    CHECK_FALSE(surface<T>(glass).interior().present);
}

TEST_CASE("openpbr_surface: a parameter outside the specification's range is refused by name") {
    params<double> p;
    p.coat_weight = 1.5;
    CHECK_THROWS_WITH_AS(surface<double>{p}, doctest::Contains("coat_weight"), shade::invalid_parameter);
    p = {};
    p.specular_ior = -1;
    CHECK_THROWS_WITH_AS(surface<double>{p}, doctest::Contains("specular_ior"), shade::invalid_parameter);
    p = {};
    p.base_color = rgb<double>(0.5, std::nan(""), 0.5);
    CHECK_THROWS_WITH_AS(surface<double>{p}, doctest::Contains("base_color"), shade::invalid_parameter);
}

TEST_CASE_TEMPLATE("openpbr_surface: the reciprocal form is reciprocal for opaque materials; albedo scaling is not", T,
                   float, double) {
    // layering::reciprocal replaces each layer's 1 - w E(v) by (1 - w E(l)) (1 - w E(v)) /
    // (1 - w E_avg) and the fuzz lobe by zeltner_sheen_reciprocal: every factor and lobe is
    // symmetric in l and v, so f(l, v) = f(v, l) to rounding. The specification's albedo
    // scaling weighs the base by the view alone, so exchanging a grazing l with a steep v
    // changes the base's share by far more than the tolerance (the check must fail).
    const auto at = check_test::model_point<T>();
    params<T> p;
    p.base_color = rgb<T>(T(0.8), T(0.5), T(0.3));
    p.base_metalness = T(0.3);
    p.coat_weight = T(0.8);
    p.coat_roughness = T(0.2);
    p.fuzz_weight = T(0.6);
    p.specular_roughness = T(0.4);
    shade::check::pair_options pairs{.pairs = 2000};
    pairs.model = "openpbr_surface (reciprocal form)";
    const surface<T> reciprocal(p, shade::layering::reciprocal);
    shade::check::doctest_expect(shade::check::adjoint_reciprocity(reciprocal, at, 1, pairs));
    // Anisotropic coat and specular: E_coat and E_spec read at each direction's azimuth, l's
    // as v's (reading l's at its cosine alone, as an isotropic table, breaks the symmetry).
    params<T> q = p;
    q.coat_roughness_anisotropy = T(0.8);
    q.specular_roughness_anisotropy = T(0.9);
    pairs.model = "openpbr_surface (reciprocal form, anisotropic)";
    shade::check::doctest_expect(shade::check::adjoint_reciprocity(surface<T>(q, shade::layering::reciprocal), at, 1, pairs));
    pairs.model = "openpbr_surface (albedo scaling)";
    const surface<T> scaled(p);
    shade::check::doctest_expect_failure(shade::check::adjoint_reciprocity(scaled, at, 1, pairs));
    // The reciprocal form samples consistently too.
    shade::check::sample_options options{.views = 60, .samples_per_view = 20};
    options.model = "openpbr_surface (reciprocal form)";
    shade::check::doctest_expect(shade::check::sample_consistency(reciprocal, at, options));
    shade::check::chi2_options chi2{.samples = 40000, .alpha = 1e-3, .tests = 4};
    chi2.model = "openpbr_surface (reciprocal form)";
    for (const double deg : {25.0, 70.0})
        shade::check::doctest_expect(shade::check::chi2_goodness_of_fit(reciprocal, bsdf_test::view_deg(at, deg), at, chi2));
}

TEST_CASE_TEMPLATE("openpbr_surface's albedo rows read what the tables read", T, float, double) {
    // detail::dielectric_albedo_row combines the table's rows along sqrt(alpha) and the
    // index once with the weights of the splines it reads them with; the splines are linear
    // in the node values, so the row's spline along the view equals the full read to
    // rounding.
    shade::rng random(17);
    const T tol = sizeof(T) == 4 ? T(2e-5) : T(1e-12);
    for (int i = 0; i < 2000; ++i) {
        const T alpha = T(1e-3 + 1.2 * random.uniform<double>());
        // Index ratios up to 5.5 on each side: beyond the table's eta_hat 3 the row adds
        // reflection_albedo_change as the function does.
        const T eta = random.uniform<double>() < 0.5 ? T(1.0005 + 4.5 * random.uniform<double>())
                                                     : T(1) / T(1.0005 + 4.5 * random.uniform<double>());
        const T mu = random.uniform<T>();
        CAPTURE(alpha);
        CAPTURE(eta);
        CAPTURE(mu);
        const shade::detail::reflection_albedo_row<T> r(alpha, eta);
        CHECK(std::abs(r.at(mu) - shade::dielectric_reflection_albedo(mu, alpha, eta)) <= tol);
        // With F(mu, eta) passed in, the same number (F is then computed once for the value
        // and the table's view coordinate); a wrong F moves it.
        const T fresnel = shade::F_dielectric(mu, eta);
        CHECK(r.at(mu, fresnel) == r.at(mu));
        const shade::detail::dielectric_albedo_grid grid{};
        const auto cell = shade::detail::dielectric_albedo_locate(grid, alpha, eta);
        const shade::detail::dielectric_albedo_row<T, shade::detail::dielectric_albedo_mu_nodes> e(
            shade::detail::ggx_rough_dielectric_albedo, grid, cell);
        CHECK(std::abs(e.at(mu) - shade::detail::dielectric_albedo_interpolate(shade::detail::ggx_rough_dielectric_albedo,
                                                                               grid, cell, mu)) <= tol);
    }
}

TEST_CASE("openpbr_surface: the dispersed index at a wavelength") {
    // Without dispersion every wavelength sees specular_ior. With scale 1 and Abbe number
    // V = 20, Cauchy's n(lambda) = A + B / lambda^2 through n(587.6 nm) = n_d with
    // (n_d - 1) / (n_F - n_C) = V (openpbr::dispersed_ior): at the d line, n_d exactly.
    params<double> p;
    CHECK(surface<double>(p).specular_ior_at(450) == 1.5);
    p.transmission_dispersion_scale = 1;
    const surface<double> m(p);
    CHECK(m.specular_ior_at(587.6) == doctest::Approx(1.5).epsilon(1e-12));
    CHECK(m.specular_ior_at(486.1) - m.specular_ior_at(656.3) == doctest::Approx(0.5 / 20).epsilon(1e-9));
}

TEST_CASE_TEMPLATE("openpbr_surface: random parameters at the ends of their ranges give finite values, never NaN", T,
                   float, double) {
    // Parameters drawn at either end of their range (30 %) or inside it, indices from the
    // extremes the validation accepts (1e-3, 1e3, exactly 1); directions over the sphere
    // with some on the horizon (|n·w| = 1e-7). f, pdf, emission and every sample's weight
    // must be finite and >= 0 (e.g. a coat of index 1e-3 reflects all diffuse light back,
    // K = 1, over a white base, E_b = 1: the darkening's 0 / 0 is its limit 1). 400
    // materials in the full suite, the first 80 of them in the quick one (an anisotropic
    // interface below an index ratio of 1 integrates its albedo grid when built, and about
    // a fifth of these materials have one).
    shade::rng r(5);
    const auto U = [&]() { return r.uniform<T>(); };
    const auto pick = [&](T a, T b) {
        const T x = U();
        if (x < T(0.15)) return a;
        if (x < T(0.3)) return b;
        return a + (b - a) * U();
    };
    const auto colour = [&]() { return rgb<T>(pick(0, 1), pick(0, 1), pick(0, 1)); };
    const T iors[] = {T(1), T(1.5), T(0.5), T(3), T(1e-3), T(1e3), T(1.0001)};
    const auto ior = [&]() { return iors[r.next_u32() % 7]; };
    const auto at = check_test::model_point<T>();
    {
        // The darkening's 0 / 0, directly: a coat of index 1e-3 over a white base.
        params<T> p = white<T>();
        p.coat_weight = T(1);
        p.coat_ior = T(1e-3);
        const rgb<T> f = surface<T>(p).f(view_at_cosine(at, 0.7, 1.0), view_at_cosine(at, 0.5), at);
        for (int c = 0; c < 3; ++c) CHECK(std::isfinite(f[c]));
    }
    int bad = 0;
    const int materials = shade_test::full ? 400 : 80;
    for (int k = 0; k < materials; ++k) {
        params<T> p;
        p.base_weight = pick(0, 1);
        p.base_color = colour();
        p.base_diffuse_roughness = pick(0, 1);
        p.base_metalness = pick(0, 1);
        p.specular_weight = pick(0, 3);
        p.specular_color = colour();
        p.specular_roughness = pick(0, 1);
        p.specular_roughness_anisotropy = pick(0, 1);
        p.specular_ior = ior();
        p.transmission_weight = pick(0, 1);
        p.transmission_color = colour();
        p.transmission_depth = pick(0, 2);
        p.transmission_scatter = colour();
        p.subsurface_weight = pick(0, 1);
        p.subsurface_color = colour();
        p.subsurface_scatter_anisotropy = pick(-1, 1);
        p.coat_weight = pick(0, 1);
        p.coat_color = colour();
        p.coat_roughness = pick(0, 1);
        p.coat_roughness_anisotropy = pick(0, 1);
        p.coat_ior = ior();
        p.coat_darkening = pick(0, 1);
        p.fuzz_weight = pick(0, 1);
        p.fuzz_color = colour();
        p.fuzz_roughness = pick(0, 1);
        p.thin_film_weight = pick(0, 1);
        p.thin_film_thickness = pick(0, 2);
        p.thin_film_ior = ior();
        p.emission_luminance = pick(0, 100);
        p.geometry_opacity = pick(0, 1);
        p.geometry_thin_walled = U() < T(0.3);
        const surface<T> m(p);
        for (int i = 0; i < 50; ++i) {
            const auto direction = [&]() {
                T z = T(2) * U() - T(1);
                if (U() < T(0.05)) z = U() < T(0.5) ? T(1e-7) : T(-1e-7);
                const T phi = T(6.2831853) * U();
                const T s = std::sqrt(std::max(T(0), T(1) - z * z));
                return glm::normalize(at.shading.to_world(vec3<T>(s * std::cos(phi), s * std::sin(phi), z)));
            };
            const vec3<T> l = direction(), v = direction();
            const rgb<T> f = m.f(l, v, at);
            const T pdf = m.pdf(l, v, at);
            const rgb<T> e = m.emission(v, at);
            bool ok = std::isfinite(pdf) && pdf >= T(0);
            for (int c = 0; c < 3; ++c) ok = ok && std::isfinite(f[c]) && f[c] >= T(0) && std::isfinite(e[c]);
            for (const auto mode : {shade::transport_mode::radiance, shade::transport_mode::importance}) {
                const auto s = m.sample(v, U(), vec2<T>(U(), U()), at, mode);
                if (!s) continue;
                ok = ok && s->pdf > T(0) && std::isfinite(s->pdf) && std::isfinite(s->l.x);
                for (int c = 0; c < 3; ++c) ok = ok && std::isfinite(s->weight[c]) && s->weight[c] >= T(0);
            }
            if (!ok) ++bad;
        }
    }
    CHECK(bad == 0);
}

TEST_CASE_TEMPLATE("openpbr_surface: white furnace with anisotropic specular, coat and glass", T, float, double) {
    // E of an anisotropic GGX reflection lobe depends on the view's azimuth; the material
    // reads shade::dielectric_reflection_albedo's anisotropic form (the isotropic table plus
    // a tabulated correction at the view's azimuth, an upper envelope). In a white
    // furnace its error is the furnace's: albedo(v) = 1 + E_true(v) - E_read(v). The issue's
    // band [0.99, 1.001] (each reading widened by 4 standard errors) over anisotropy 0.5, 0.9
    // and 1, roughness 0.1 to 1, mu 1 to 0.1 and four azimuths, for an anisotropic specular
    // over white diffuse, alone and under a smooth coat of higher index, and an anisotropic
    // coat over white diffuse and over white metal (anisotropic glass: the next test). The
    // table's furnace error alone, without sampling noise, is within the band from outside at
    // every anisotropy here (the noise-free test "the anisotropic reflection albedo's furnace
    // error" below: 0.9934 at its lowest, anisotropy 1, roughness 1, mu 0.1).
    const auto at = check_test::model_point<T>();
    furnace_band band;
    for (const T aniso : {T(0.5), T(0.9), T(1)}) {
        for (const T r : {T(0.1), T(0.2), T(0.3), T(0.5), T(0.7), T(1)}) {
            params<T> p = white<T>();
            p.specular_roughness = r;
            p.specular_roughness_anisotropy = aniso;
            params<T> coat = p;
            coat.coat_weight = T(1);
            coat.coat_roughness = r;
            coat.coat_roughness_anisotropy = aniso;
            coat.specular_roughness_anisotropy = T(0);
            params<T> coat_metal = coat;
            coat_metal.base_metalness = T(1);
            params<T> glass = p;
            glass.transmission_weight = T(1);
            params<T> under = p; // the specular under a smooth coat of higher index (1.6 over 1.5)
            under.coat_weight = T(1);
            under.coat_roughness = T(0);
            for (const auto& q : {p, coat, coat_metal, glass, under}) {
                // Glass is the next test's (a sampled estimate here cannot resolve the band at
                // its sharp transmission lobes).
                if (q.transmission_weight > T(0)) continue;
                const surface<T> m(q);
                for (const double mu : {1.0, 0.5, 0.2, 0.1}) {
                    for (const double phi : {0.0, 0.8, 1.5708, 2.4}) {
                        const auto reading = furnace(m, view_at_cosine(at, mu, phi), at, 64);
                        INFO("anisotropy ", double(aniso), " roughness ", double(r), " coat ", double(q.coat_weight),
                             " metal ", double(q.base_metalness), " glass ", double(q.transmission_weight), " mu ", mu,
                             " phi ", phi, ": ", reading.first, " +- ", reading.second);
                        band.check(reading);
                    }
                }
            }
        }
    }
    MESSAGE("anisotropic white furnace: " << band.low << " to " << band.high);
}

TEST_CASE_TEMPLATE("openpbr_surface: white furnace of a strongly anisotropic metal, to anisotropy 1", T, float, double) {
    // A white metal (base_metalness 1, base and specular colour 1) at specular_roughness_
    // anisotropy 0.95 (alpha_t / alpha_b = 20, the first anisotropic table's end), 0.98 (50:1)
    // and 1 (a 1-D rough surface, alpha_b held at the smallest alpha): kulla_conty_anisotropic
    // reads the strong-anisotropy tables above 20:1. The band within 4 standard errors (160^2
    // draws) at roughness 0.3 to 1, mu 1 to 0.1, four azimuths. Before those tables the ratio was read
    // as 20:1 and the furnace fell to 0.81 at anisotropy 0.98 and 0.38 at anisotropy 1
    // (roughness 1, mu 1).
    const auto at = check_test::model_point<T>();
    furnace_band band;
    for (const T aniso : {T(0.95), T(0.98), T(1)}) {
        for (const T r : {T(0.3), T(0.6), T(1)}) {
            params<T> p = white<T>();
            p.base_metalness = T(1);
            p.specular_roughness = r;
            p.specular_roughness_anisotropy = aniso;
            const surface<T> m(p);
            for (const double mu : {1.0, 0.5, 0.2, 0.1}) {
                for (const double phi : {0.0, 0.8, 1.5708, 2.4}) {
                    if (mu == 1.0 && phi > 0) continue; // one view at normal incidence
                    const auto reading = furnace(m, view_at_cosine(at, mu, phi), at, 160);
                    INFO("anisotropy ", double(aniso), " roughness ", double(r), " mu ", mu, " phi ", phi, ": ",
                         reading.first, " +- ", reading.second);
                    band.check(reading);
                }
            }
        }
    }
    MESSAGE("strongly anisotropic white metal, white furnace: " << band.low << " to " << band.high);
}

TEST_CASE_TEMPLATE("openpbr_surface: white furnace of a strongly anisotropic dielectric seen along its smoother axis", T,
                   float, double) {
    // An opaque white dielectric (specular over EON) at anisotropy 0.98 and 0.99 (50:1 and
    // 100:1), roughness 0.8 and 1, specular_ior 1.5, and under a coat of index 2 (coat_weight
    // 1: the base's ratio n_c / n_b = 1.33, the specification's fix against total
    // reflection at the coat/base boundary), seen at grazing views within a few degrees of
    // the smoother axis, where E_spec changes within a few degrees of azimuth. Before the
    // per-interface grid at strong anisotropy above 1 the table read E_spec up to 0.06 high
    // there and the furnace fell to 0.94 (anisotropy 0.99, roughness 1, mu 0.1 along the
    // smoother axis). The band within 4 standard errors (128^2 draws).
    const auto at = check_test::model_point<T>();
    furnace_band band;
    for (const T aniso : {T(0.98), T(0.99)}) {
        for (const T r : {T(0.8), T(1)}) {
            for (const bool coat : {false, true}) {
                params<T> p = white<T>();
                p.specular_roughness = r;
                p.specular_roughness_anisotropy = aniso;
                if (coat) {
                    p.coat_weight = T(1);
                    p.coat_ior = T(2);
                    p.coat_roughness = T(0.5);
                }
                const surface<T> m(p);
                for (const double mu : {0.1, 0.15, 0.25}) {
                    for (const double phi : {1.45, 1.52, 1.5708}) {
                        const auto reading = furnace(m, view_at_cosine(at, mu, phi), at);
                        INFO("anisotropy ", double(aniso), " roughness ", double(r), " coat ", coat, " mu ", mu,
                             " phi ", phi, ": ", reading.first, " +- ", reading.second);
                        band.check(reading);
                    }
                }
            }
        }
    }
    MESSAGE("strongly anisotropic white dielectric along its smoother axis, white furnace: " << band.low << " to "
                                                                                             << band.high);
}

TEST_CASE_TEMPLATE("openpbr_surface: white furnace of rough glass near index match", T, float, double) {
    // Glass (transmission_weight 1) at specular_ior 0.97, 0.99, 1.01 and 1.03, within a
    // factor 1.05 of the surroundings' index, below the total-albedo tables' first index: at
    // roughness 0.3 to 1 the tables read E_s at 1.05, and the transmission lobe's
    // compensation made the furnace 1.02 to 1.10 from the denser side and 0.95 from the
    // rarer (specular_ior 0.99, roughness 0.6, mu 0.2: 1.097). A grid of the interface
    // serves there in either albedo mode (isotropic and, at anisotropy 0.5, anisotropic).
    // The band within 4 standard errors (128^2 draws).
    const auto at = check_test::model_point<T>();
    furnace_band band;
    for (const T ior : {T(0.97), T(0.99), T(1.01), T(1.03)}) {
        for (const T r : {T(0.3), T(0.6), T(1)}) {
            for (const T aniso : {T(0), T(0.5)}) {
                if (aniso > T(0) && !(ior == T(0.99) && r == T(0.6))) continue; // one anisotropic point
                params<T> p = white<T>();
                p.transmission_weight = T(1);
                p.specular_ior = ior;
                p.specular_roughness = r;
                p.specular_roughness_anisotropy = aniso;
                const surface<T> m(p);
                for (const double mu : {0.2, 0.5, 1.0}) {
                    const auto reading = furnace(m, view_at_cosine(at, mu), at);
                    INFO("specular_ior ", double(ior), " roughness ", double(r), " anisotropy ", double(aniso), " mu ",
                         mu, ": ", reading.first, " +- ", reading.second);
                    band.check(reading);
                }
            }
        }
    }
    MESSAGE("rough glass near index match, white furnace: " << band.low << " to " << band.high);
}

TEST_CASE_TEMPLATE("openpbr_surface: white furnace of anisotropic glass below 1 whose specular lobe is at another index", T,
                   float, double) {
    // Glass at specular_ior 0.7, roughness 0.06 (widened by the coat), anisotropy 0.5 and 1,
    // under a coat of index 2.32 (weight 0.48: the specular lobe's index is the TIR fix's
    // lerp(0.7, 2.32 / 0.7, 0.48), above 1) and at specular_weight 0.2 and 1: E_spec is not
    // the R_ss the transmission lobe is divided by, so their reads do not cancel. With R_ss
    // read with its grid's margin the lobe carried (1 - R_true) / (1 - R_read) > 1 of its
    // share and the furnace read 1.0044 at normal incidence (anisotropy 1, specular_weight
    // 0.2; a random scan found 1.0035 with transmission_weight 0.81). The band within 4
    // standard errors (128^2 draws).
    const auto at = check_test::model_point<T>();
    furnace_band band;
    for (const T aniso : {T(0.5), T(1)}) {
        for (const T weight : {T(0.2), T(1)}) {
            params<T> p = white<T>();
            p.transmission_weight = T(1);
            p.specular_ior = T(0.7);
            p.specular_roughness = T(0.06);
            p.specular_roughness_anisotropy = aniso;
            p.specular_weight = weight;
            p.coat_weight = T(0.48);
            p.coat_ior = T(2.32);
            p.coat_roughness = T(0.12);
            const surface<T> m(p);
            for (const double mu : {1.0, 0.7, 0.4}) {
                const auto reading = furnace(m, view_at_cosine(at, mu, 2.6), at);
                INFO("anisotropy ", double(aniso), " specular_weight ", double(weight), " mu ", mu, ": ",
                     reading.first, " +- ", reading.second);
                band.check(reading);
            }
        }
    }
    MESSAGE("anisotropic glass below 1 under a coat, white furnace: " << band.low << " to " << band.high);
}

TEST_CASE("openpbr_surface: white furnace of anisotropic glass, stratified with the lobe choice integrated out") {
    // Anisotropic glass (transmission_weight 1, specular_ior 1.5) over a white base, seen
    // from outside, roughness 0.1, 0.2, 0.5, anisotropy 0.5, 0.9 and 1, mu 1, 0.5, 0.2, 0.1 at up
    // to four azimuths: furnace_stratified (32^2 u strata, 32 lobe-choice strata and 4 cosine
    // directions each; standard errors about 1e-3 where the reading is near the band, as
    // against 0.01 to 0.15 for 64^2 draws of sample() alone, whose weights are heavy-tailed
    // at grazing views of a sharp lobe). The glass transmits through
    // compensated_rough_dielectric, its anisotropic E_s(w) read from the isotropic table plus
    // the tabulated correction (shade/bsdf/dielectric_anisotropic_albedo_table.hpp), and its
    // reflection is scaled by the anisotropic dielectric_reflection_albedo: the furnace
    // reads 1 + the tables' errors at v. Issue #32's band [0.99, 1.001] (widened by 4
    // standard errors) holds at every view, anisotropy 1 included (measured 0.9879 to 1.0018;
    // the correction reaches anisotropy 1 and is an upper envelope of E; seen from inside,
    // which this test does not, it reads high by up to 0.075: docs/properties.md). The
    // same views with openpbr::interface_albedo::grid read 0.9919 to 1.0038 (the highest at
    // mu 0.1 and roughness 0.2 with standard errors of 3e-3 to 5e-3; at 96^2 strata those
    // views read 0.995 to 0.998).
    using T = double;
    const auto at = check_test::model_point<T>();
    furnace_band band;
    for (const T aniso : {T(0.5), T(0.9), T(1)}) {
        for (const T r : {T(0.1), T(0.2), T(0.5)}) {
            params<T> glass = white<T>();
            glass.specular_roughness = r;
            glass.specular_roughness_anisotropy = aniso;
            glass.transmission_weight = T(1);
            const surface<T> m(glass);
            for (const double mu : {1.0, 0.5, 0.2, 0.1}) {
                for (const double phi : {0.0, 0.8, 1.5708, 2.4}) {
                    if (mu == 1.0 && phi > 0) continue; // one view at normal incidence
                    if (mu == 0.5 && (phi == 0.8 || phi == 2.4)) continue; // two at mu 0.5
                    const auto reading =
                        furnace_stratified(m, view_at_cosine(at, mu, phi), at, double(glass.specular_ior), 32, 32, 4);
                    INFO("anisotropy ", double(aniso), " roughness ", double(r), " mu ", mu, " phi ", phi, ": ",
                         reading.first, " +- ", reading.second);
                    CHECK(reading.second < 0.02);
                    band.check(reading);
                }
            }
        }
    }
    MESSAGE("anisotropic glass white furnace: " << band.low << " to " << band.high);
}

TEST_CASE("openpbr_surface: white furnace of anisotropic glass below an index ratio of 1, stratified") {
    // Glass denser outside than in (specular_ior 0.5 and 0.93, transmission_weight 1) at
    // roughness 0.75, anisotropy 0.5 (alpha about 2:1) and 0.97 (about 33:1), seen from
    // outside at mu 1, 0.5, 0.2, 0.1 (furnace_stratified, 48^2 u strata): most views lie in or
    // near the cone of total reflection, where the transmission lobe's normalisation needs
    // E_s(w) of the denser side. Built with openpbr::interface_albedo::grid, E_s comes from
    // the interface's own rough_dielectric_albedo_grid: measured 0.991 to 0.9999. (The
    // default mode: the next test.) Issue #32's band
    // [0.99, 1.001], widened by 4 standard errors.
    using T = double;
    const auto at = check_test::model_point<T>();
    furnace_band band;
    for (const T ior : {T(0.5), T(0.93)}) {
        for (const T aniso : {T(0.5), T(0.97)}) {
            params<T> glass = white<T>();
            glass.specular_roughness = T(0.75);
            glass.specular_roughness_anisotropy = aniso;
            glass.specular_ior = ior;
            glass.transmission_weight = T(1);
            const surface<T> m(glass, shade::layering::albedo_scaling, shade::openpbr::interface_albedo::grid);
            REQUIRE(m.albedo_source() == shade::openpbr::interface_albedo::grid);
            for (const double mu : {1.0, 0.5, 0.2, 0.1}) {
                for (const double phi : {0.3, 1.2}) {
                    if (mu == 1.0 && phi > 1) continue;
                    const auto reading = furnace_stratified(m, view_at_cosine(at, mu, phi), at, double(ior), 48, 32, 4);
                    INFO("specular_ior ", double(ior), " anisotropy ", double(aniso), " mu ", mu, " phi ", phi, ": ",
                         reading.first, " +- ", reading.second);
                    CHECK(reading.second < 0.01);
                    band.check(reading);
                }
            }
        }
    }
    MESSAGE("anisotropic glass below an index ratio of 1, white furnace: " << band.low << " to " << band.high);
}

TEST_CASE("openpbr_surface: white furnace of anisotropic glass below an index ratio of 1 in the default tables mode") {
    // The test above with the default openpbr::interface_albedo::tables, and a nearly smooth
    // interface (roughness 0.17, anisotropy 1, specular_ior 0.608: alphas 0.04 x 1e-4) at its
    // grazing views across the smoother axis (phi 0). From outside, E_s of the transmission
    // lobe's interface is read from a grid filled in the same pass as the side's R_ss
    // (detail::anisotropic_reflection_albedo_grid's with_total): the tables' correction read
    // it up to 0.016 high at grazing views (a white furnace of 0.97), and on the nearly
    // smooth interface it switched the compensation off (0.92; issue #32's random scans:
    // 0.926 to 0.94). Issue #32's band [0.99, 1.001], widened by 4 standard errors.
    using T = double;
    const auto at = check_test::model_point<T>();
    furnace_band band;
    struct glass_point {
        T roughness, anisotropy, ior;
    };
    for (const glass_point g : {glass_point{T(0.75), T(0.5), T(0.5)}, glass_point{T(0.75), T(0.97), T(0.5)},
                                glass_point{T(0.75), T(0.5), T(0.93)}, glass_point{T(0.75), T(0.97), T(0.93)},
                                glass_point{T(0.17), T(1), T(0.608)}}) {
        params<T> glass = white<T>();
        glass.specular_roughness = g.roughness;
        glass.specular_roughness_anisotropy = g.anisotropy;
        glass.specular_ior = g.ior;
        glass.transmission_weight = T(1);
        const surface<T> m(glass);
        REQUIRE(m.albedo_source() == shade::openpbr::interface_albedo::tables);
        for (const double mu : {1.0, 0.5, 0.2, 0.1}) {
            for (const double phi : {0.0, 0.3, 1.2}) {
                if (mu == 1.0 && phi > 0) continue;
                const auto reading = furnace_stratified(m, view_at_cosine(at, mu, phi), at, double(g.ior), 48, 32, 4);
                INFO("roughness ", double(g.roughness), " anisotropy ", double(g.anisotropy), " specular_ior ",
                     double(g.ior), " mu ", mu, " phi ", phi, ": ", reading.first, " +- ", reading.second);
                CHECK(reading.second < 0.01);
                band.check(reading);
            }
        }
    }
    MESSAGE("anisotropic glass below an index ratio of 1, tables mode, white furnace: " << band.low << " to " << band.high);
}

TEST_CASE("openpbr_surface: white furnace of anisotropic glass with a thin film below an index ratio of 1") {
    // Glass denser outside than in (transmission_weight 1) under a thin film, anisotropic:
    // E_spec is the film's share (not R_ss), so the transmission lobe, divided by 1 - R_ss
    // at v, keeps its albedo 1 only where that R_ss is the interface's own; read from the
    // anisotropic table, which reads R_ss up to 0.18 high on the denser side, the lobe
    // carried (1 - R_true) / (1 - R_read) > 1 of what it was given and the furnace read
    // above 1: 1.039 (roughness 0.951, anisotropy 0.92, specular_ior 0.658, mu 0.7, phi 0.8),
    // 1.035 (0.51, 0.97, 0.432, film weight 0.96, mu 0.8, phi 0.4), 1.015 (0.702, 0.47,
    // 0.517, mu 0.6, phi 1.2; all predicted from the lobes' albedos, the first sampled at
    // 1.034). Each view here read above 1.001 that way; with R_ss integrated for the
    // interface (anisotropic_reflection_albedo_grid below 1, read without its margin) none
    // may: at most 1.001 + 4 standard errors of furnace_stratified (48^2 u strata). Below:
    // the film's share is integrated with R_ss in the grid's pass (D, its difference from
    // R_ss), and E_s of the outside read from the same pass (the tables mode's one-sided
    // grid), so the band's 0.99 holds within the estimates' error (measured 0.9875 to 0.9962,
    // the lowest the scan's two materials below; 0.980 to 0.991 with the share read from the
    // isotropic reference plus its anisotropic correction and E_s from the tables). With it
    // the random scan's materials (issue #32): film over glass at
    // anisotropy 1 and specular_ior 0.725 with subsurface and a little metal (0.898 at mu 0.5),
    // and a film of weight 1 over glass at specular_ior 0.426, anisotropy 0.14 (0.978 at the
    // normal).
    using T = double;
    const auto at = check_test::model_point<T>();
    struct film_glass {
        T roughness, anisotropy, ior, film_weight, thickness, film_ior;
        double mu, phi;
    };
    double low = 2, high = 0;
    for (const film_glass g : {film_glass{T(0.951), T(0.92), T(0.658), T(1), T(1.47), T(1.89), 0.7, 0.8},
                               film_glass{T(0.951), T(0.92), T(0.658), T(1), T(1.47), T(1.89), 0.6, 1.2},
                               film_glass{T(0.51), T(0.97), T(0.432), T(0.96), T(0.84), T(1.39), 0.8, 0.4},
                               film_glass{T(0.51), T(0.97), T(0.432), T(0.96), T(0.84), T(1.39), 0.8, 0.0},
                               film_glass{T(0.702), T(0.47), T(0.517), T(1), T(0.66), T(1.76), 0.6, 1.2},
                               film_glass{T(0.702), T(0.47), T(0.517), T(1), T(0.66), T(1.76), 0.8, 0.8},
                               film_glass{T(0.72), T(1), T(0.725), T(0.85), T(0.525), T(1.35), 0.5, 0.91},
                               film_glass{T(0.72), T(1), T(0.725), T(0.85), T(0.525), T(1.35), 0.2, 1.2},
                               film_glass{T(0.3), T(0.14), T(0.426), T(1), T(0.774), T(2.1), 1.0, 0.0},
                               film_glass{T(0.3), T(0.14), T(0.426), T(1), T(0.774), T(2.1), 0.5, 0.6}}) {
        params<T> p = white<T>();
        p.specular_roughness = g.roughness;
        p.specular_roughness_anisotropy = g.anisotropy;
        p.specular_ior = g.ior;
        p.transmission_weight = T(1);
        p.thin_film_weight = g.film_weight;
        p.thin_film_thickness = g.thickness;
        p.thin_film_ior = g.film_ior;
        const surface<T> m(p);
        const auto reading = furnace_stratified(m, view_at_cosine(at, g.mu, g.phi), at, double(g.ior), 48, 32, 4);
        INFO("roughness ", double(g.roughness), " anisotropy ", double(g.anisotropy), " specular_ior ", double(g.ior),
             " mu ", g.mu, " phi ", g.phi, ": ", reading.first, " +- ", reading.second);
        CHECK(reading.second < 0.01);
        CHECK(reading.first <= 1.001 + 4 * reading.second);
        CHECK(reading.first >= 0.99 - 4 * reading.second);
        low = std::min(low, reading.first);
        high = std::max(high, reading.first);
    }
    MESSAGE("anisotropic thin-film glass below an index ratio of 1, white furnace: " << low << " to " << high);
}

TEST_CASE("openpbr_surface: white furnace of a thin film over glass below 1 on a narrow isotropic lobe") {
    // A film over a base of specular_ior below 1 reflects totally under the base's critical
    // cosine mu_c; a narrow lobe's share of it steps from 1 toward F_film within about alpha
    // of mu_c, which the film row's 64 view nodes bridged from above across a whole cell. A
    // random scan's material (issue #32, seed 8's k 242: film 0.74 of 1.392 um at index 1.59
    // over glass of specular_ior 0.855, roughness 0 roughened to alpha 0.003 by a coat of
    // weight 0.06, metalness 0.19) read 0.917 at mu 0.5 (mu_c 0.519); the same glass uncoated
    // at roughness 0.05 and 0.2. With the narrow lobe's window of views around mu_c
    // (detail::kink_view_window) issue #32's band holds, widened by 4 standard errors of
    // furnace_stratified (48^2 u strata). Last, a thinner film (0.5 of 0.3 um at 1.5) over
    // glass of specular_ior 0.45 at roughness 0.02 just above mu_c (0.893): the transmission
    // lobe, divided by 1 - R_ss, read R_ss from the reflection row, high there by up to 9e-3
    // (furnace 1.0043 at mu_c + 0.0005); it reads the lobe's window at or below R_ss now. At
    // most 1.001 there; within 0.005 above mu_c the band's low end is not asserted (0.989 at
    // mu_c + 0.0005: the window's read below R_ss).
    using T = double;
    const auto at = check_test::model_point<T>();
    furnace_band band;
    double near_high = 0;
    for (int variant = 0; variant < 4; ++variant) {
        params<T> p = white<T>();
        p.specular_roughness = variant == 0 ? T(0) : variant == 1 ? T(0.05) : T(0.2);
        p.specular_ior = T(0.855);
        p.transmission_weight = T(1);
        p.thin_film_weight = T(0.74);
        p.thin_film_thickness = T(1.392);
        p.thin_film_ior = T(1.59);
        if (variant == 0) {
            p.base_metalness = T(0.19);
            p.coat_weight = T(0.06);
            p.coat_roughness = T(0.76);
            p.coat_ior = T(2.76);
            p.base_diffuse_roughness = T(0.41);
        }
        if (variant == 3) {
            p.specular_roughness = T(0.02);
            p.specular_ior = T(0.45);
            p.thin_film_weight = T(0.5);
            p.thin_film_thickness = T(0.3);
            p.thin_film_ior = T(1.5);
        }
        const surface<T> m(p);
        const double mu_c = std::sqrt(1 - double(p.specular_ior) * double(p.specular_ior));
        const std::array<double, 4> views = variant < 3 ? std::array<double, 4>{0.5, 0.512, 0.519, 0.53}
                                                        : std::array<double, 4>{mu_c - 0.002, mu_c + 0.0005,
                                                                                mu_c + 0.001, mu_c + 0.007};
        for (const double mu : views) {
            const auto reading =
                furnace_stratified(m, view_at_cosine(at, mu, 3.968), at, double(p.specular_ior), 48, 32, 4);
            INFO("variant ", variant, " mu ", mu, ": ", reading.first, " +- ", reading.second);
            CHECK(reading.second < 0.01);
            if (mu > mu_c && mu < mu_c + 0.005) {
                CHECK(reading.first <= 1.001 + 4 * reading.second);
                near_high = std::max(near_high, reading.first);
            } else {
                band.check(reading);
            }
        }
    }
    MESSAGE("thin film over glass below 1, narrow isotropic lobes, white furnace: "
            << band.low << " to " << band.high << " (within 0.005 above mu_c: up to " << near_high << ")");
}

TEST_CASE("openpbr_surface: white furnace of an opaque dielectric below an index ratio of 1, isotropic") {
    // specular_ior below 1, uncoated, opaque (white diffuse base), and the same indices and
    // roughnesses as coat_ior of a full coat over the default dielectric: the furnace reads
    // 1 + R_ss,true - R_ss,read, nothing cancels the lobe's albedo. The reflection row (33
    // view nodes) read R_ss low near the critical cosine mu_c for narrow lobes and slightly
    // low at grazing views: measured 1.094 (index 0.3, roughness 0.05, mu 0.945; mu_c
    // 0.954), 1.0089 (0.65, 0.05, mu 0.76), 1.0025 (0.7, roughness 0.15, mu 0.1), the coat
    // alike.
    // With the row raised below 1 and the narrow lobe's window of views around mu_c
    // (detail::kink_view_window of F itself, mu_c on a node), never above 1.001 (4 standard
    // errors of furnace_stratified, 48^2 u strata); the band's 0.99 everywhere but in the
    // window's cell just above mu_c, where a narrow lobe's R_ss falls faster than the
    // window's cells (0.981 at 0.955 for the first material; before 0.613).
    using T = double;
    const auto at = check_test::model_point<T>();
    struct opaque {
        T ior, roughness;
    };
    furnace_band band;
    double highest_near = 0;
    for (const bool coat : {false, true}) {
        for (const opaque o : {opaque{T(0.3), T(0.05)}, opaque{T(0.65), T(0.05)}, opaque{T(0.7), T(0.15)},
                               opaque{T(0.9), T(0.02)}, opaque{T(0.95), T(0.3)}}) {
            params<T> p = white<T>();
            if (coat) {
                p.coat_weight = T(1);
                p.coat_ior = o.ior;
                p.coat_roughness = o.roughness;
            } else {
                p.specular_ior = o.ior;
                p.specular_roughness = o.roughness;
            }
            const surface<T> m(p);
            const double mu_c = std::sqrt(1 - double(o.ior) * double(o.ior));
            for (const double mu : {0.1, 0.3, mu_c - 0.01, mu_c - 0.004, mu_c - 0.001, mu_c + 0.001, mu_c + 0.01, 0.9}) {
                if (!(mu >= 0.1 && mu < 1)) continue;
                const auto reading = furnace_stratified(m, view_at_cosine(at, mu, 0.7), at, 1.0, 48, 32, 4);
                INFO((coat ? "coat" : "specular"), " ior ", double(o.ior), " roughness ", double(o.roughness), " mu ", mu,
                     " (mu_c ", mu_c, "): ", reading.first, " +- ", reading.second);
                CHECK(reading.second < 0.01);
                if (mu > mu_c && mu < mu_c + 0.005) {
                    CHECK(reading.first <= 1.001 + 4 * reading.second);
                    highest_near = std::max(highest_near, reading.first);
                } else {
                    band.check(reading);
                }
            }
        }
    }
    MESSAGE("opaque dielectric below 1, white furnace: " << band.low << " to " << band.high
                                                         << " (just above mu_c: up to " << highest_near << ")");
}

TEST_CASE("openpbr_surface: white furnace of an opaque dielectric below an index ratio of 1, anisotropic, around the critical cosine") {
    // The anisotropic form of the test above: specular (or a full coat's) index below 1,
    // narrow anisotropic lobes, views within 0.004 of the critical cosine mu_c at three
    // azimuths. R_ss came from the interface's grid, whose rows bridge a narrow lobe's step
    // at mu_c with chords reading it low: measured 1.042 (index 0.5, roughness 0.05,
    // anisotropy 0.7, mu_c - 0.001, azimuth pi / 2), 1.016-1.020 (0.9, 0.08, 1; mu_c + 0.002),
    // 1.018 (0.7, 0.1, 0.9; mu_c - 0.001). Now it is read from the interface's
    // anisotropic_kink_window there: the band [0.99, 1.001] (4 standard errors of
    // furnace_stratified, 48^2 u strata).
    using T = double;
    const auto at = check_test::model_point<T>();
    struct opaque {
        T ior, roughness, anisotropy;
    };
    furnace_band band;
    for (const bool coat : {false, true}) {
        for (const opaque o : {opaque{T(0.5), T(0.05), T(0.7)}, opaque{T(0.9), T(0.08), T(1)},
                               opaque{T(0.7), T(0.1), T(0.9)}, opaque{T(0.3), T(0.2), T(0.5)}}) {
            params<T> p = white<T>();
            if (coat) {
                p.coat_weight = T(1);
                p.coat_ior = o.ior;
                p.coat_roughness = o.roughness;
                p.coat_roughness_anisotropy = o.anisotropy;
            } else {
                p.specular_ior = o.ior;
                p.specular_roughness = o.roughness;
                p.specular_roughness_anisotropy = o.anisotropy;
            }
            const surface<T> m(p);
            const double mu_c = std::sqrt(1 - double(o.ior) * double(o.ior));
            for (const double offset : {-0.004, -0.001, -0.0003, 0.0003, 0.001, 0.004})
                for (const double phi : {0.0, 0.8, 1.5708}) {
                    const double mu = mu_c + offset;
                    const auto reading = furnace_stratified(m, view_at_cosine(at, mu, phi), at, 1.0, 48, 32, 4);
                    INFO((coat ? "coat" : "specular"), " ior ", double(o.ior), " roughness ", double(o.roughness),
                         " anisotropy ", double(o.anisotropy), " mu ", mu, " (mu_c ", mu_c, ") phi ", phi, ": ",
                         reading.first, " +- ", reading.second);
                    CHECK(reading.second < 0.01);
                    band.check(reading);
                }
        }
    }
    MESSAGE("opaque anisotropic dielectric below 1 around mu_c, white furnace: " << band.low << " to " << band.high);
}

TEST_CASE("openpbr_surface: white furnace of a thin film over an anisotropic dielectric below 1 around the film's own kink") {
    // A film over a base of specular_ior n_b < 1 reflects totally under the base's critical
    // cosine sqrt(1 - n_b^2); at specular_weight < 1 the specular lobe's index (and so the
    // grid's dense rows) is elsewhere, and the film's share D on the grid's sparse rows there
    // read E_spec low: measured 1.118 (opaque, n_b 0.5196, roughness 0.0344, anisotropy
    // 0.255, film 0.175 um, specular_weight 0.74, mu at the kink - 0.0008), 1.116 as glass
    // (1.051 before the R_ss window), 1.041 as glass at n_b 0.6146, roughness 0.101,
    // anisotropy 0.351, film 0.308 um, specular_weight 0.611. Around the lobe's own critical
    // cosine (at its modulated index) R_ss is read from its window but D was the grid's,
    // relative to the grid's R_ss: 1.007 (opaque, n_b 0.5977, roughness 0.0503, anisotropy
    // 0.423, film 0.639 um, specular_weight 0.524). The grid now integrates the
    // film's albedo on a window around that kink (anisotropic_reflection_albedo_grid's
    // other_kink): the band [0.99, 1.001] (4 standard errors, 48^2 u strata), with and
    // without specular_weight (measured 0.9926-1.0010; 0.856-1.119 and 89 of 324 assertions
    // failing before). Glass under the film reads R_ss without the grid's margin in R_ss's
    // window (1.006 with it, at specular_weight 1 just under the kink).
    using T = double;
    const auto at = check_test::model_point<T>();
    struct filmed {
        T ior, roughness, anisotropy, thickness, specular_weight;
    };
    furnace_band band;
    for (const filmed f : {filmed{T(0.5196), T(0.0344), T(0.255), T(0.175), T(0.74)},
                           filmed{T(0.5196), T(0.0344), T(0.255), T(0.175), T(1)},
                           filmed{T(0.6146), T(0.101), T(0.351), T(0.308), T(0.611)},
                           filmed{T(0.5977), T(0.0503), T(0.423), T(0.639), T(0.524)}})
        for (const bool glass : {false, true}) {
            params<T> p = white<T>();
            p.specular_ior = f.ior;
            p.specular_roughness = f.roughness;
            p.specular_roughness_anisotropy = f.anisotropy;
            p.specular_weight = f.specular_weight;
            p.thin_film_weight = T(1);
            p.thin_film_thickness = f.thickness;
            if (glass) p.transmission_weight = T(1);
            const surface<T> m(p);
            // The film's kink, and the specular lobe's critical cosine at its modulated index.
            const double kink = std::sqrt(1 - double(f.ior) * double(f.ior));
            const double eta_lobe = double(shade::openpbr::modulated_ior_ratio(f.ior, f.specular_weight));
            const double lobe_kink = std::sqrt(1 - eta_lobe * eta_lobe);
            for (const double offset : {-0.003, -0.0008, -0.0002, 0.0003, 0.001, 0.003, 10.0, 9.9997, 10.0003, 10.004})
                for (const double phi : {0.8, 3.8, 5.3}) {
                    // Offsets from 10 on: around the lobe's critical cosine instead.
                    const double mu = offset < 5 ? kink + offset : lobe_kink + (offset - 10.0);
                    if (offset > 5 && f.specular_weight == T(1)) continue;
                    const auto reading = furnace_stratified(m, view_at_cosine(at, mu, phi), at,
                                                            glass ? double(f.ior) : 1.0, 48, 32, 4);
                    INFO((glass ? "glass" : "opaque"), " ior ", double(f.ior), " roughness ", double(f.roughness),
                         " anisotropy ", double(f.anisotropy), " film ", double(f.thickness), " um, specular_weight ",
                         double(f.specular_weight), " mu ", mu, " (kink ", kink, ") phi ", phi, ": ", reading.first,
                         " +- ", reading.second);
                    CHECK(reading.second < 0.01);
                    band.check(reading);
                }
        }
    MESSAGE("thin film over an anisotropic dielectric below 1 around the film's kink, white furnace: "
            << band.low << " to " << band.high);
}

TEST_CASE("openpbr_surface: glass below an index ratio of 1/3 never reads its furnace above 1.001") {
    // specular_ior 0.3 (beyond the reflection table's index range, 1/3 to 3), roughness 0.5:
    // with specular_weight 0.7 (E_spec at another index) or a film E_spec is not the
    // interface's R_ss, and the transmission lobe, divided by 1 - R_ss, read R_ss from the
    // row, up to 6e-2 high there: furnace 1.034-1.041 at mu 0.94-0.97 (1.006-1.011 with the
    // film). It reads the interface's own R_ss over every view at or below its value now
    // (a kink_view_window reaching the whole range). Only the upper bound is the issue's
    // here (E_spec's row reads high beyond the table too: 0.955 with the film), within 4
    // standard errors of furnace_stratified (48^2 u strata).
    using T = double;
    const auto at = check_test::model_point<T>();
    double highest = 0;
    for (const bool film : {false, true}) {
        params<T> p = white<T>();
        p.specular_ior = T(0.3);
        p.specular_roughness = T(0.5);
        p.transmission_weight = T(1);
        if (film) {
            p.thin_film_weight = T(0.5);
            p.thin_film_thickness = T(0.3);
            p.thin_film_ior = T(1.5);
        } else {
            p.specular_weight = T(0.7);
        }
        const surface<T> m(p);
        for (const double mu : {0.3, 0.94, 0.97}) {
            const auto reading = furnace_stratified(m, view_at_cosine(at, mu, 0.3), at, 0.3, 48, 32, 4);
            INFO("film ", film, " mu ", mu, ": ", reading.first, " +- ", reading.second);
            CHECK(reading.second < 0.01);
            CHECK(reading.first <= 1.001 + 4 * reading.second);
            highest = std::max(highest, reading.first);
        }
    }
    MESSAGE("glass below an index ratio of 1/3, white furnace: at most " << highest);
}

TEST_CASE("openpbr_surface: white furnace of a thin film over an anisotropic base at specular_weight 0") {
    // specular_weight 0 switches the base's own reflection off (eta'_s = 1), not the film's:
    // the specular lobe reflects F_film alone. Anisotropic, its share is integrated on a grid
    // of the lobe's views as where R_ss is integrated (D alone, R_ss = 0); read as the
    // isotropic reference at alpha_v plus a tabulated anisotropic correction, a random scan's material (issue #32:
    // thin-walled, roughness 0.1, anisotropy 0.68, specular_ior 0.518, transmission 0.61,
    // film 0.81 of 0.78 um at index 1.08) read 0.985 at mu 0.2. Issue #32's band, widened by
    // 4 standard errors of furnace_stratified (48^2 u strata).
    using T = double;
    const auto at = check_test::model_point<T>();
    furnace_band band;
    for (const bool thin : {true, false}) {
        for (const T anisotropy : {T(0.68), T(0.95)}) {
            params<T> p = white<T>();
            p.specular_weight = T(0);
            p.specular_roughness = T(0.1);
            p.specular_roughness_anisotropy = anisotropy;
            p.specular_ior = T(0.518);
            p.transmission_weight = T(0.61);
            p.thin_film_weight = T(0.81);
            p.thin_film_thickness = T(0.78);
            p.thin_film_ior = T(1.08);
            p.base_diffuse_roughness = T(0.25);
            p.geometry_thin_walled = thin;
            const surface<T> m(p);
            for (const double mu : {0.2, 0.5, 1.0}) {
                const auto reading =
                    furnace_stratified(m, view_at_cosine(at, mu, 1.37), at, thin ? 1.0 : 0.518, 48, 32, 4);
                INFO("thin-walled ", thin, " anisotropy ", double(anisotropy), " mu ", mu, ": ", reading.first, " +- ",
                     reading.second);
                CHECK(reading.second < 0.01);
                band.check(reading);
            }
        }
    }
    MESSAGE("thin film over an anisotropic base at specular_weight 0, white furnace: " << band.low << " to " << band.high);
}

TEST_CASE("openpbr_surface: copies of a material below an index ratio of 1 keep its windows of views") {
    // Below an index ratio of 1 a narrow isotropic lobe reads R_ss around the critical cosine
    // from a detail::kink_view_window whose values live in a heap block (specular, coat and,
    // below 1/3, the transmission's): a copy (copy construction, copy assignment, move)
    // evaluates as the original did after the original is gone (a freed or shared block
    // would read freed memory under the sanitizers; here the values would differ), and an
    // empty window's copy stays empty.
    using T = double;
    const auto at = check_test::model_point<T>();
    for (const bool coated : {false, true}) {
        params<T> p = white<T>();
        // Uncoated: the specular lobe's window (eta'_s 0.45) and, with a film, the transmission
        // reading it; coated: the coat's (coat_ior 0.65) and the transmission's own (specular_ior
        // 0.3, E_spec at another index).
        p.specular_ior = coated ? T(0.3) : T(0.45);
        p.specular_roughness = T(0.05);
        p.transmission_weight = T(0.5);
        if (coated) {
            p.specular_weight = T(0.7);
            p.coat_weight = T(0.5);
            p.coat_ior = T(0.65);
            p.coat_roughness = T(0.05);
        } else {
            p.thin_film_weight = T(0.5);
        }
        const double n = coated ? 0.65 : 0.45;
        const double mu_c = std::sqrt(1 - n * n);
        const vec3<T> v = view_at_cosine(at, mu_c + 0.001, 0.7);
        const vec3<T> l_reflected = view_at_cosine(at, 0.6, 2.0);
        const vec3<T> l_transmitted = glm::normalize(vec3<T>(0.2, -0.1, 0) - at.n());
        rgb<T> f_reflected{}, f_transmitted{};
        T pdf_reflected = 0;
        std::optional<surface<T>> copied, assigned, moved;
        {
            const surface<T> original(p);
            f_reflected = original.f(l_reflected, v, at);
            f_transmitted = original.f(l_transmitted, v, at);
            pdf_reflected = original.pdf(l_reflected, v, at);
            copied.emplace(original);
            surface<T> other(white<T>());
            other = original;
            assigned.emplace(other);
            surface<T> temporary(original);
            moved.emplace(std::move(temporary));
        }
        CHECK(f_reflected.x > 0);
        CHECK(f_transmitted.x > 0);
        for (const auto* m : {&*copied, &*assigned, &*moved}) {
            CHECK(m->f(l_reflected, v, at).x == f_reflected.x);
            CHECK(m->f(l_transmitted, v, at).x == f_transmitted.x);
            CHECK(m->pdf(l_reflected, v, at) == pdf_reflected);
        }
        // A material without windows, copied and assigned over one with them.
        surface<T> plain(white<T>());
        plain = *copied;
        CHECK(plain.f(l_reflected, v, at).x == f_reflected.x);
        *copied = surface<T>(white<T>());
        CHECK(copied->f(l_reflected, v, at).x == surface<T>(white<T>()).f(l_reflected, v, at).x);
    }
}

TEST_CASE("openpbr_surface: with interface_albedo::grid, copies share the grid and outlive the material that built it") {
    // The transmission lobe points to a grid on the heap that the material's copies share;
    // a copy (made by copy construction, copy assignment or move) evaluates as the original
    // did after the original is gone (a dangling grid would read freed memory: the sanitizer
    // build reports it; here the values would differ).
    using T = double;
    const auto at = check_test::model_point<T>();
    params<T> glass = white<T>();
    glass.specular_roughness = T(0.5);
    glass.specular_roughness_anisotropy = T(0.8);
    glass.specular_ior = T(0.8);
    glass.transmission_weight = T(1);
    const vec3<T> v = view_at_cosine(at, 0.3, 0.7);
    const vec3<T> l_reflected = view_at_cosine(at, 0.6, 2.0);
    const vec3<T> l_transmitted = glm::normalize(vec3<T>(0.2, -0.1, 0) - at.n());
    rgb<T> f_reflected{}, f_transmitted{};
    std::optional<surface<T>> copied, assigned, moved;
    {
        const surface<T> original(glass, shade::layering::albedo_scaling, shade::openpbr::interface_albedo::grid);
        f_reflected = original.f(l_reflected, v, at);
        f_transmitted = original.f(l_transmitted, v, at);
        copied.emplace(original);
        surface<T> other(white<T>());
        other = original;
        assigned.emplace(other);
        surface<T> temporary(original);
        moved.emplace(std::move(temporary));
    }
    CHECK(f_transmitted.x > 0);
    for (const auto* m : {&*copied, &*assigned, &*moved}) {
        CHECK(m->albedo_source() == shade::openpbr::interface_albedo::grid);
        CHECK(m->f(l_reflected, v, at).x == f_reflected.x);
        CHECK(m->f(l_transmitted, v, at).x == f_transmitted.x);
    }
    // The default reads the tables: another E_s, so another value.
    const surface<T> tables(glass);
    CHECK(tables.albedo_source() == shade::openpbr::interface_albedo::tables);
    CHECK(tables.f(l_transmitted, v, at).x != f_transmitted.x);
}

TEST_CASE("openpbr_surface: white furnace of glass above the tables' index 3, stratified") {
    // Glass (transmission_weight 1) at specular_ior 6 and 20, roughness 0.4 and 1, seen from
    // outside at mu 1, 0.5, 0.1: compensated_rough_dielectric reads E_s from the
    // continuation tables above eta_hat 3 and the reflection is scaled by
    // dielectric_reflection_albedo's continuation, so the furnace reads 1 up to those
    // (furnace_stratified as in the anisotropic glass test). Reading the tables' ends at 3
    // instead gave 0.54-0.72 at normal views of roughness 1 (specular_ior 20) and up to
    // 1.007 at mu 0.1 (specular_ior 6).
    using T = double;
    const auto at = check_test::model_point<T>();
    furnace_band band;
    for (const T ior : {T(6), T(20)}) {
        for (const T r : {T(0.4), T(1)}) {
            params<T> glass = white<T>();
            glass.specular_roughness = r;
            glass.specular_ior = ior;
            glass.transmission_weight = T(1);
            const surface<T> m(glass);
            for (const double mu : {1.0, 0.5, 0.1}) {
                const auto reading = furnace_stratified(m, view_at_cosine(at, mu), at, double(ior), 32, 32, 4);
                INFO("ior ", double(ior), " roughness ", double(r), " mu ", mu, ": ", reading.first, " +- ", reading.second);
                CHECK(reading.second < 0.02);
                band.check(reading);
            }
        }
    }
    MESSAGE("glass above index 3, white furnace: " << band.low << " to " << band.high);
}

TEST_CASE("openpbr_surface: the anisotropic reflection albedo's furnace error, without sampling noise") {
    // Over a white, energy-conserving base the furnace reads 1 + E_true(v) - E_read(v) for
    // the coat and the dielectric specular, E_read the anisotropic
    // shade::dielectric_reflection_albedo at the lobe's alphas (openpbr::roughness_to_alpha,
    // alpha_b at least openpbr::smallest_alpha) and E_true a fresh 64^2 estimate by
    // rough_dielectric's own sampler. Views mu 1 to 0.1 at eight azimuths, roughness 0.1 to
    // 1 (0.95 between the exiting side's last two roughness nodes), anisotropy 0.5, 0.9 and 1
    // (a 1-D rough surface). Seen from outside at the default indices (specular 1.5, coat
    // 1.6), and index ratios below 1 (eta_s = 1 / 1.0667, 1 / 1.25, 1 / 1.5, 1 / 2.5 and 1 /
    // 3, on and between the eta nodes; total internal reflection), which the material reaches
    // with a specular_ior below 1 (under a denser coat the specification's TIR fix,
    // openpbr::specular_ior_ratio, reads n_c / n_b > 1 from outside). The issue's band is
    // [0.99, 1.001]; each reading is held to its band's bounds widened by 4 standard errors of
    // E_true: the issue's where met, else the measured value (docs/properties.md). From
    // outside the whole band holds at anisotropy 0.5, 0.9 and 1 (measured 0.9934 to 0.9997;
    // the lowest at anisotropy 1, roughness 1, mu 0.1, the view along the smoother axis). From
    // inside the upper bound holds but at eta_s 1 / 1.5, anisotropy 1, roughness 0.1, mu 0.5,
    // the view along the smoother axis (1.0009 here, 1.00104 +- 4e-5 with 256^2 samples: y
    // between the smooth row and the first node); the low ends are the measured ones
    // (grazing views of 1-D rough surfaces, where the table reads high, and the envelope's two
    // standard errors of its check estimates).
    struct band {
        double eta_s;
        double anisotropy;
        double low, high;
    };
    const band bands[] = {{1.5, 0.5, 0.99, 1.001},           {1.5, 0.9, 0.99, 1.001},           {1.5, 1.0, 0.99, 1.001},
                          {1.6, 0.5, 0.99, 1.001},           {1.6, 0.9, 0.99, 1.001},           {1.6, 1.0, 0.99, 1.001},
                          {1 / 1.0666666666666667, 0.5, 0.9797, 1.001}, {1 / 1.0666666666666667, 0.9, 0.9653, 1.001},
                          {1 / 1.0666666666666667, 1.0, 0.9038, 1.001},  {1 / 1.5, 0.5, 0.9695, 1.001},
                          {1 / 1.5, 0.9, 0.9619, 1.001},     {1 / 1.5, 1.0, 0.9835, 1.0011},    {1 / 3.0, 0.5, 0.9706, 1.001},
                          {1 / 3.0, 0.9, 0.9586, 1.001},     {1 / 3.0, 1.0, 0.9355, 1.001},
                          {1 / 1.25, 0.5, 0.9667, 1.001},    {1 / 1.25, 1.0, 0.9710, 1.001},
                          {1 / 2.5, 0.5, 0.9665, 1.001},     {1 / 2.5, 1.0, 0.9200, 1.001}};
    for (const band& b : bands) {
        double low = 2, high = 0;
        for (const double r : {0.1, 0.2, 0.3, 0.5, 0.7, 0.95, 1.0}) {
            const auto alpha = shade::openpbr::roughness_to_alpha(r, b.anisotropy);
            const double alpha_x = alpha.t, alpha_y = std::max(alpha.b, shade::openpbr::smallest_alpha<double>);
            const shade::rough_dielectric<shade::ggx<double>> model(shade::ggx<double>(alpha_x, alpha_y),
                                                                    b.eta_s > 1 ? b.eta_s : 1 / b.eta_s);
            for (const double mu : {0.1, 0.2, 0.3, 0.5, 0.8, 1.0})
                for (int k = 0; k < 8; ++k) {
                    const double phi = k * shade::pi<double> / 8, s = std::sqrt((1 - mu) * (1 + mu));
                    const vec3<double> v(s * std::cos(phi), s * std::sin(phi), b.eta_s > 1 ? mu : -mu);
                    const auto fresh = bsdf_test::single_scattering_reflection(model, v, 64, std::uint64_t(5 + k));
                    const double reading = 1 + fresh.albedo.x - shade::dielectric_reflection_albedo(v, alpha_x, alpha_y, b.eta_s);
                    INFO("eta_s ", b.eta_s, " anisotropy ", b.anisotropy, " roughness ", r, " mu ", mu, " phi ", phi, ": ",
                         reading);
                    CHECK(reading >= b.low - 4 * fresh.standard_error.x);
                    CHECK(reading <= b.high + 4 * fresh.standard_error.x);
                    low = std::min(low, reading);
                    high = std::max(high, reading);
                }
        }
        MESSAGE("eta_s " << b.eta_s << ", anisotropy " << b.anisotropy << ": furnace " << low << " to " << high);
    }
}

// Film parameters of the thin-film furnace tests: weight, thickness (um), film index, base
// index; thin to thick films, the specification's soft index range [1, 3] and both weights.
template <class T>
using film_point = film_test::film_point<T>;

template <class T>
std::vector<film_point<T>> film_points() {
    return {{1, T(0.1), T(1.1), T(1.5)}, {1, T(0.3), T(1.1), T(1.5)}, {1, T(0.5), T(1.4), T(1.5)},
            {1, T(0.8), T(2), T(1.5)},   {1, T(1), T(3), T(1.5)},     {1, T(3), T(2), T(1.5)},
            {1, T(0.4), T(1), T(1.33)},  {1, T(0.6), T(1.6), T(2)},   {T(0.5), T(0.3), T(2), T(1.5)},
            {T(0.5), T(1.5), T(1.3), T(1.8)}};
}

using film_test::film_albedo_error;

TEST_CASE_TEMPLATE("openpbr_surface: white furnace with a thin film, read through the specular albedo", T, float,
                   double) {
    // film_albedo_error at the film points, roughness 0.1 to 1, mu 0.1 to 1. The issue's
    // band [0.99, 1.001] is E_R - E_R,true in [-1e-3, 1e-2]; the table's stated accuracy is
    // [-2.9e-4, +1.6e-3] for these sums. float: f's rounding adds 2e-5.
    const double tol = std::is_same_v<T, float> ? 2e-5 : 0.0;
    double lowest = 1, highest = -1;
    for (const auto& fl : film_points<T>()) {
        for (const T r : {T(0.1), T(0.3), T(0.6), T(1)}) {
            for (const double mu : {1.0, 0.5, 0.2, 0.1}) {
                const rgb<double> error = film_albedo_error(fl, r, mu);
                for (int k = 0; k < 3; ++k) {
                    INFO("film weight ", double(fl.weight), " thickness ", double(fl.thickness_um), " film ior ",
                         double(fl.ior), " base ior ", double(fl.base_ior), " roughness ", double(r), " mu ", mu,
                         " channel ", k, ": E_R read - true ", error[k]);
                    CHECK(error[k] >= -1e-3 - tol);
                    CHECK(error[k] <= 1e-2 + tol);
                    lowest = std::min(lowest, error[k]);
                    highest = std::max(highest, error[k]);
                }
            }
        }
    }
    MESSAGE("thin film: E_R read - true in [", lowest, ", ", highest, "] (white furnace 1 - that)");
}

TEST_CASE_TEMPLATE("openpbr_surface: a thin film's share of E_spec never reads low, on narrow lobes too", T, float,
                   double) {
    // Where the film's reflectance oscillates in c faster than the 64 nodes of
    // cosine_weights.hpp resolve (a low film index, whose refraction angle, and so its
    // optical path, changes most with c, at 1.5 to 5 um; or a thin film of high index) and
    // the lobe is narrower than a node spacing, the node sum misses the fringe, by up to
    // 8e-3 low and 1e-2 high at film index >= 1.1 (2e-2 below); the row is raised by the margin of
    // thin_film_margin_data.hpp (per film index, the largest shortfall over the films of
    // the specification's range, from the generator), so that the white furnace
    // 1 + E_R,true - E_R stays at most 1.001 anywhere: E_R read - true >= -1e-3. The
    // issue's low end 0.99 (read - true <= 1e-2) holds at film index >= 1.2 with eta'_s the
    // film's base index; below (and for another eta'_s, the margin's table 1) the margin
    // that keeps the read from falling short reads it high by more: the generator states
    // at most 1.33e-2 at index >= 1.1 and 4.2e-2 at 1.01-1.075, asserted here. The films
    // where the margin was largest (index 1.05 and 1.1 at 2-3 um, index 3 at 0.05 um), two
    // at weight 0.5 and one at specular_weight 0.5 (eta'_s 1.33), on the narrow lobes
    // (roughness 0.02-0.2) and a wide one, mu 0.1-0.7. float: f's rounding adds 2e-5.
    const double tol = std::is_same_v<T, float> ? 2e-5 : 0.0;
    const std::vector<film_point<T>> corners = {
        {1, T(2), T(1.05), T(1.5)},        {1, T(3), T(1.05), T(1.5)},       {1, T(3), T(1.1), T(1.5)},
        {1, T(0.05), T(3), T(1.5)},        {1, T(1.2), T(1.2), T(2)},        {T(0.5), T(2.5), T(1.05), T(1.33)},
        {T(0.5), T(0.7), T(2.5), T(3)},    {1, T(2), T(1.1), T(1.5), T(0.5)}};
    double lowest = 1, highest = -1;
    for (const auto& fl : corners) {
        for (const T r : {T(0.02), T(0.05), T(0.1), T(0.2), T(0.5)}) {
            for (const double mu : {0.1, 0.15, 0.3, 0.7}) {
                const rgb<double> error = film_albedo_error(fl, r, mu);
                for (int k = 0; k < 3; ++k) {
                    INFO("weight ", double(fl.weight), " thickness ", double(fl.thickness_um), " film ior ",
                         double(fl.ior), " base ior ", double(fl.base_ior), " specular_weight ",
                         double(fl.specular_weight), " roughness ", double(r), " mu ", mu, " channel ", k,
                         ": E_R read - true ", error[k]);
                    CHECK(error[k] >= -1e-3 - tol);
                    CHECK(error[k] <= film_test::film_high_bound(fl) + tol);
                    lowest = std::min(lowest, error[k]);
                    highest = std::max(highest, error[k]);
                }
            }
        }
    }
    MESSAGE("thin film corners: E_R read - true in [", lowest, ", ", highest, "]");
}

TEST_CASE_TEMPLATE("openpbr_surface: a thin film of the usual range reads its share within its own bound", T, float,
                   double) {
    // Films up to 2.5 um are read with the film's own bound of the node sums' shortfall
    // (film_row_margin) where it is below the margin table's (the largest over every film of
    // the index, up to 10 um thick). Films of index 1.2-2.5 and 0.1-1 um over 1.33-2.2, at
    // specular_weight 1 and 0.5, roughness 0.05-1, mu 0.1-1: the read never falls short
    // (E_R read - true >= -1e-3: the white furnace stays at most 1.001) and reads high by at
    // most 4.5e-3 (measured 3.7e-3; the margin table alone reads up to 8.8e-3 high here).
    // float: f's rounding adds 2e-5.
    const double tol = std::is_same_v<T, float> ? 2e-5 : 0.0;
    const std::vector<film_point<T>> films = {
        {1, T(0.1), T(2.5), T(1.33)}, {1, T(0.3), T(1.4), T(1.5)},  {1, T(0.5), T(2), T(2.2)},
        {1, T(0.7), T(1.2), T(1.5)},  {1, T(1), T(1.7), T(1.33)},   {1, T(0.25), T(2.2), T(1.5), T(0.5)},
        {1, T(0.8), T(1.3), T(2.2), T(0.5)}};
    double lowest = 1, highest = -1;
    for (const auto& fl : films) {
        for (const T r : {T(0.05), T(0.15), T(0.3), T(0.6), T(1)}) {
            for (const double mu : {0.1, 0.2, 0.4, 0.7, 1.0}) {
                const rgb<double> error = film_albedo_error(fl, r, mu, 96);
                for (int k = 0; k < 3; ++k) {
                    INFO("thickness ", double(fl.thickness_um), " film ior ", double(fl.ior), " base ior ",
                         double(fl.base_ior), " specular_weight ", double(fl.specular_weight), " roughness ", double(r),
                         " mu ", mu, " channel ", k, ": E_R read - true ", error[k]);
                    CHECK(error[k] >= -1e-3 - tol);
                    CHECK(error[k] <= 4.5e-3 + tol);
                    lowest = std::min(lowest, error[k]);
                    highest = std::max(highest, error[k]);
                }
            }
        }
    }
    MESSAGE("thin films of the usual range: E_R read - true in [", lowest, ", ", highest, "]");
}

TEST_CASE_TEMPLATE("openpbr_surface: a thin film over a base of index below 1 never reads its share low", T, float,
                   double) {
    // Over specular_ior below 1 the film/base interface reflects totally under the base's
    // critical cosine mu_c = sqrt(1 - specular_ior^2), so F_film is 1 there and falls steeply
    // above it: a kink between two of the 64 nodes of cosine_weights.hpp, which their linear
    // interpolation cut off (E_R read 0.02-0.09 low at roughness 0.1-0.3 near mu_c, 1.4e-2 at
    // 0.3-1, before kink_cell_correction and kink_view_shortfall). The read must never fall
    // short (white furnace at most 1.001): E_R read - true >= -1e-3, at the critical cosine
    // and beside it too. What it reads high is bounded as measured: near mu_c (within 0.05) a
    // narrow lobe's E_R steps within about alpha of mu_c by up to 1 - F there, which the row's
    // view nodes bridge from above only across a whole cell (read up to 0.44 high at roughness
    // 0.05 and 0.23 at 0.1, and 1.6e-2 low at 0.05, before the kink's window of views,
    // detail::kink_view_window): there 2e-2 (measured 1.5e-2); elsewhere 1.5e-2 (1.04e-2).
    // Isotropic lobes; float: f's rounding adds 2e-5. The last film is scan seed 8's k 242
    // (a film over glass of specular_ior 0.855; its white furnace read 0.917 at mu 0.5). The
    // true E_R takes R_ss by the same quadrature (film_reader's r_ss_by_quadrature): below an
    // index ratio of 1 the material reads R_ss from its own window around mu_c, not from
    // the table the reader would otherwise count as true.
    const double tol = std::is_same_v<T, float> ? 2e-5 : 0.0;
    const std::vector<film_point<T>> films = {{1, T(0.5), T(1.4), T(0.4)},   {1, T(1.2), T(2.2), T(0.45)},
                                              {1, T(0.3), T(1.7), T(0.65)},  {1, T(0.9), T(2.4), T(0.8)},
                                              {T(0.6), T(0.7), T(1.5), T(0.9)}, {1, T(0.15), T(2), T(0.95)},
                                              {T(0.74), T(1.392), T(1.59), T(0.855)}};
    double lowest = 1, highest_near = -1, highest_far = -1;
    for (const auto& fl : films) {
        const double mu_c = std::sqrt(1 - double(fl.base_ior) * double(fl.base_ior));
        for (const T r : {T(0.05), T(0.1), T(0.25), T(0.6), T(1)}) {
            const film_test::film_reader<T> reader(fl, r, T(0));
            for (const double mu : {0.1, 0.3, mu_c - 0.02, mu_c - 0.005, mu_c - 0.002, mu_c, mu_c + 0.002,
                                    mu_c + 0.005, mu_c + 0.02, 0.9, 1.0}) {
                if (!(mu >= 0.05 && mu <= 1)) continue;
                const rgb<double> error = reader.error(mu, 0.4, 160, true);
                const bool near = std::abs(mu - mu_c) <= 0.05;
                for (int k = 0; k < 3; ++k) {
                    INFO("weight ", double(fl.weight), " thickness ", double(fl.thickness_um), " film ior ",
                         double(fl.ior), " base ior ", double(fl.base_ior), " roughness ", double(r), " mu ", mu,
                         " (mu_c ", mu_c, ") channel ", k, ": E_R read - true ", error[k]);
                    CHECK(error[k] >= -1e-3 - tol);
                    CHECK(error[k] <= (near ? 2e-2 : 1.5e-2) + tol);
                    lowest = std::min(lowest, error[k]);
                    (near ? highest_near : highest_far) = std::max(near ? highest_near : highest_far, error[k]);
                }
            }
        }
    }
    MESSAGE("thin film over a base below 1: E_R read - true >= ", lowest, "; at most ", highest_near,
            " within 0.05 of mu_c, ", highest_far, " elsewhere");
}

#if SHADE_TEST_FULL
// In the full suite only (about 20 s per type: each of 24 lobes' truth is its own quadrature
// at 160^2 points per view). The quick suite keeps the isotropic case above and the white
// furnace of anisotropic glass under a thin film below an index ratio of 1 (below).
TEST_CASE_TEMPLATE("openpbr_surface: an anisotropic lobe's thin film over a base of index below 1 never reads low", T,
                   float, double) {
    // The same kink for an anisotropic lobe. Its R_ss is integrated per interface below 1
    // (detail::anisotropic_reflection_albedo_grid), and the film's share with it in the same
    // pass, D(v) = int (F_film - F) G2 / G1 on the grid's nodes (rows dense toward the
    // critical cosine from both sides, where D steps; 0 in the cone of total reflection).
    // E_R read - true >= -1e-3 at the critical cosine, beside it and away from it, at
    // azimuths from the rougher axis to the smoother, anisotropy 0.5 to 1; high by at most
    // 3e-2: the grid's margins (5e-3, 1e-2 at strong anisotropy; D's 2e-3) and, at
    // anisotropy 1 just below the critical cosine, R_ss's step between two rows (measured
    // -6e-4 to 2.5e-2, 1.5e-2 below anisotropy 1. The share read from the isotropic
    // reference at alpha_v plus its anisotropic correction, lifted around the kink, read up
    // to 0.12 high here and 0.19 over 180 random films, and 0.13 low before the lift).
    const double tol = std::is_same_v<T, float> ? 2e-5 : 0.0;
    // Films of weight 1: there E_R is the share alone (the true E_R by the lobe's own
    // quadrature of F(eta'_s) as well, film_reader's r_ss_by_quadrature).
    const std::vector<film_point<T>> films = {{1, T(0.5), T(1.4), T(0.45)}, {1, T(1.2), T(2.2), T(0.6)},
                                              {1, T(0.8), T(1.8), T(0.8)}, {1, T(0.3), T(2), T(0.93)}};
    double lowest = 1, highest = -1;
    for (const auto& fl : films) {
        const double mu_c = std::sqrt(1 - double(fl.base_ior) * double(fl.base_ior));
        for (const T r : {T(0.3), T(0.6), T(1)}) {
            for (const T a : {T(0.5), T(0.9), T(1)}) {
                const film_test::film_reader<T> reader(fl, r, a);
                for (const double mu : {0.1, 0.3, mu_c - 0.02, mu_c, mu_c + 0.02, 0.9, 1.0}) {
                    if (!(mu >= 0.05 && mu <= 1)) continue;
                    for (const double phi : {0.0, 0.7, 1.2, 1.5}) {
                        const rgb<double> error = reader.error(mu, phi, 160, true);
                        for (int k = 0; k < 3; ++k) {
                            INFO("weight ", double(fl.weight), " thickness ", double(fl.thickness_um), " film ior ",
                                 double(fl.ior), " base ior ", double(fl.base_ior), " roughness ", double(r),
                                 " anisotropy ", double(a), " mu ", mu, " (mu_c ", mu_c, ") phi ", phi, " channel ", k,
                                 ": E_R read - true ", error[k]);
                            CHECK(error[k] >= -1e-3 - tol);
                            CHECK(error[k] <= 3e-2 + tol);
                            lowest = std::min(lowest, error[k]);
                            highest = std::max(highest, error[k]);
                        }
                    }
                }
            }
        }
    }
    MESSAGE("anisotropic, thin film over a base below 1: E_R read - true from ", lowest, " to ", highest);
}
#endif

TEST_CASE_TEMPLATE("openpbr_surface: white furnace with a thin film over metal and glass, and smooth", T, float,
                   double) {
    // End to end through sample(): the film over a white metal (Kulla-Conty compensation
    // with the film's Fresnel average), in glass, and at roughness 0 (exact: the film's
    // Fresnel at the view). Allowed: the issue's band widened by 4 standard errors of the
    // stratified estimate (48^2 draws; they are larger than the read-through test's error).
    const auto at = check_test::model_point<T>();
    const auto films = film_points<T>();
    furnace_band band;
    for (std::size_t i = 0; i < films.size(); i += 3) {
        const auto& fl = films[i];
        for (const T r : {T(0), T(0.3), T(1)}) {
            for (const int base : {0, 1, 2}) {
                params<T> p = white<T>();
                p.specular_roughness = r;
                p.specular_ior = fl.base_ior;
                p.thin_film_weight = fl.weight;
                p.thin_film_thickness = fl.thickness_um;
                p.thin_film_ior = fl.ior;
                if (base == 1) p.base_metalness = T(1);
                if (base == 2) p.transmission_weight = T(1);
                const surface<T> m(p);
                for (const double mu : {1.0, 0.3, 0.1}) {
                    const auto reading = furnace(m, view_at_cosine(at, mu), at, 48);
                    INFO("base ", base, " film ", i, " roughness ", double(r), " mu ", mu, ": ", reading.first, " +- ",
                         reading.second);
                    band.check(reading);
                }
            }
        }
    }
    MESSAGE("thin film over metal and glass, white furnace: " << band.low << " to " << band.high);
}

TEST_CASE_TEMPLATE("openpbr_surface: white furnace with a thin film under a coat, and over a base of index below 1", T,
                   float, double) {
    // Under a coat of index 1.6 the specular lobe's index ratio is n_c / n_b (the
    // specification's TIR fix): 1.067 over specular_ior 1.5 and 1.203 over 1.33, both in the
    // issue's band. Uncoated with specular_ior 0.9375 it is below 1: the dielectric's F and
    // the film's F_film (the film/base interface reflects totally at the same angle, by
    // Snell's invariant) are 1 below the critical cosine sqrt(1 - 0.9375^2) = 0.348 and fall
    // steeply above it, a kink between the nodes c_31 = 0.345 and c_32 = 0.362 of
    // cosine_weights.hpp. Summed as F_film - F at the nodes, E_spec came out 0.118 low at
    // roughness 0.02, mu 0.35 (furnace 1.118 +- 0.004, above the band); as F_film's node sum
    // minus the dielectric table's R_ss (which holds the kink), high: measured furnace
    // 0.9715 +- 0.0035 there, 0.981 to 0.996 at roughness 0.05 and 0.2, mu 0.35 and 0.36
    // (0.9916 without the film). That corner is asserted at its measured range, below the
    // band's upper bound; it needs a node at the critical cosine. Allowed elsewhere: the
    // issue's band widened by 4 standard errors of the stratified estimate (48^2 draws).
    const auto at = check_test::model_point<T>();
    struct base_case {
        T specular_ior, coat_weight;
    };
    for (const base_case b : {base_case{T(1.5), T(1)}, base_case{T(1.33), T(1)}, base_case{T(0.9375), T(0)}}) {
        for (const T r : {T(0.02), T(0.05), T(0.2)}) {
            for (const double mu : {0.35, 0.36, 0.5}) {
                params<T> p = white<T>();
                p.specular_roughness = r;
                p.specular_ior = b.specular_ior;
                p.coat_weight = b.coat_weight;
                p.coat_ior = T(1.6);
                p.coat_roughness = T(0);
                p.thin_film_weight = T(1);
                p.thin_film_thickness = T(0.5);
                p.thin_film_ior = T(1.4);
                const surface<T> m(p);
                const auto reading = furnace(m, view_at_cosine(at, mu), at, 48);
                INFO("specular_ior ", double(b.specular_ior), " coat ", double(b.coat_weight), " roughness ",
                     double(r), " mu ", mu, ": ", reading.first, " +- ", reading.second);
                const bool kink = b.specular_ior < T(1) && mu < 0.4;
                CHECK(reading.first >= (kink ? 0.96 : 0.99) - 4 * reading.second);
                CHECK(reading.first <= 1.001 + 4 * reading.second);
            }
        }
    }
}

TEST_CASE_TEMPLATE("openpbr_surface: white furnace with a thin film at specular_weight 0.5 and on anisotropic lobes",
                   T, float, double) {
    // specular_weight 0.5 (eta'_s 1.33 at specular_ior 1.5: the film's share summed against
    // that index's Fresnel) and anisotropy 0.5 and 0.9 (the film's share read at the view's
    // azimuth, integrated with R_ss on the lobe's grid of views), over
    // a white diffuse base, end to end through sample(). Allowed: the issue's band widened by
    // 4 standard errors of the stratified estimate (48^2 draws); on the anisotropic lobes its
    // low end is the next test's high bound (read - true <= 5e-2: furnace >= 0.95).
    const auto at = check_test::model_point<T>();
    const auto films = film_points<T>();
    for (std::size_t i = 0; i < films.size(); i += 4) {
        const auto& fl = films[i];
        for (const T r : {T(0.1), T(0.3), T(0.7)}) {
            for (const T a : {T(0), T(0.5), T(0.9)}) {
                params<T> p = white<T>();
                p.specular_roughness = r;
                p.specular_roughness_anisotropy = a;
                p.specular_weight = a == T(0) ? T(0.5) : T(1);
                p.specular_ior = fl.base_ior;
                p.thin_film_weight = fl.weight;
                p.thin_film_thickness = fl.thickness_um;
                p.thin_film_ior = fl.ior;
                const surface<T> m(p);
                for (const double mu : {1.0, 0.3, 0.1}) {
                    const auto reading = furnace(m, view_at_cosine(at, mu), at, 48);
                    INFO("film ", i, " roughness ", double(r), " anisotropy ", double(a), " mu ", mu, ": ",
                         reading.first, " +- ", reading.second);
                    const bool anisotropic = a > T(0);
                    CHECK(reading.first >= (anisotropic ? 0.95 : 0.99) - 4 * reading.second);
                    CHECK(reading.first <= 1.001 + 4 * reading.second);
                }
            }
        }
    }
}

TEST_CASE_TEMPLATE("openpbr_surface: a thin film's share on anisotropic lobes never reads low (without sampling noise)", T,
                   float, double) {
    // film_albedo_error (the read against the anisotropic lobe's own quadrature of v·h, 96^2
    // cells, F_film read at each cell's cosine): never above the white furnace's 1.001 is
    // E_R read - true >= -1e-3, at every azimuth, anisotropy 0.5 to 1 (alpha_y / alpha_x
    // from 3 to 1e4, beyond the anisotropic albedo tables' 20) and roughness 0.3 to 1. The
    // films and views are where the read fell shortest, before the anisotropic lobe's own
    // grid (the isotropic node sum at the view's projected roughness: -4.3e-2 at index 3,
    // 0.25 um over 1.33, roughness 1, anisotropy 0.9, mu 0.1 along the tangent; -1.6e-1 at
    // anisotropy 1, index 1.05, 3 um, across it) and after it, before its margin (index
    // 1.05 at 1-3 um, mu 0.1-0.3, phi 1.2-pi/2, where the grid's margin stays 1.4e-2). The
    // high side (the furnace's low end): every anisotropic lobe with a film now integrates
    // R_ss and the film's share on a grid of its views (the true R_ss then by quadrature,
    // film_reader::integrates_r_ss), measured +4.2e-3 to +9.0e-3 (the margins of R_ss, 3e-3,
    // and of the share, 2e-3); asserted at 1.5e-2 for every film (the share read from the
    // isotropic reference plus a tabulated anisotropic correction reached 2.4e-2 at index 1.05 and 1.3e-2 at index
    // 1.2 and above, asserted at 3e-2 and 1.5e-2). float: f's rounding adds 2e-5.
    const double tol = std::is_same_v<T, float> ? 2e-5 : 0.0;
    const std::vector<film_point<T>> films = {{1, T(0.25), T(3), T(1.33)}, {1, T(3), T(1.05), T(1.5)},
                                              {1, T(1), T(1.05), T(1.5)},   {1, T(0.5), T(1.2), T(1.5)},
                                              {1, T(1), T(1.3), T(2.2)}};
    double lowest = 1, highest = -1, highest_from_1_2 = -1;
    for (const auto& fl : films) {
        for (const T r : {T(0.3), T(0.6), T(1)}) {
            for (const T a : {T(0.5), T(0.9), T(1)}) {
                for (const double mu : {0.1, 0.3, 1.0}) {
                    for (const double phi : {0.0, 1.2, 1.5708}) {
                        const film_test::film_reader<T> reader(fl, r, a);
                        const rgb<double> error = reader.error(mu, phi, 96, reader.integrates_r_ss());
                        for (int k = 0; k < 3; ++k) {
                            INFO("thickness ", double(fl.thickness_um), " film ior ", double(fl.ior), " base ior ",
                                 double(fl.base_ior), " roughness ", double(r), " anisotropy ", double(a), " mu ", mu,
                                 " phi ", phi, " channel ", k, ": E_R read - true ", error[k]);
                            CHECK(error[k] >= -1e-3 - tol);
                            CHECK(error[k] <= 1.5e-2 + tol);
                            if (fl.ior >= T(1.2)) {
                                CHECK(error[k] <= 1.5e-2 + tol);
                                highest_from_1_2 = std::max(highest_from_1_2, error[k]);
                            }
                            lowest = std::min(lowest, error[k]);
                            highest = std::max(highest, error[k]);
                        }
                    }
                }
            }
        }
    }
    MESSAGE("thin film, anisotropic: E_R read - true in [", lowest, ", ", highest, "] (film index >= 1.2: up to ",
            highest_from_1_2, ")");
}
