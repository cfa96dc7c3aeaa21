#pragma once
// The parameters of OpenPBR Surface 1.1 (Academy Software Foundation, MaterialX
// subproject; the specification's names, ranges and defaults) and the closed-form pieces
// the specification prescribes for turning them into lobes: the roughness and anisotropy
// mapping, the specular IOR as the coat and specular_weight change it, the coat's
// roughening of the base, its darkening of the base, its view-dependent absorption, the
// interior media (transmission and subsurface) and the dispersion.
//
//   shade::openpbr_parameters<float> p;      // the specification's defaults
//   p.base_metalness = 1;
//   p.base_color = {0.944f, 0.776f, 0.373f};
//   p.validate();                            // throws shade::invalid_parameter naming a bad one
//
// Not part of shade/shade.hpp: include this header where it is used.

#include <cmath>
#include <concepts>
#include <limits>

#include <glm/common.hpp>
#include <glm/exponential.hpp>
#include <glm/vector_relational.hpp>

#include <shade/brdf/fresnel.hpp>
#include <shade/core/error.hpp>
#include <shade/core/types.hpp>

namespace shade {

/// Every parameter of OpenPBR Surface 1.1 except the geometry's normal and tangent inputs
/// (those are the shading frame of the surface point the material is evaluated at). The
/// members carry the specification's names and default values; validate() checks the
/// specification's ranges. Colours are linear RGB; lengths (transmission_depth,
/// subsurface_radius) are in scene units; thin_film_thickness is in micrometres;
/// emission_luminance is in nits (cd/m^2).
template <std::floating_point T>
struct openpbr_parameters {
    // Base.
    T base_weight = T(1);                          ///< [0, 1], multiplier of base_color
    rgb<T> base_color = rgb<T>(T(0.8));            ///< [0, 1]^3, diffuse albedo and metal F0
    T base_diffuse_roughness = T(0);               ///< [0, 1], roughness of the EON diffuse lobe
    T base_metalness = T(0);                       ///< [0, 1], mix weight of the metal
    // Specular.
    T specular_weight = T(1);                      ///< [0, inf), dielectric F0 multiplier (metal: Fresnel weight)
    rgb<T> specular_color = rgb<T>(T(1));          ///< [0, 1]^3, dielectric tint; metal edge tint (F82)
    T specular_roughness = T(0.3);                 ///< [0, 1], roughness r (alpha = r^2)
    T specular_roughness_anisotropy = T(0);        ///< [0, 1]
    T specular_ior = T(1.5);                       ///< (0, inf), index of the base dielectric
    // Transmission.
    T transmission_weight = T(0);                  ///< [0, 1], translucent versus opaque base
    rgb<T> transmission_color = rgb<T>(T(1));      ///< [0, 1]^3, extinction colour
    T transmission_depth = T(0);                   ///< [0, inf), depth at which the colour is reached
    rgb<T> transmission_scatter = rgb<T>(T(0));    ///< [0, 1]^3, interior scattering
    T transmission_scatter_anisotropy = T(0);      ///< [-1, 1], Henyey-Greenstein g
    T transmission_dispersion_scale = T(0);        ///< [0, 1]
    T transmission_dispersion_abbe_number = T(20); ///< (0, inf), Abbe number
    // Subsurface.
    T subsurface_weight = T(0);                                        ///< [0, 1]
    rgb<T> subsurface_color = rgb<T>(T(0.8));                          ///< [0, 1]^3
    T subsurface_radius = T(1);                                        ///< [0, inf), mean free path scale
    rgb<T> subsurface_radius_scale = rgb<T>(T(1), T(0.5), T(0.25));    ///< [0, 1]^3
    T subsurface_scatter_anisotropy = T(0);                            ///< [-1, 1], Henyey-Greenstein g
    // Coat.
    T coat_weight = T(0);                          ///< [0, 1], coverage
    rgb<T> coat_color = rgb<T>(T(1));              ///< [0, 1]^3, square of the normal-incidence transmittance
    T coat_roughness = T(0);                       ///< [0, 1]
    T coat_roughness_anisotropy = T(0);            ///< [0, 1]
    T coat_ior = T(1.6);                           ///< (0, inf)
    T coat_darkening = T(1);                       ///< [0, 1]
    // Fuzz.
    T fuzz_weight = T(0);                          ///< [0, 1], coverage
    rgb<T> fuzz_color = rgb<T>(T(1));              ///< [0, 1]^3
    T fuzz_roughness = T(0.5);                     ///< [0, 1]
    // Thin film.
    T thin_film_weight = T(0);                     ///< [0, 1], coverage
    T thin_film_thickness = T(0.5);                ///< [0, inf), micrometres
    T thin_film_ior = T(1.4);                      ///< (0, inf)
    // Emission.
    T emission_luminance = T(0);                   ///< [0, inf), nits
    rgb<T> emission_color = rgb<T>(T(1));          ///< [0, inf)^3
    // Geometry.
    T geometry_opacity = T(1);                     ///< [0, 1]
    bool geometry_thin_walled = false;             ///< a thin shell rather than the boundary of a solid

