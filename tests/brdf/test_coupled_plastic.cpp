// shade::coupled_plastic: with a white base (k_d = 1) the albedo is in [0.97, 1.001] at
// every alpha in {0.05, 0.25, 0.5, 0.75, 1} and view cosine down to 0.05 (issue #19), with
// k_d = 0 it is the compensated coating exactly, the base term is reciprocal, and the
// property kit passes it.

#include <cmath>
#include <optional>
#include <string>

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/brdf/aliases.hpp>
#include <shade/brdf/coupled_plastic.hpp>
#include <shade/brdf/multiple_scattering.hpp>
#include <shade/bsdf/layer.hpp>
#include <shade/check/doctest.hpp>
#include <shade/check/properties.hpp>
#include <shade/core/error.hpp>
#include <shade/core/random.hpp>
#include <shade/core/sampling.hpp>

#include "brdf/properties_support.hpp"
#include "brdf/support.hpp"

using namespace brdf_test;
using shade::vec2;

static_assert(shade::sampled_brdf<shade::coupled_plastic<float>> && shade::split_brdf<shade::coupled_plastic<double>>);

namespace {

constexpr double alphas[] = {0.05, 0.25, 0.5, 0.75, 1.0};
constexpr double view_cosines[] = {1.0, 0.75, 0.5, 0.25, 0.1, 0.05};

template <class T>
vec3<T> view_of(double mu) {
    return vec3<T>(T(std::sqrt((1 - mu) * (1 + mu))), 0, T(mu));
}

} // namespace

TEST_CASE_TEMPLATE("coupled_plastic: with k_d = 1 the albedo is in [0.97, 1.001] at every roughness and view", T, float,
                   double) {
    // The albedo split into parts: the coating's single-scattering lobe E_F(mu), estimated
    // with its own visible-normal sampler (weight F G2 / G1: low variance; standard error
    // < 2e-4, asserted), and the parts that are exact by quadrature of the model's table
    // reads: the coating's multiple-scattering lobe F_ms (1 - E(mu)) (1 - A) / (1 - E_avg)
    // (A = 2 integral E mu), and the base k_d (1 - E_s(mu)) (1 - A_s) / (1 - E_s,avg)
    // (A_s = 2 integral E_s mu = E_s,avg up to the table's consistency). The model's own
    // sampler (noisier: three lobes) must agree with the split within 4 standard errors.
    using single_lobe = shade::cook_torrance<shade::ggx<T>, shade::dielectric_fresnel<T>, shade::smith_height_correlated<T>>;
    for (const double alpha : alphas) {
        CAPTURE(alpha);
        const shade::coupled_plastic<T> white(shade::ggx<T>(T(alpha)), rgb<T>(1));
        const auto& coating = white.coating();
        const single_lobe single(shade::ggx<T>(T(alpha)), shade::dielectric_fresnel<T>(T(1.5)));
        // The uncoupled rough_plastic (base k_d / pi simply added) reflects more than it
        // receives with the same white base: the coupling is what keeps it below 1.
        const auto uncoupled = shade::make_rough_plastic<T>(T(alpha), rgb<T>(1));
        const auto average = [](const auto& g) {
            double sum = 0;
            for (int i = 0; i < 20000; ++i) {
                const double mu = (i + 0.5) / 20000;
                sum += 2 * g(mu) * mu / 20000;
            }
            return sum;
        };
        const double e_avg = double(coating.average_single_scattering_albedo());
        const double a = average([&](double x) { return double(coating.single_scattering_albedo(T(x))); });
        const double a_s = average([&](double x) { return double(white.coating_albedo(T(x))); });
        const double f_ms = double(shade::detail::multiple_scattering_fresnel(
                                       shade::detail::fresnel_average<T>(shade::dielectric_fresnel<T>(T(1.5))), T(e_avg))
                                       .x);
        const double e_s_avg = double(shade::detail::albedo_average_lookup(shade::detail::ggx_dielectric_albedo_average,
                                                                           shade::detail::albedo_grid_nodes, T(alpha))) +
                               f_ms * (1 - e_avg);
        for (const double mu : view_cosines) {
            CAPTURE(mu);
            const auto ss = shade::check::sampled_albedo(single, view_of<T>(mu), flat<T>(), 192, 3);
            CHECK(ss.standard_error.x < 2e-4);
            const double coating_ms = f_ms * (1 - double(coating.single_scattering_albedo(T(mu)))) * (1 - a) / (1 - e_avg);
            const double base = (1 - double(white.coating_albedo(T(mu)))) * (1 - a_s) / (1 - e_s_avg);
            const double total = ss.albedo.x + coating_ms + base;
            CHECK(total >= 0.97);
            CHECK(total <= 1.001);
            const auto own = shade::check::sampled_albedo(white, view_of<T>(mu), flat<T>(), 128, 3);
            CHECK(std::abs(own.albedo.x - total) < 4 * (own.standard_error.x + ss.standard_error.x));
            const auto b = shade::check::sampled_albedo(uncoupled, view_of<T>(mu), flat<T>(), 64, 3);
            CHECK(b.albedo.x > 1.001);
        }
    }
}

