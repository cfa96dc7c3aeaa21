#pragma once
// shade::kulla_conty_anisotropic: the Kulla-Conty multiple-scattering compensation of
// shade::cook_torrance (shade/brdf/multiple_scattering.hpp) for anisotropic distributions,
// with the albedo of each direction read at its azimuth:
//
//   cook_torrance<ggx<T>, schlick<T>, smith_height_correlated<T>, cook_torrance_form::walter,
//                 kulla_conty_anisotropic>
//
// Not part of shade/shade.hpp (its tables are large): include this header where it is used.

#include <concepts>

#include <glm/common.hpp>

#include <shade/brdf/microfacet/anisotropic_albedo_table.hpp>
#include <shade/brdf/microfacet/beckmann.hpp>
#include <shade/brdf/microfacet/detail/anisotropic_albedo_data.hpp>
#include <shade/brdf/microfacet/detail/anisotropic_strong_albedo_data.hpp>
#include <shade/brdf/microfacet/ggx.hpp>
#include <shade/brdf/multiple_scattering.hpp>
#include <shade/core/types.hpp>

namespace shade {

/// Scattering policy of shade::cook_torrance: Kulla and Conty's multiple-scattering lobe
/// (shade::kulla_conty, whose formulas and citations apply unchanged),
///
///     f_ms(l, v) = F_ms (1 - E(l)) (1 - E(v)) / (pi (1 - E_avg)),
///
/// with E(w) the directional albedo (F = 1) of the anisotropic single-scattering lobe at
/// the direction w itself, not only at its cosine: the isotropic table at sqrt(alpha_x
/// alpha_y) plus the tabulated correction Delta(w) of
/// shade/brdf/microfacet/anisotropic_albedo_table.hpp, and E_avg the cosine-weighted
/// hemispherical average of that same E(w) (the isotropic E_avg plus Delta_avg). With F = 1
/// the albedo of f_ms is then (1 - E(v)) (1 - E_avg) / (1 - E_avg) = 1 - E(v), so the total
/// is 1 at every view and azimuth to the accuracy of the tables; f_ms stays a product of
/// one factor per direction, so the model stays reciprocal. For alpha_x = alpha_y it is
/// kulla_conty exactly (same values). Up to detail::anisotropic_albedo_ratio_max (20:1) E(w)
/// is read as above; beyond, up to a 1-D rough surface (alpha_min -> 0, OpenPBR's
/// anisotropy 1), as the isotropic table at the base roughness alpha_base (the root mean
/// square of the two, bent below 1) plus the strong-anisotropy correction of the same header,
/// and E_avg as the isotropic average at alpha_base plus that correction's average.
/// Applies to ggx and beckmann, as kulla_conty.
struct kulla_conty_anisotropic : kulla_conty {};

namespace detail {

/// The anisotropic correction tables of a distribution type and its two roughnesses;
/// defined for ggx and beckmann.
template <class Distribution>
struct anisotropic_albedo_tables_of;

template <std::floating_point T>
struct anisotropic_albedo_tables_of<ggx<T>> {
    static constexpr const float* delta = ggx_anisotropic_albedo_delta;
    static constexpr const float* average = ggx_anisotropic_albedo_delta_average;
    static constexpr const float* strong_delta = ggx_anisotropic_strong_albedo_delta;
    static constexpr const float* strong_average = ggx_anisotropic_strong_albedo_delta_average;
    [[nodiscard]] static T alpha_x(const ggx<T>& d) noexcept { return d.alpha_x(); }
    [[nodiscard]] static T alpha_y(const ggx<T>& d) noexcept { return d.alpha_y(); }
};

template <std::floating_point T>
struct anisotropic_albedo_tables_of<beckmann<T>> {
    static constexpr const float* delta = beckmann_anisotropic_albedo_delta;
    static constexpr const float* average = beckmann_anisotropic_albedo_delta_average;
    static constexpr const float* strong_delta = beckmann_anisotropic_strong_albedo_delta;
    static constexpr const float* strong_average = beckmann_anisotropic_strong_albedo_delta_average;
    [[nodiscard]] static T alpha_x(const beckmann<T>& d) noexcept { return d.m_x(); }
    [[nodiscard]] static T alpha_y(const beckmann<T>& d) noexcept { return d.m_y(); }
};

/// The state of kulla_conty_anisotropic: kulla_conty's, with E_avg the average of the
/// corrected E(w), and the lobe's cell in the correction tables (the strong-anisotropy
/// tables beyond detail::anisotropic_albedo_ratio_max, where alpha is the base roughness).
template <std::floating_point T>
struct scattering_state<kulla_conty_anisotropic, T> : kulla_conty_state<T> {
    anisotropic_albedo_cell<T> cell{};
    strong_anisotropy_cell<T> strong_cell{};
    bool anisotropic = false; ///< alpha_x != alpha_y; otherwise exactly kulla_conty's state
    bool strong = false;      ///< max / min roughness above anisotropic_albedo_ratio_max

    scattering_state() = default;

    // The table roughness and E_avg are settled first and the state is made once (its
    // Fresnel average is 40 evaluations of F).
    template <class Distribution, class Fresnel>
    scattering_state(const Distribution& distribution, const Fresnel& fresnel) noexcept {
        using tables = anisotropic_albedo_tables_of<Distribution>;
        using iso = albedo_tables_of<Distribution>;
        const T alpha_x = tables::alpha_x(distribution), alpha_y = tables::alpha_y(distribution);
        T table_alpha = iso::roughness(distribution);
        T average = albedo_average_lookup(iso::e_avg, albedo_grid_nodes, table_alpha);
        if (alpha_x != alpha_y) {
            anisotropic = true;
            const T alpha_max = glm::max(alpha_x, alpha_y), alpha_min = glm::min(alpha_x, alpha_y);
            if (alpha_max > T(anisotropic_albedo_ratio_max) * alpha_min) {
                strong = true;
                strong_cell = strong_anisotropy_locate(alpha_x, alpha_y);
                table_alpha = strong_cell.alpha_base;
                average = albedo_average_lookup(iso::e_avg, albedo_grid_nodes, table_alpha) +
                          strong_anisotropy_delta_average(tables::strong_average, strong_cell);
            } else {
                cell = anisotropic_albedo_locate(alpha_x, alpha_y);
                average += anisotropic_albedo_delta_average(tables::average, cell);
            }
            average = glm::clamp(average, T(0), T(1));
        }
        static_cast<kulla_conty_state<T>&>(*this) = make_kulla_conty_state(table_alpha, average, fresnel);
    }

    /// E(w) for the unit local direction w (n = +z), in [0, 1].
    template <class Distribution>
    [[nodiscard]] T albedo(const vec3<T>& w) const noexcept {
        const T e = albedo_lookup(albedo_tables_of<Distribution>::e, albedo_grid_nodes, w.z, this->alpha);
        if (!anisotropic) return e;
        const T delta =
            strong ? strong_anisotropy_delta(anisotropic_albedo_tables_of<Distribution>::strong_delta, strong_cell, w.x, w.y, w.z)
                   : anisotropic_albedo_delta(anisotropic_albedo_tables_of<Distribution>::delta, cell, w.x, w.y, w.z);
        // Clamped to [0, 1]: near a mirror the tables' noise can carry E + Delta just past 1,
        // and f_ms >= 0 needs 1 - E >= 0.
        return glm::clamp(e + delta, T(0), T(1));
    }
};

} // namespace detail

} // namespace shade
