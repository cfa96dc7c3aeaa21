#pragma once
// The thin film's share of openpbr_surface's E_spec, read by the material against the true
// integral (issue #32): shared by tests/material/test_openpbr_surface.cpp and the wide sweep
// of tests/sweep/test_openpbr_film_sweep.cpp.

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

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
/// roughness r and anisotropy a (alpha_t = r^2 sqrt(2 / (1 + (1 - a)^2)), alpha_b = (1 - a)
/// alpha_t, openpbr::roughness_to_alpha, alpha_b held at openpbr::smallest_alpha as the
/// material holds it), the view at cosine mu and azimuth phi from the tangent, over a white
/// Lambertian base (base_diffuse_roughness 0, uncoated): there f = f_spec + (1 - E_R(v)) /
/// pi, so the material's E_R(v) is 1 - pi (f - f_spec) at any l, f_spec the public specular
/// lobe built here, and the white furnace reads 1 + E_R,true(v) - E_R(v) exactly. The lobe's
/// index ratio is eta'_s = openpbr::modulated_ior_ratio(specular_ior, specular_weight). The
/// true albedo with the film is R_ss(v) (dielectric_reflection_albedo, isotropic or of the
/// local view, the table the material reads without a film, tested on its own) plus w times
/// the integral of F_film - F(eta'_s) (F_film over specular_ior) against the lobe's measure
/// of c = v·h, by the midpoint rule on strata^2 cells of the lobe's visible-normal square
/// (Heitz 2018, "Sampling the GGX Distribution of Visible Normals", JCGT 7(4)), each
/// weighted by G2(v, l) / G1(v) = (1 + Lambda(v)) / (1 + Lambda(v) + Lambda(l)) (Heitz
/// 2014, JCGT 3(2), eq. 99), l = reflect(v, h) above the surface, with F_film read at each
/// cell's own cosine (at this very view and lobe, not the tables' nodes).
/// film_reader builds the material and the lobe once for a film, roughness and anisotropy and
/// reads any number of views; film_albedo_error reads one.
template <class T>
class film_reader {
public:
    film_reader(const film_point<T>& fl, T r, T a)
        : fl_(fl), a_(a), eta_(shade::openpbr::modulated_ior_ratio(fl.base_ior, fl.specular_weight)),
          film_(shade::thin_film_fresnel<T>::over_dielectric(fl.base_ior, fl.ior, fl.thickness_um * T(1000))),
          alpha_(shade::openpbr::roughness_to_alpha(r, a)),
          alpha_b_(std::max(alpha_.b, shade::openpbr::smallest_alpha<T>)), m_(parameters(fl, r, a)),
          spec_(shade::ggx<T>(alpha_.t, alpha_b_),
                shade::openpbr::surface_fresnel<T>::dielectric(eta_, shade::rgb<T>(1), fl.weight, film_)) {}

    /// Whether the material integrates R_ss of this lobe per interface: an anisotropic lobe
    /// with a film does (detail::anisotropic_reflection_albedo_grid with the film's Fresnel
    /// term), and the film's share with it; the true E_R then wants R_ss by quadrature too
    /// (error's r_ss_by_quadrature), not the table's.
    [[nodiscard]] bool integrates_r_ss() const { return a_ != T(0) && fl_.weight > T(0) && alpha_.t != alpha_b_; }

    /// E_R read - true at the view of cosine mu and azimuth phi, strata^2 cells. With
    /// r_ss_by_quadrature, R_ss is integrated on the same cells too (F(eta'_s) at each cell's
    /// cosine) instead of read from the table: the true E_R with the table's error counted,
    /// which matters below an index ratio of 1, where the material's share holds F_film
    /// alone and a film of weight 1 leaves no part of R_ss in E_R.
    [[nodiscard]] shade::rgb<double> error(double mu, double phi, std::size_t strata,
                                           bool r_ss_by_quadrature = false) const {
        using shade::rgb;
        using shade::vec3;
        const auto at = check_test::model_point<T>();
        const double s = std::sqrt((1 - mu) * (1 + mu));
        const vec3<T> v_local(T(s * std::cos(phi)), T(s * std::sin(phi)), T(mu));
        const vec3<T> v = glm::normalize(at.shading.to_world(v_local));
        const vec3<T> l = at.n();
        const rgb<T> diffuse_part = m_.f(l, v, at) - spec_.f(l, v, at);
        double r_ss = 0;
        if (!r_ss_by_quadrature)
            r_ss = a_ == T(0) ? double(shade::dielectric_reflection_albedo(T(mu), alpha_.t, eta_))
                              : double(shade::dielectric_reflection_albedo(shade::unchecked, v_local, alpha_.t,
                                                                           alpha_b_, eta_));
        const shade::ggx<double> d(shade::unchecked, double(alpha_.t), double(alpha_b_));
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
                film_part += weight * (rgb<double>(film_.F(T(c))) - rgb<double>(shade::F_dielectric(c, double(eta_))));
                if (r_ss_by_quadrature) r_ss += weight * shade::F_dielectric(c, double(eta_));
            }
        rgb<double> out;
        for (int k = 0; k < 3; ++k)
            out[k] = (1 - shade::pi<double> * double(diffuse_part[k])) - (r_ss + double(fl_.weight) * film_part[k]);
        return out;
    }

private:
    static shade::openpbr_parameters<T> parameters(const film_point<T>& fl, T r, T a) {
        shade::openpbr_parameters<T> p;
        p.base_color = shade::rgb<T>(1);
        p.specular_roughness = r;
        p.specular_roughness_anisotropy = a;
        p.specular_ior = fl.base_ior;
        p.specular_weight = fl.specular_weight;
        p.thin_film_weight = fl.weight;
        p.thin_film_thickness = fl.thickness_um;
        p.thin_film_ior = fl.ior;
        return p;
    }

    film_point<T> fl_;
    T a_, eta_;
    shade::thin_film_fresnel<T> film_;
    shade::openpbr::alpha_pair<T> alpha_;
    T alpha_b_;
    shade::openpbr_surface<T> m_;
    typename shade::openpbr_surface<T>::specular_lobe spec_;
};

/// film_reader's error for one view.
template <class T>
shade::rgb<double> film_albedo_error(const film_point<T>& fl, T r, T a, double mu, double phi,
                                     std::size_t strata = 128) {
    return film_reader<T>(fl, r, a).error(mu, phi, strata);
}

/// film_albedo_error of an isotropic lobe (anisotropy 0), the view at azimuth 0.4.
template <class T>
shade::rgb<double> film_albedo_error(const film_point<T>& fl, T r, double mu, std::size_t strata = 160) {
    return film_albedo_error(fl, r, T(0), mu, 0.4, strata);
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
