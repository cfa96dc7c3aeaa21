#pragma once
// shade::dielectric_reflection_albedo: the directional albedo of the reflected part alone of
// a rough dielectric interface (shade::rough_dielectric over GGX), tabulated, for layered
// models that scale what lies below an interface by what its reflection leaves (OpenPBR's
// albedo scaling, f = f_R + (1 - E[f_R](v)) f_below).

#include <cmath>
#include <concepts>

#include <glm/common.hpp>

#include <shade/brdf/brdf.hpp>
#include <shade/brdf/fresnel.hpp>
#include <shade/bsdf/detail/dielectric_albedo_row.hpp>
#include <shade/bsdf/detail/dielectric_reflection_albedo_data.hpp>
#include <shade/bsdf/dielectric_albedo_table.hpp>
#include <shade/core/error.hpp>

namespace shade {

/// The directional albedo of the reflection lobe of shade::rough_dielectric<ggx<T>> with
/// isotropic roughness alpha, for a view at cosine mu = |n·v| on the side of relative index
/// eta_s = n_far / n_v (eta_s > 1: v in the rarer medium, light entering the denser one;
/// eta_s < 1: v in the denser medium, with total internal reflection beyond the critical
/// angle):
///
///     R_ss(mu, alpha, eta_s) = integral over v's hemisphere of f_R(l, v) |n·l| dl,
///     f_R = F G D / (4 |n·l| |n·v|)
///
/// with F the exact dielectric Fresnel reflectance at the microfacet normal (shade::F_dielectric),
/// G the height-correlated Smith term and D GGX (Walter, Marschner, Li, Torrance 2007,
/// "Microfacet Models for Refraction through Rough Surfaces", EGSR, eq. 20), single
/// scattering only (the reflections of rough_dielectric's sampler, each weighted by the F
/// with which it chooses them). The same in radiance and importance mode (a reflection
/// crosses no interface). Returns a dimensionless value in [0, 1]: what the interface
/// reflects of the energy arriving along v; 1 - R_ss is what it transmits or loses to masking.
///
/// Read from a table (shade/bsdf/detail/dielectric_reflection_albedo_data.hpp, written by
/// examples/dielectric_albedo_tables --reflection; grid and interpolation in
/// shade/bsdf/dielectric_albedo_table.hpp, detail::dielectric_reflection_albedo_grid) that
/// holds R_ss - F(mu, eta_s) on a grid of mu, sqrt(alpha) and log(eta_hat - 1),
/// eta_hat = max(eta_s, 1 / eta_s) in [1.001, 3]: the lookup adds F(mu, eta_s) back, so as
/// alpha -> 0 it tends to the exact Fresnel reflectance of a smooth interface, total
/// internal reflection included (the table's difference at alpha = 1e-4 is masking only).
/// Its accuracy, measured against fresh estimates at the centre of every cell, is stated in
/// the data header. Outside the grid:
///   * alpha is clamped to [0, 1] (a rougher interface reads alpha = 1); the table's first
///     row, estimated at alpha = 1e-4, stands for alpha = 0 (it differs from a mirror by
///     masking below 1e-5 for mu >= 0.05, and by the blur of F over a 1e-4 spread of
///     normals, which matters only within about 1e-3 of the critical angle);
///   * eta_hat above 3 (a dense dielectric, or OpenPBR's specular_weight above 1, which
///     raises the index): the table at the end eta_3 of v's side (3 or 1/3) plus the change
///     of the lobe's albedo with its Fresnel factor (detail::reflection_albedo_change),
///
///         R_ss(mu, alpha, eta_s) = R_ss(mu, alpha, eta_3)
///                                  + sum_k w_k(mu, alpha) (F(c_k, eta_s) - F(c_k, eta_3)),
///
///     w_k the lobe's measure of c = v·h at nodes c_k (shade/brdf/microfacet/
///     cosine_weights.hpp): exact at eta_hat = 3 and tending to the lobe's albedo with F = 1
///     as eta_hat grows. Against the model's own sampler it is within 3e-3 entering; exiting,
///     within 1e-2 for mu <= 0.8 and 5e-2 above, where the node sum's linear pieces in v·h
///     cross the total-reflection edge, which nears v·h = 1 as eta_hat grows;
///   * eta_hat in [1, 1.001): F(mu, eta_s) plus the table's difference at 1.001 scaled by
///     (eta_hat - 1) / 0.001, so that an index-matched interface (eta_s = 1) reflects
///     nothing, R_ss = 0 exactly (the difference is linear in eta_hat - 1 near 1).
/// mu is clamped to [0, 1].
///
/// Preconditions (unchecked): eta_s finite and > 0, alpha >= 0, mu not NaN. The checked
/// overload below throws instead.
template <std::floating_point T>
[[nodiscard]] inline T dielectric_reflection_albedo(unchecked_t, T mu, T alpha, T eta_s) noexcept {
    constexpr const detail::dielectric_albedo_grid& grid = detail::dielectric_reflection_albedo_grid;
    const T m = glm::clamp(mu, T(0), T(1));
    const T fresnel = F_dielectric(m, eta_s);
    const T eta_hat = eta_s > T(1) ? eta_s : T(1) / eta_s;
    detail::dielectric_albedo_cell<T> cell = detail::dielectric_albedo_locate(grid, alpha, eta_s);
    // Row 0, estimated at alpha = 1e-4 (a mirror but for masking), stands for alpha -> 0:
    // sqrt(alpha) is read from 0, not from sqrt(1e-4) as the clamped alpha would.
    cell.alpha = detail::albedo_grid_locate(std::sqrt(glm::clamp(alpha, T(0), T(1))), grid.alpha_nodes);
    T difference = detail::dielectric_albedo_interpolate(detail::ggx_rough_dielectric_reflection_albedo, grid, cell, m);
    // Below the grid's eta_hat, the difference shrinks linearly to 0 at eta_hat = 1.
    if (eta_hat < T(grid.eta_min)) difference *= (eta_hat - T(1)) / T(grid.eta_min - 1);
    if (!(eta_hat > T(grid.eta_max))) return glm::clamp(fresnel + difference, T(0), T(1));
    // Beyond the grid the cell reads the end eta_end: R_ss there plus the change with F.
    const T eta_end = eta_s > T(1) ? T(grid.eta_max) : T(1) / T(grid.eta_max);
    return glm::clamp(F_dielectric(m, eta_end) + difference + detail::reflection_albedo_change(m, alpha, eta_end, eta_s),
                      T(0), T(1));
}

/// dielectric_reflection_albedo(unchecked, mu, alpha, eta_s), validated first: throws
/// shade::invalid_parameter naming "mu" unless mu lies in [0, 1], "alpha" unless alpha is
/// finite and >= 0, "eta_s" unless eta_s lies in [1e-4, 1e4] (1, an index-matched
/// interface, allowed: it returns 0).
template <std::floating_point T>
[[nodiscard]] inline T dielectric_reflection_albedo(T mu, T alpha, T eta_s) {
    require_in_range("mu", mu, T(0), T(1));
    require_non_negative("alpha", alpha);
    require_in_range("eta_s", eta_s, dielectric_eta_min<T>, dielectric_eta_max<T>);
    return dielectric_reflection_albedo(unchecked, mu, alpha, eta_s);
}

/// The reflection albedo of an anisotropic GGX interface (roughnesses alpha_x, alpha_y) for
/// no view azimuth in particular: the isotropic table at the geometric mean
/// sqrt(alpha_x alpha_y). R_ss of an anisotropic interface depends on the azimuth; the form
/// that takes the view's direction (shade/bsdf/dielectric_anisotropic_reflection_albedo.hpp)
/// reads it there. The error of this one against
/// direct estimates at 2:1 and 10:1 anisotropy is in docs/properties.md ("Reflection albedo
/// of the rough dielectric"). Preconditions as the isotropic form (alpha_x, alpha_y >= 0).
/// Dimensionless, in [0, 1].
template <std::floating_point T>
[[nodiscard]] inline T dielectric_reflection_albedo(unchecked_t, T mu, T alpha_x, T alpha_y, T eta_s) noexcept {
    return dielectric_reflection_albedo(unchecked, mu, std::sqrt(alpha_x * alpha_y), eta_s);
}

/// The azimuth-free anisotropic form, validated first: throws shade::invalid_parameter naming
/// "mu", "alpha_x", "alpha_y" or "eta_s" as the isotropic checked form does.
template <std::floating_point T>
[[nodiscard]] inline T dielectric_reflection_albedo(T mu, T alpha_x, T alpha_y, T eta_s) {
    require_in_range("mu", mu, T(0), T(1));
    require_non_negative("alpha_x", alpha_x);
    require_non_negative("alpha_y", alpha_y);
    require_in_range("eta_s", eta_s, dielectric_eta_min<T>, dielectric_eta_max<T>);
    return dielectric_reflection_albedo(unchecked, mu, alpha_x, alpha_y, eta_s);
}

} // namespace shade