TEST_CASE_TEMPLATE("coupled_plastic: with k_d = 0 it is the coating alone, bit for bit", T, float, double) {
    const auto at = tilted<T>();
    for (const double alpha : {0.05, 0.4, 1.0}) {
        const shade::coupled_plastic<T> plastic(shade::ggx<T>(T(alpha)), rgb<T>(0));
        const typename shade::coupled_plastic<T>::coating_type coating(shade::ggx<T>(T(alpha)),
                                                                       shade::dielectric_fresnel<T>(T(1.5)));
        shade::rng random(11);
        for (int k = 0; k < 500; ++k) {
            const vec3<T> l = at.shading.to_world(shade::square_to_cosine_hemisphere(vec2<T>(random.uniform<T>(), random.uniform<T>())));
            const vec3<T> v = at.shading.to_world(shade::square_to_cosine_hemisphere(vec2<T>(random.uniform<T>(), random.uniform<T>())));
            CHECK(plastic.f(l, v, at) == coating.f(l, v, at));
            CHECK(plastic.pdf(l, v, at) == coating.pdf(l, v, at));
            const T uc = random.uniform<T>();
            const vec2<T> u(random.uniform<T>(), random.uniform<T>());
            const auto a = plastic.sample(v, uc, u, at);
            const auto b = coating.sample(v, uc, u, at);
            REQUIRE(a.has_value() == b.has_value());
            if (a) {
                CHECK(a->l == b->l);
                CHECK(a->f == b->f);
                CHECK(a->pdf == b->pdf);
                CHECK(a->weight == b->weight);
            }
        }
    }
}

TEST_CASE_TEMPLATE("coupled_plastic: the base term is k_d (1 - E_s(l))(1 - E_s(v)) / (pi (1 - E_s,avg))", T, float, double) {
    const rgb<T> k_d(T(0.8), T(0.4), T(0.1));
    const shade::coupled_plastic<T> plastic(shade::ggx<T>(T(0.3)), k_d);
    const auto at = flat<T>();
    const vec3<T> l = glm::normalize(vec3<T>(T(0.3), T(-0.4), T(0.6)));
    const vec3<T> v = glm::normalize(vec3<T>(T(-0.7), T(0.1), T(0.3)));
    // E_s,avg by its definition, 2 integral E_s(mu) mu dmu (midpoint rule, 20000 cells).
    double e_s_avg = 0;
    for (int i = 0; i < 20000; ++i) {
        const double mu = (i + 0.5) / 20000;
        e_s_avg += 2 * double(plastic.coating_albedo(T(mu))) * mu / 20000;
    }
    const double expected_factor = (1 - double(plastic.coating_albedo(l.z))) * (1 - double(plastic.coating_albedo(v.z))) /
                                   (shade::pi<double> * (1 - e_s_avg));
    const rgb<T> base = plastic.f_diffuse(l, v, at);
    for (int c = 0; c < 3; ++c) CHECK(double(base[c]) == doctest::Approx(double(k_d[c]) * expected_factor).epsilon(1e-4));
    CHECK(plastic.f_diffuse(l, v, at) == plastic.f_diffuse(v, l, at));
    // The coating reflects little of normal light (F(1) = ((1.5 - 1) / (1.5 + 1))^2 = 0.04,
    // plus a little multiple scattering) and more toward grazing, where F grows to 1.
    CHECK(plastic.coating_albedo(T(1)) < T(0.06));
    CHECK(plastic.coating_albedo(T(0.05)) > T(2) * plastic.coating_albedo(T(1)));
    CHECK_THROWS_AS(shade::coupled_plastic<T>(shade::ggx<T>(T(0.3)), rgb<T>(T(-0.1), 0, 0)), shade::invalid_parameter);
}

TEST_CASE_TEMPLATE("coupled_plastic: every property check passes", T, float, double) {
    const auto run = [](const auto& model, const std::string& name) { expect_every_property(model, name, 24); };
    run(shade::coupled_plastic<T>(shade::ggx<T>(T(0.1)), rgb<T>(T(0.9), T(0.2), T(0.1))), "coupled plastic alpha 0.1");
    run(shade::make_coupled_plastic<T>(T(0.8), rgb<T>(1)), "coupled plastic alpha 0.8, white");
}