    /// Throws shade::invalid_parameter naming the first parameter outside the
    /// specification's range (or not finite); returns *this.
    const openpbr_parameters& validate() const {
        const auto unit = [](const char* name, T x) { require_in_range(name, x, T(0), T(1)); };
        const auto unit_rgb = [](const char* name, const rgb<T>& c) { require_in_range(name, c, T(0), T(1)); };
        const auto anisotropy = [](const char* name, T g) { require_in_range(name, g, T(-1), T(1)); };
        unit("base_weight", base_weight);
        unit_rgb("base_color", base_color);
        unit("base_diffuse_roughness", base_diffuse_roughness);
        unit("base_metalness", base_metalness);
        require_non_negative("specular_weight", specular_weight);
        unit_rgb("specular_color", specular_color);
        unit("specular_roughness", specular_roughness);
        unit("specular_roughness_anisotropy", specular_roughness_anisotropy);
        require_positive("specular_ior", specular_ior);
        unit("transmission_weight", transmission_weight);
        unit_rgb("transmission_color", transmission_color);
        require_non_negative("transmission_depth", transmission_depth);
        unit_rgb("transmission_scatter", transmission_scatter);
        anisotropy("transmission_scatter_anisotropy", transmission_scatter_anisotropy);
        unit("transmission_dispersion_scale", transmission_dispersion_scale);
        require_positive("transmission_dispersion_abbe_number", transmission_dispersion_abbe_number);
        unit("subsurface_weight", subsurface_weight);
        unit_rgb("subsurface_color", subsurface_color);
        require_non_negative("subsurface_radius", subsurface_radius);
        unit_rgb("subsurface_radius_scale", subsurface_radius_scale);
        anisotropy("subsurface_scatter_anisotropy", subsurface_scatter_anisotropy);
        unit("coat_weight", coat_weight);
        unit_rgb("coat_color", coat_color);
        unit("coat_roughness", coat_roughness);
        unit("coat_roughness_anisotropy", coat_roughness_anisotropy);
        require_positive("coat_ior", coat_ior);
        unit("coat_darkening", coat_darkening);
        unit("fuzz_weight", fuzz_weight);
        unit_rgb("fuzz_color", fuzz_color);
        unit("fuzz_roughness", fuzz_roughness);
        unit("thin_film_weight", thin_film_weight);
        require_non_negative("thin_film_thickness", thin_film_thickness);
        require_positive("thin_film_ior", thin_film_ior);
        require_non_negative("emission_luminance", emission_luminance);
        require_non_negative("emission_color", emission_color);
        unit("geometry_opacity", geometry_opacity);
        return *this;
    }
};

/// The closed-form pieces of OpenPBR Surface 1.1 (section numbers and equation labels are
/// the specification's).
namespace openpbr {

/// GGX roughnesses along the tangent and the bitangent.
template <std::floating_point T>
struct alpha_pair {
    T t; ///< alpha_t, along the tangent
    T b; ///< alpha_b, along the bitangent
};

/// Section "Microfacet model", equation openpbr-anisotropy-formula: roughness r and
/// anisotropy a in [0, 1] to alpha_t = r^2 sqrt(2 / (1 + (1 - a)^2)), alpha_b = (1 - a)
/// alpha_t, so that alpha_t^2 + alpha_b^2 = 2 r^4 whatever a (a = 0: alpha = r^2 both ways).
/// The caller guarantees r and a in [0, 1].
template <std::floating_point T>
[[nodiscard]] inline alpha_pair<T> roughness_to_alpha(T r, T a) noexcept {
    const T b = T(1) - a;
    const T t = r * r * std::sqrt(T(2) / (T(1) + b * b));
    return {t, b * t};
}

/// Section "Coat", equation specular_ior_ratio with the TIR fix of equation
/// specular_ior_ratio_with_tir_fix: the ratio of the base dielectric's index n_b to its
/// surroundings, lerp(n_b / n_a, eta_bc, C), with eta_bc = n_b / n_c where the coat is the
/// rarer medium (n_c <= n_b) and n_c / n_b otherwise (no spurious total internal reflection
/// at the coat/base boundary). n_a is the ambient index, n_c coat_ior, C coat_weight. The
/// caller guarantees indices > 0 and C in [0, 1].
template <std::floating_point T>
[[nodiscard]] inline T specular_ior_ratio(T n_b, T n_a, T n_c, T coat_weight) noexcept {
    const T eta_bc = n_c > n_b ? n_c / n_b : n_b / n_c;
    return glm::mix(n_b / n_a, eta_bc, coat_weight);
}

/// Section "Dielectric base", equations unmodulated_fresnel and modulated_ior: the index
/// ratio eta'_s whose normal-incidence reflectance is specular_weight xi_s times that of
/// eta_s, F_s = ((1 - eta_s) / (1 + eta_s))^2:
///
///     eta'_s = (1 + epsilon) / (1 - epsilon),   epsilon = sgn(eta_s - 1) sqrt(xi_s F_s),
///
/// with xi_s clamped to [0, 1 / F_s] as the specification requires, and the result clamped
/// to [dielectric_eta_min, dielectric_eta_max] (xi_s F_s = 1 would be an infinite index).
/// xi_s = 0 gives 1 (no interface), xi_s = 1 gives eta_s. The caller guarantees eta_s > 0
/// and xi_s >= 0.
template <std::floating_point T>
[[nodiscard]] inline T modulated_ior_ratio(T eta_s, T specular_weight) noexcept {
    const T f_s = f0_from_ior(eta_s);
    const T xi_f = glm::clamp(specular_weight * f_s, T(0), T(1));
    const T epsilon = (eta_s > T(1) ? T(1) : (eta_s < T(1) ? T(-1) : T(0))) * std::sqrt(xi_f);
    if (epsilon >= T(1)) return dielectric_eta_max<T>;
    return glm::clamp((T(1) + epsilon) / (T(1) - epsilon), dielectric_eta_min<T>, dielectric_eta_max<T>);
}

/// Section "Coat", "Roughening": the base roughness r_B = specular_roughness as a coat of
/// roughness r_C and coverage C widens it, lerp(r_B, min(1, r_B^4 + 2 r_C^4)^(1/4), C) (the
/// slope variances r^4 add, the coat's counted twice for the way in and out). The caller
/// guarantees all three in [0, 1].
template <std::floating_point T>
[[nodiscard]] inline T coat_roughened(T r_b, T r_c, T coat_weight) noexcept {
    const T b2 = r_b * r_b, c2 = r_c * r_c;
    const T widened = std::sqrt(std::sqrt(glm::min(T(1), b2 * b2 + T(2) * c2 * c2)));
    return glm::mix(r_b, widened, coat_weight);
}

/// Section "Coat", "Darkening", equation internal_diffuse_reflection_coefficient_for_rough_base:
/// K_r = 1 - (1 - E_F(eta_c)) / eta_c^2, the fraction of diffuse light from below that a coat
/// of index eta_c reflects back down (E_F = dielectric_fresnel_average). Dimensionless, in
/// [0, 1]. The caller guarantees eta_c > 0.
template <std::floating_point T>
[[nodiscard]] inline T coat_rough_reflection(T eta_c) noexcept {
    return T(1) - (T(1) - dielectric_fresnel_average(eta_c)) / (eta_c * eta_c);
}

/// coat_darkening_factor (below) with both of its reflectances given, K_s = F(mu_o, eta_c)
/// and K_r = coat_rough_reflection(eta_c), for a caller that has F at the view already.
template <std::floating_point T>
[[nodiscard]] inline rgb<T> coat_darkening_factor_of_reflectances(const rgb<T>& base_albedo, T k_s, T k_r, T r_b,
                                                                  T coat_weight, T coat_darkening) noexcept {
    const T k = glm::mix(k_s, k_r, r_b);
    // A coat that reflects all diffuse light back (K = 1) over a white base (E_b = 1) is
    // 0 / 0: the limit of Delta as E_b -> 1 is 1 (a white base loses nothing), taken there.
    rgb<T> delta(1);
    for (int c = 0; c < 3; ++c) {
        const T denominator = T(1) - base_albedo[c] * k;
        if (denominator > T(0)) delta[c] = (T(1) - k) / denominator;
    }
    return glm::mix(rgb<T>(1), delta, coat_weight * coat_darkening);
}

/// coat_darkening_factor (below) with K_r = coat_rough_reflection(eta_c) given, for a caller
/// that evaluates it at many views of one coat.
template <std::floating_point T>
[[nodiscard]] inline rgb<T> coat_darkening_factor(const rgb<T>& base_albedo, T eta_c, T k_r, T mu_o, T r_b,
                                                  T coat_weight, T coat_darkening) noexcept {
    return coat_darkening_factor_of_reflectances(base_albedo, F_dielectric(mu_o, eta_c), k_r, r_b, coat_weight,
                                                 coat_darkening);
}

/// Section "Coat", "Darkening", equations general_darkening_formula,
/// internal_diffuse_reflection_coefficient_for_rough_base / _smooth_base / _general_base and
/// modulated_darkening_factor: the factor the base's lobes are multiplied by under a coat,
///
///     K_r = 1 - (1 - E_F(eta_c)) / eta_c^2,   E_F = dielectric_fresnel_average (footnote avg_fresnel),   K_s = F(mu_o, eta_c),   K = lerp(K_s, K_r, r_b)
///     Delta = (1 - K) / (1 - E_b K),          factor = lerp(1, Delta, C delta)
///
/// with eta_c the coat's index relative to the ambient medium, mu_o the view cosine, r_b the
/// estimated base roughness (equation base_roughness_estimate; see base_roughness_estimate),
/// E_b the base's normal-incidence albedo (per channel), C coat_weight and delta
/// coat_darkening. Per channel, in (0, 1]; 1 for E_b = 1 (a white base loses nothing to the
/// coat's internal reflections). The caller guarantees eta_c > 0, mu_o in [0, 1], r_b, C,
/// delta and E_b in [0, 1].
template <std::floating_point T>
[[nodiscard]] inline rgb<T> coat_darkening_factor(const rgb<T>& base_albedo, T eta_c, T mu_o, T r_b, T coat_weight,
                                                  T coat_darkening) noexcept {
    return coat_darkening_factor(base_albedo, eta_c, coat_rough_reflection(eta_c), mu_o, r_b, coat_weight,
                                 coat_darkening);
}

/// Section "Coat", "Darkening", equations base_roughness_estimate and
/// dielectric_roughness_estimate: r_b = lerp(r_d, r, M) with r_d = lerp(1, r, clamp(xi_s F_s,
/// 0, 1)), r = specular_roughness, M = base_metalness, xi_s = specular_weight and F_s the
/// normal-incidence reflectance of the base dielectric's index ratio eta_s.
template <std::floating_point T>
[[nodiscard]] inline T base_roughness_estimate(T specular_roughness, T base_metalness, T specular_weight,
                                               T eta_s) noexcept {
    const T r_d = glm::mix(T(1), specular_roughness, glm::clamp(specular_weight * f0_from_ior(eta_s), T(0), T(1)));
    return glm::mix(r_d, specular_roughness, base_metalness);
}

/// Section "Coat", "View-dependent absorption": the transmittance of the coat along the
/// two refracted paths, T_coat^(1/mu_i^t + 1/mu_o^t) with mu^t = sqrt(1 - (1 - mu^2) /
/// eta_c^2) and T_coat^2 = coat_color, i.e. coat_color^((1/mu_i^t + 1/mu_o^t) / 2); at
/// normal incidence it is coat_color. Per channel, in [0, 1]. mu_i and mu_o are the cosines
/// outside the coat, in [0, 1]; eta_c >= 1 is the coat's index relative to the ambient
/// medium (a coat rarer than the ambient medium is treated as eta_c = 1: straight paths).
template <std::floating_point T>
[[nodiscard]] inline rgb<T> coat_absorption(const rgb<T>& coat_color, T mu_i, T mu_o, T eta_c) noexcept {
    const T e = glm::max(eta_c, T(1));
    const auto refracted = [e](T mu) {
        const T c = glm::clamp(mu, T(0), T(1));
        return std::sqrt(glm::max(T(0), T(1) - (T(1) - c * c) / (e * e)));
    };
    const T mu_ti = refracted(mu_i), mu_to = refracted(mu_o);
    if (!(mu_ti > T(0)) || !(mu_to > T(0))) return glm::mix(rgb<T>(0), rgb<T>(1), glm::equal(coat_color, rgb<T>(1)));
    const T exponent = T(0.5) * (T(1) / mu_ti + T(1) / mu_to);
    return glm::pow(coat_color, rgb<T>(exponent));
}


/// A homogeneous participating medium for a renderer's volume integrator: per-channel
/// extinction sigma_t (1 / scene length), single-scattering albedo (sigma_s / sigma_t, in
/// [0, 1]) and the Henyey-Greenstein anisotropy g of its phase function. present is false
/// when the material has no interior medium (sigma_t = 0).
template <std::floating_point T>
struct homogeneous_medium {
    rgb<T> sigma_t = rgb<T>(0); ///< extinction coefficient per channel, >= 0
    rgb<T> albedo = rgb<T>(0);  ///< single-scattering albedo per channel, in [0, 1]
    T g = T(0);                 ///< Henyey-Greenstein anisotropy, in [-1, 1]
    bool present = false;       ///< an interior medium exists
};

/// Section "Translucent base": the interior medium of the transmissive dielectric from
/// transmission_color T, transmission_depth lambda, transmission_scatter S and
/// transmission_scatter_anisotropy g:
///
///     sigma_t = -ln(T) / lambda,   sigma_s = S / lambda,   sigma_a = sigma_t - sigma_s,
///
/// sigma_a shifted up by the grey -min(sigma_a) when a channel is negative, then sigma_t =
/// sigma_a + sigma_s. lambda = 0 means no medium (present = false; the specification then
/// uses transmission_color as a tint of the refraction instead). A channel of T = 0 is read
/// as the smallest normal number of T (a finite, very large extinction); sigma_t is capped
/// at the largest finite T (lambda near 0). The caller validates the parameters.
template <std::floating_point T>
[[nodiscard]] inline homogeneous_medium<T> transmission_medium(const openpbr_parameters<T>& p) noexcept {
    homogeneous_medium<T> m;
    m.g = p.transmission_scatter_anisotropy;
    if (!(p.transmission_depth > T(0))) return m;
    m.present = true;
    // The coefficients times lambda first (bounded: -ln of the smallest normal number is
    // below 745), so that the shift and the albedo do not meet inf - inf for a tiny lambda;
    // the division by lambda last, the extinction capped at the largest finite T.
    const rgb<T> color = glm::max(p.transmission_color, rgb<T>(std::numeric_limits<T>::min()));
    const rgb<T> t_lambda = -glm::log(color);
    const rgb<T> s_lambda = p.transmission_scatter;
    rgb<T> a_lambda = t_lambda - s_lambda;
    const T lowest = glm::min(a_lambda.x, glm::min(a_lambda.y, a_lambda.z));
    if (lowest < T(0)) a_lambda -= rgb<T>(lowest);
    const rgb<T> extinction_lambda = a_lambda + s_lambda;
    for (int c = 0; c < 3; ++c) {
        m.sigma_t[c] = glm::min(extinction_lambda[c] / p.transmission_depth, std::numeric_limits<T>::max());
        m.albedo[c] = extinction_lambda[c] > T(0) ? glm::min(T(1), s_lambda[c] / extinction_lambda[c]) : T(0);
    }
    return m;
}

/// Section "Subsurface": the interior medium of the subsurface slab. Extinction sigma_t =
/// 1 / r per channel with the mean free path r = subsurface_radius * subsurface_radius_scale
/// (r below 1e-6 scene units is read as 1e-6: the specification asks for a regularisation
/// as r -> 0); single-scattering albedo from subsurface_color C by the inversion of van de
/// Hulst's relation the specification gives (index-matched boundary; Kulla, Conty 2017;
/// d'Eon 2021):
///
///     s = 4.09712 + 4.20863 C - sqrt(9.59217 + 41.6808 C + 17.7126 C^2),
///     albedo = (1 - s^2) / (1 - g s^2),
///
/// g = subsurface_scatter_anisotropy. The caller validates the parameters.
template <std::floating_point T>
[[nodiscard]] inline homogeneous_medium<T> subsurface_medium(const openpbr_parameters<T>& p) noexcept {
    homogeneous_medium<T> m;
    m.present = true;
    m.g = p.subsurface_scatter_anisotropy;
    const rgb<T> r = glm::max(p.subsurface_radius * p.subsurface_radius_scale, rgb<T>(T(1e-6)));
    m.sigma_t = rgb<T>(1) / r;
    for (int c = 0; c < 3; ++c) {
        const double color = double(p.subsurface_color[c]);
        const double s = 4.09712 + 4.20863 * color - std::sqrt(9.59217 + 41.6808 * color + 17.7126 * color * color);
        const double s2 = s * s;
        const double albedo = (1 - s2) / (1 - double(m.g) * s2);
        m.albedo[c] = T(glm::clamp(albedo, 0.0, 1.0));
    }
    return m;
}

/// The Abbe number of the dispersion, V_d = transmission_dispersion_abbe_number /
/// transmission_dispersion_scale (section "Translucent base"); infinite (no dispersion) for
/// scale 0.
template <std::floating_point T>
[[nodiscard]] inline T abbe_number(const openpbr_parameters<T>& p) noexcept {
    if (!(p.transmission_dispersion_scale > T(0))) return std::numeric_limits<T>::infinity();
    return p.transmission_dispersion_abbe_number / p.transmission_dispersion_scale;
}

/// Section "Translucent base": the index at wavelength lambda_nm (nanometres) by Cauchy's
/// formula n = A + B / lambda^2 through n(587.6 nm) = n_d with Abbe number V_d =
/// (n_d - 1) / (n(486.1 nm) - n(656.3 nm)):
///
///     B = (n_d - 1) / (V_d (lambda_F^-2 - lambda_C^-2)),   A = n_d - B / lambda_d^2.
///
/// An infinite V_d returns n_d at every wavelength. A very small V_d (strong dispersion)
/// can take the formula below 0 far from lambda_d: the result is clamped to [1e-4, 1e4],
/// the indices openpbr_surface works with. The caller guarantees n_d > 0, V_d > 0, and a
/// wavelength > 0.
template <std::floating_point T>
[[nodiscard]] inline T dispersed_ior(T n_d, T abbe, T lambda_nm) noexcept {
    if (std::isinf(abbe)) return n_d;
    constexpr double lambda_f = 486.1, lambda_d = 587.6, lambda_c = 656.3;
    const double b = (double(n_d) - 1) / (double(abbe) * (1 / (lambda_f * lambda_f) - 1 / (lambda_c * lambda_c)));
    const double a = double(n_d) - b / (lambda_d * lambda_d);
    const double l = double(lambda_nm);
    const double n = a + b / (l * l);
    return T(std::isnan(n) ? double(n_d) : glm::clamp(n, 1e-4, 1e4));
}

} // namespace openpbr

} // namespace shade
