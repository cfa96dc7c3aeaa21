#pragma once
// The thin film's share of openpbr_surface's E_spec, read by the material against the true
// integral (issue #32): shared by tests/material/test_openpbr_surface.cpp and the wide sweep
// of tests/sweep/test_openpbr_film_sweep.cpp.

#include <cmath>

#include <glm/geometric.hpp>

#include <shade/brdf/microfacet/cosine_weights.hpp>
#include <shade/bsdf/dielectric_anisotropic_reflection_albedo.hpp>
#include <shade/bsdf/dielectric_reflection_albedo.hpp>
#include <shade/material/openpbr_surface.hpp>

#include "check/model_point.hpp"

namespace film_test {

/// A film: weight, thickness (um), film index, base index (specular_ior), and the
/// specular_weight of the material (1 unless given).
template <class T>
struct film_point {
    T weight, thickness_um, ior, base_ior, specular_weight = T(1);
};

/// E_R(v) read by the material minus the true E_R(v), per channel, for the film fl at
/// roughness r and anisotropy 0, view cosine mu, over a white Lambertian base
/// (base_diffuse_roughness 0, uncoated): there f = f_spec + (1 - E_R(v)) / pi, so the
/// material's E_R(v) is 1 - pi (f - f_spec) at any l, f_spec the public specular lobe built
/// here, and the white furnace reads 1 + E_R,true(v) - E_R(v) exactly. The lobe's index
/// ratio is eta'_s = openpbr::modulated_ior_ratio(specular_ior, specular_weight). The true
/// albedo with the film is R_ss(eta'_s) (dielectric_reflection_albedo, the table the material
/// reads without a film, tested on its own) plus w times the integral of F_film - F(eta'_s)
/// (F_film over specular_ior) against the lobe's measure of c = v·h, by the midpoint rule on
/// strata^2 cells of the visible-normal square with F_film read at each cell's own cosine
/// (ggx_cosine_weights' quadrature at this very mu and alpha, not the table's nodes).
template <class T>
shade::rgb<double> film_albedo_error(const film_point<T>& fl, T r, double mu, std::size_t strata = 160) {
    using shade::rgb;
    using shade::vec3;
    const auto at = check_test::model_point<T>();
    const T eta = shade::openpbr::modulated_ior_ratio(fl.base_ior, fl.specular_weight);
    const auto film = shade::thin_film_fresnel<T>::over_dielectric(fl.base_ior, fl.ior, fl.thickness_um * T(1000));
    const auto fresnel = shade::openpbr::surface_fresnel<T>::dielectric(eta, rgb<T>(1), fl.weight, film);
    shade::openpbr_parameters<T> p;
    p.base_color = rgb<T>(1);
    p.specular_roughness = r;
    p.specular_ior = fl.base_ior;
    p.specular_weight = fl.specular_weight;
    p.thin_film_weight = fl.weight;
    p.thin_film_thickness = fl.thickness_um;
    p.thin_film_ior = fl.ior;
    const shade::openpbr_surface<T> m(p);
    const T alpha = shade::openpbr::roughness_to_alpha(r, T(0)).t;
    const typename shade::openpbr_surface<T>::specular_lobe spec(shade::ggx<T>(alpha), fresnel);
    const double s = std::sqrt((1 - mu) * (1 + mu));
    const vec3<T> v =
        glm::normalize(at.shading.to_world(vec3<T>(T(s * std::cos(0.4)), T(s * std::sin(0.4)), T(mu))));
    const vec3<T> l = at.n();
    const rgb<T> diffuse_part = m.f(l, v, at) - spec.f(l, v, at);
    const double r_ss = double(shade::dielectric_reflection_albedo(T(mu), alpha, eta));
    rgb<double> film_part(0);
    shade::detail::visit_ggx_cosine_measure(mu, double(alpha), strata, [&](double c, double w) {
        film_part += w * (rgb<double>(film.F(T(c))) - rgb<double>(shade::F_dielectric(c, double(eta))));
    });
    rgb<double> error;
    for (int k = 0; k < 3; ++k)
        error[k] = (1 - shade::pi<double> * double(diffuse_part[k])) - (r_ss + double(fl.weight) * film_part[k]);
    return error;
}

/// film_albedo_error for an anisotropic lobe: roughness r, anisotropy a (alpha_t = r^2
/// sqrt(2 / (1 + (1 - a)^2)), alpha_b = (1 - a) alpha_t, openpbr::roughness_to_alpha), the
/// view at cosine mu and azimuth phi from the tangent. The true albedo is the anisotropic
/// R_ss(v) the material reads without a film (dielectric_reflection_albedo of the local
/// view, tested on its own) plus w times the integral of F_film - F(eta'_s) against the
/// anisotropic lobe's measure of c = v·h: the midpoint rule on strata^2 cells of its
/// visible-normal square (Heitz 2018, "Sampling the GGX Distribution of Visible Normals",
/// JCGT 7(4)), each weighted by G2(v, l) / G1(v) = (1 + Lambda(v)) / (1 + Lambda(v) +
/// Lambda(l)) (Heitz 2014, JCGT 3(2), eq. 99), l = reflect(v, h) above the surface.
template <class T>
shade::rgb<double> anisotropic_film_albedo_error(const film_point<T>& fl, T r, T a, double mu, double phi,
                                                 std::size_t strata = 128) {
    using shade::rgb;
    using shade::vec3;
    const auto at = check_test::model_point<T>();
    const T eta = shade::openpbr::modulated_ior_ratio(fl.base_ior, fl.specular_weight);
    const auto film = shade::thin_film_fresnel<T>::over_dielectric(fl.base_ior, fl.ior, fl.thickness_um * T(1000));
    const auto fresnel = shade::openpbr::surface_fresnel<T>::dielectric(eta, rgb<T>(1), fl.weight, film);
    shade::openpbr_parameters<T> p;
    p.base_color = rgb<T>(1);
    p.specular_roughness = r;
    p.specular_roughness_anisotropy = a;
    p.specular_ior = fl.base_ior;
    p.specular_weight = fl.specular_weight;
    p.thin_film_weight = fl.weight;
    p.thin_film_thickness = fl.thickness_um;
    p.thin_film_ior = fl.ior;
    const shade::openpbr_surface<T> m(p);
    const auto alpha = shade::openpbr::roughness_to_alpha(r, a);
    const typename shade::openpbr_surface<T>::specular_lobe spec(shade::ggx<T>(alpha.t, alpha.b), fresnel);
    const double s = std::sqrt((1 - mu) * (1 + mu));
    const vec3<T> v_local(T(s * std::cos(phi)), T(s * std::sin(phi)), T(mu));
    const vec3<T> v = glm::normalize(at.shading.to_world(v_local));
    const vec3<T> l = at.n();
    const rgb<T> diffuse_part = m.f(l, v, at) - spec.f(l, v, at);
    const double r_ss = double(shade::dielectric_reflection_albedo(shade::unchecked, v_local, alpha.t, alpha.b, eta));
    const shade::ggx<double> d(shade::unchecked, double(alpha.t), double(alpha.b));
    const vec3<double> w(s * std::cos(phi), s * std::sin(phi), mu);
    const double lambda_v = d.Lambda(w);
    rgb<double> film_part(0);
    for (std::size_t i = 0; i < strata; ++i)
        for (std::size_t j = 0; j < strata; ++j) {
            const shade::vec2<double> u((double(i) + 0.5) / double(strata), (double(j) + 0.5) / double(strata));
            const vec3<double> h = d.sample_visible_normal(w, u);
            const double c = glm::dot(w, h);
            const vec3<double> l_local = 2 * c * h - w;
            if (!(l_local.z > 0) || !(c > 0)) continue;
            const double weight = (1 + lambda_v) / (1 + lambda_v + d.Lambda(l_local)) / double(strata * strata);
            film_part += weight * (rgb<double>(film.F(T(c))) - rgb<double>(shade::F_dielectric(c, double(eta))));
        }
    rgb<double> error;
    for (int k = 0; k < 3; ++k)
        error[k] = (1 - shade::pi<double> * double(diffuse_part[k])) - (r_ss + double(fl.weight) * film_part[k]);
    return error;
}

/// The largest E_R read - true the film's margin allows for fl at mu >= 0.1 (white furnace
/// >= 1 - that), as the generator states it in thin_film_margin_data.hpp: the 1e-2
/// at film index >= 1.2 over its own base (table 0); 1.4e-2 at index >= 1.1 or for another
/// eta'_s (table 1); 4.2e-2 below 1.1.
template <class T>
double film_high_bound(const film_point<T>& fl) {
    if (fl.ior < T(1.1)) return 4.2e-2;
    if (fl.ior < T(1.2) || fl.specular_weight != T(1)) return 1.4e-2;
    return 1e-2;
}

} // namespace film_test