namespace {

// coupled_plastic as it was written on its own before it became a layer of two lobes,
// frozen here from its class comment: f = f_s + k_d (1 - E_s(n·l)) (1 - E_s(n·v)) /
// (pi (1 - E_s,avg)), E_s(mu) = E_F(mu) + F_ms (1 - E(mu)) and E_s,avg = E_F,avg +
// F_ms (1 - E_avg) from the tables, the coating with probability P_s = E_s / (E_s +
// max(k_d) (1 - E_s)) in [0.1, 0.9] (1 when k_d = 0), else the cosine.
template <class T>
class frozen_coupled_plastic {
public:
    using coating_type = typename shade::coupled_plastic<T>::coating_type;

    frozen_coupled_plastic(const shade::ggx<T>& distribution, const rgb<T>& k_d)
        : coating_(distribution, shade::dielectric_fresnel<T>(T(1.5))), k_d_(k_d) {
        alpha_ = shade::detail::albedo_tables_of<shade::ggx<T>>::roughness(distribution);
        const T e_avg = coating_.average_single_scattering_albedo();
        f_ms_ = shade::detail::multiple_scattering_fresnel(
                    shade::detail::fresnel_average<T>(shade::dielectric_fresnel<T>(T(1.5))), e_avg)
                    .x;
        const T e_s_avg = shade::detail::albedo_average_lookup(shade::detail::ggx_dielectric_albedo_average,
                                                               shade::detail::albedo_grid_nodes, alpha_) +
                          f_ms_ * (T(1) - e_avg);
        base_scale_ = shade::inv_pi<T> / (T(1) - e_s_avg);
    }

    T coating_albedo(T mu) const {
        const T e_f = shade::detail::albedo_lookup(shade::detail::ggx_dielectric_albedo,
                                                   shade::detail::albedo_grid_nodes, mu, alpha_);
        return e_f + f_ms_ * (T(1) - coating_.single_scattering_albedo(mu));
    }

    rgb<T> f(const vec3<T>& l, const vec3<T>& v, const shade::surface_point<T>& at) const {
        const T n_dot_l = glm::dot(at.n(), l);
        const T n_dot_v = glm::dot(at.n(), v);
        rgb<T> base(0);
        if (n_dot_l > T(0) && n_dot_v > T(0))
            base = k_d_ * (base_scale_ * ((T(1) - coating_albedo(n_dot_l)) * (T(1) - coating_albedo(n_dot_v))));
        return coating_.f(l, v, at) + base;
    }

    T specular_probability(T n_dot_v) const {
        const T w_d = shade::detail::max_channel(k_d_);
        if (!(w_d > T(0))) return T(1);
        const T e_s = coating_albedo(n_dot_v);
        return glm::clamp(e_s / (e_s + w_d * (T(1) - e_s)), T(0.1), T(0.9));
    }

    T pdf(const vec3<T>& l, const vec3<T>& v, const shade::surface_point<T>& at) const {
        const T n_dot_l = glm::dot(at.n(), l);
        const T n_dot_v = glm::dot(at.n(), v);
        if (!(n_dot_l > T(0)) || !(n_dot_v > T(0))) return T(0);
        const T p_s = specular_probability(n_dot_v);
        return p_s * coating_.pdf(l, v, at) + (T(1) - p_s) * n_dot_l * shade::inv_pi<T>;
    }

    std::optional<shade::brdf_sample<T>> sample(const vec3<T>& v, T uc, const vec2<T>& u,
                                                const shade::surface_point<T>& at) const {
        if (!(glm::dot(at.n(), v) > T(0))) return std::nullopt;
        const T p_s = specular_probability(glm::dot(at.n(), v));
        vec3<T> l;
        if (uc < p_s) {
            const auto s = coating_.sample(v, uc / p_s, u, at);
            if (!s) return std::nullopt;
            l = s->l;
        } else {
            l = at.shading.to_world(shade::square_to_cosine_hemisphere(u));
        }
        const T n_dot_l = glm::dot(at.n(), l);
        if (!(n_dot_l > T(0))) return std::nullopt;
        return shade::detail::make_brdf_sample(l, f(l, v, at), pdf(l, v, at), n_dot_l);
    }

private:
    coating_type coating_;
    rgb<T> k_d_;
    T alpha_ = 0;
    T f_ms_ = 0;
    T base_scale_ = 0;
};

// A unit direction at `at`: uniform on the sphere, moved above the surface 4 times in 5
// when it falls below (most pairs then have both above, and some do not).
template <class T>
vec3<T> random_direction(const shade::surface_point<T>& at, shade::rng& random) {
    vec3<T> w = shade::square_to_uniform_sphere(vec2<T>(random.uniform<T>(), random.uniform<T>()));
    if (w.z < T(0) && random.uniform<T>() < T(0.8)) w.z = -w.z;
    return glm::normalize(at.shading.to_world(w));
}

} // namespace

