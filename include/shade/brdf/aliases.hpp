#pragma once
// Short names for the common reflection-model configurations, and functions that build
// them from the parameters one usually has (a roughness alpha, a colour), so that
// cook_torrance<ggx<T>, schlick<T>, smith_height_correlated<T>> need not be spelled out.

#include <concepts>

#include <shade/brdf/cook_torrance.hpp>
#include <shade/brdf/coupled_plastic.hpp>
#include <shade/brdf/fresnel.hpp>
#include <shade/brdf/microfacet.hpp>
#include <shade/core/types.hpp>

namespace shade {

/// A rough metal: GGX microfacets (Walter, Marschner, Li, Torrance 2007), Schlick's
/// Fresnel with the metal's colour as f0 (Schlick 1994), height-correlated Smith masking
/// (Heitz 2014), the microfacet form F D G / (4 (n·l)(n·v)), no diffuse part.
template <std::floating_point T>
using ggx_conductor = cook_torrance<ggx<T>, schlick<T>, smith_height_correlated<T>>;

/// The same metal with Beckmann microfacets (Beckmann, Spizzichino 1963).
template <std::floating_point T>
using beckmann_conductor = cook_torrance<beckmann<T>, schlick<T>, smith_height_correlated<T>>;

/// ggx_conductor compensated for multiple scattering (shade::kulla_conty, Kulla, Conty
/// 2017): with f0 = 1 it reflects all the light at every roughness and view, where
/// ggx_conductor loses up to ~70 % at alpha = 1.
template <std::floating_point T>
using compensated_ggx_conductor =
    cook_torrance<ggx<T>, schlick<T>, smith_height_correlated<T>, cook_torrance_form::walter, kulla_conty>;

/// beckmann_conductor compensated for multiple scattering (shade::kulla_conty).
template <std::floating_point T>
using compensated_beckmann_conductor =
    cook_torrance<beckmann<T>, schlick<T>, smith_height_correlated<T>, cook_torrance_form::walter, kulla_conty>;

/// A rough plastic: a Lambertian base k_d / pi under a GGX specular lobe with the exact
/// dielectric Fresnel reflectance of a coating of relative index eta, height-correlated
/// Smith masking. The two parts simply add (no energy exchange between the coating and
/// the base), as cook_torrance's diffuse term does; shade::coupled_plastic couples them.
template <std::floating_point T>
using rough_plastic = cook_torrance<ggx<T>, dielectric_fresnel<T>, smith_height_correlated<T>>;

/// A ggx_conductor of roughness alpha (GGX's alpha, in [1e-4, 1e4]) and reflectance at
/// normal incidence f0 (per channel in [0, 1]: e.g. gold ~ (1.0, 0.71, 0.29)). Throws
/// shade::invalid_parameter naming "alpha" or "f0".
template <std::floating_point T>
[[nodiscard]] ggx_conductor<T> make_ggx_conductor(T alpha, const rgb<T>& f0) {
    return ggx_conductor<T>(ggx<T>(alpha), schlick<T>(f0));
}

/// A compensated_ggx_conductor of roughness alpha (in [1e-4, 1e4]; the compensation is
/// complete up to alpha = 1) and reflectance at normal incidence f0 (per channel in
/// [0, 1]). Throws shade::invalid_parameter naming "alpha" or "f0".
template <std::floating_point T>
[[nodiscard]] compensated_ggx_conductor<T> make_compensated_ggx_conductor(T alpha, const rgb<T>& f0) {
    return compensated_ggx_conductor<T>(ggx<T>(alpha), schlick<T>(f0));
}

/// A coupled_plastic of GGX roughness alpha (in [1e-4, 1e4]) and base albedo k_d (per
/// channel >= 0). Throws shade::invalid_parameter naming "alpha" or "k_d".
template <std::floating_point T>
[[nodiscard]] coupled_plastic<T> make_coupled_plastic(T alpha, const rgb<T>& k_d) {
    return coupled_plastic<T>(ggx<T>(alpha), k_d);
}

/// A rough_plastic of roughness alpha, diffuse albedo k_d (per channel >= 0) and coating
/// index eta (> 0; 1.5 for common plastics). Throws shade::invalid_parameter naming
/// "alpha", "eta" or "k_d".
template <std::floating_point T>
[[nodiscard]] rough_plastic<T> make_rough_plastic(T alpha, const rgb<T>& k_d, T eta = T(1.5)) {
    return rough_plastic<T>(ggx<T>(alpha), dielectric_fresnel<T>(eta), rgb<T>(1), k_d);
}

} // namespace shade