TEST_CASE_TEMPLATE("coupled_plastic: the layer of two lobes has the values of the model written on its own", T,
                   float, double) {
    // 1000 plastics (GGX alpha log-uniform in [0.01, 1.5], a fifth anisotropic with
    // alpha_y = s alpha, s in [0.25, 1]; k_d uniform in [0, 1]^3, a tenth black, a tenth
    // grey) times 100 pairs (l, v) and one sample each: 100,000 of each of f, pdf and
    // sample against frozen_coupled_plastic. The same terms in another order of the
    // products (the base's (1 - E_s)(1 - E_s) / (1 - E_s,avg) times k_d / pi): f, pdf and
    // the sample's f, pdf and weight within 1e-6 relative, the sampled l the same bits.
    const auto at = tilted<T>();
    shade::rng random(31);
    int f_off = 0, pdf_off = 0, sample_off = 0, samples = 0;
    for (int m = 0; m < 1000; ++m) {
        const T alpha = T(0.01) * std::pow(T(150), random.uniform<T>());
        const bool anisotropic = random.uniform<T>() < T(0.2);
        const T alpha_y = anisotropic ? alpha * (T(0.25) + T(0.75) * random.uniform<T>()) : alpha;
        const T kind = random.uniform<T>();
        rgb<T> k_d(random.uniform<T>(), random.uniform<T>(), random.uniform<T>());
        if (kind < T(0.1)) k_d = rgb<T>(0);
        else if (kind < T(0.2)) k_d = rgb<T>(k_d.x);
        const shade::ggx<T> distribution = anisotropic ? shade::ggx<T>(alpha, alpha_y) : shade::ggx<T>(alpha);
        const shade::coupled_plastic<T> plastic(distribution, k_d);
        const frozen_coupled_plastic<T> frozen(distribution, k_d);
        for (int k = 0; k < 100; ++k) {
            const vec3<T> l = random_direction(at, random);
            const vec3<T> v = random_direction(at, random);
            if (!close(plastic.f(l, v, at), frozen.f(l, v, at), T(1e-6))) ++f_off;
            if (!close(plastic.pdf(l, v, at), frozen.pdf(l, v, at), T(1e-6))) ++pdf_off;
            const T uc = random.uniform<T>();
            const vec2<T> u(random.uniform<T>(), random.uniform<T>());
            const auto a = plastic.sample(v, uc, u, at);
            const auto b = frozen.sample(v, uc, u, at);
            if (a.has_value() != b.has_value()) {
                ++sample_off;
                continue;
            }
            if (!a) continue;
            ++samples;
            if (!(a->l == b->l) || !close(a->f, b->f, T(1e-6)) || !close(a->pdf, b->pdf, T(1e-6)) ||
                !close(a->weight, b->weight, T(1e-6)))
                ++sample_off;
        }
    }
    CHECK(f_off == 0);
    CHECK(pdf_off == 0);
    CHECK(sample_off == 0);
    CHECK(samples > 50000); // most views are above the surface and draw
}

TEST_CASE_TEMPLATE("coupled_plastic: it is a layer whose coat reports the tabulated albedo", T, float, double) {
    const shade::coupled_plastic<T> plastic(shade::ggx<T>(T(0.3)), rgb<T>(T(0.8), T(0.4), T(0.1)));
    const typename shade::coupled_plastic<T>::layer_type& as_layer = plastic;
    static_assert(shade::detail::has_directional_albedo<shade::ggx_dielectric_coating<T>>);
    CHECK(as_layer.coat_weight() == T(1));
    CHECK(as_layer.form() == shade::layering::reciprocal);
    CHECK(as_layer.choice().base_albedo() == T(0.8));
    for (const T mu : {T(0.05), T(0.3), T(1)}) {
        CHECK(as_layer.coat_albedo(mu) == plastic.coating_albedo(mu));
        CHECK(as_layer.coat_probability(mu) == plastic.specular_probability(mu));
    }
    CHECK(as_layer.coat_average_albedo() == plastic.coat().average_albedo());
}
