#pragma once
// shade::compensated_rough_dielectric: shade::rough_dielectric over GGX or Beckmann with the energy its
// single-scattering lobes lose to masking given back by a multiple-scattering lobe, so that
// a lossless interface neither darkens nor creates energy, seen from either side.

#include <cmath>
#include <concepts>
#include <cstddef>
#include <limits>
#include <optional>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <shade/brdf/brdf.hpp>
#include <shade/brdf/fresnel.hpp>
#include <shade/brdf/microfacet/beckmann.hpp>
#include <shade/brdf/microfacet/ggx.hpp>
#include <shade/bsdf/bsdf.hpp>
#include <shade/bsdf/detail/beckmann_dielectric_albedo_beyond_data.hpp>
#include <shade/bsdf/detail/beckmann_dielectric_albedo_data.hpp>
#include <shade/bsdf/detail/dielectric_albedo_beyond_data.hpp>
#include <shade/bsdf/detail/dielectric_albedo_data.hpp>
#include <shade/bsdf/detail/dielectric_albedo_row.hpp>
#include <shade/bsdf/detail/dielectric_anisotropic_albedo_data.hpp>
#include <shade/bsdf/rough_dielectric_albedo_grid.hpp>
#include <shade/bsdf/dielectric_albedo_table.hpp>
#include <shade/bsdf/dielectric_anisotropic_albedo_table.hpp>
#include <shade/bsdf/dielectric_reflection_albedo.hpp>
#include <shade/bsdf/rough_dielectric.hpp>
#include <shade/core/math.hpp>
#include <shade/core/sampling.hpp>
#include <shade/core/scalar.hpp>
#include <shade/core/surface_point.hpp>
#include <shade/core/types.hpp>

namespace shade {

namespace detail {

/// Below this 1 - E_avg (on either side) the multiple-scattering lobe is taken as 0: the
/// interface is then so smooth that it loses almost nothing, and 1 / (1 - E_avg) would
/// only amplify the float rounding of the table.
inline constexpr double dielectric_compensation_min_loss = 1e-6;

/// Below this 1 - E_s,avg (the tables' isotropic average plus the anisotropic correction's) an
/// anisotropic interface integrates E_s,avg from its clamped reads instead
/// (compensated_rough_dielectric::clamped_average): the reads that the clamp to 1 lowers
/// are then a large part of the loss. Above it they are a small part, and the integral
/// (several times the cost of the rest of the construction) is not paid.
inline constexpr double dielectric_clamped_average_below = 0.05;

/// The albedo tables of the compensated rough dielectric over a distribution type, and its
/// two roughnesses; defined for ggx and beckmann (Beckmann's m read as alpha, as its
/// generator does): e on grid for eta_hat up to 3, e_beyond on beyond_grid above (the
/// continuation, dielectric_albedo_beyond_grid). `anisotropic` says whether the anisotropic correction of
/// shade/bsdf/dielectric_anisotropic_albedo_table.hpp is tabulated for it.
template <class Distribution>
struct dielectric_albedo_tables_of;

template <std::floating_point T>
struct dielectric_albedo_tables_of<ggx<T>> {
    static constexpr const float* e = ggx_rough_dielectric_albedo;
    static constexpr dielectric_albedo_grid grid{}; ///< the grid of e
    static constexpr const float* e_beyond = ggx_rough_dielectric_albedo_beyond;
    static constexpr dielectric_albedo_grid beyond_grid = dielectric_albedo_beyond_grid; ///< the grid of e_beyond
    static constexpr bool anisotropic = true;
    static constexpr const float* delta = ggx_dielectric_anisotropic_delta;
    static constexpr const float* delta_average = ggx_dielectric_anisotropic_delta_average;
    [[nodiscard]] static T alpha_x(const ggx<T>& d) noexcept { return d.alpha_x(); }
    [[nodiscard]] static T alpha_y(const ggx<T>& d) noexcept { return d.alpha_y(); }
};

template <std::floating_point T>
struct dielectric_albedo_tables_of<beckmann<T>> {
    static constexpr const float* e = beckmann_rough_dielectric_albedo;
    static constexpr dielectric_albedo_grid grid = dielectric_beckmann_albedo_grid; ///< the grid of e
    static constexpr const float* e_beyond = beckmann_rough_dielectric_albedo_beyond;
    static constexpr dielectric_albedo_grid beyond_grid = dielectric_beckmann_albedo_beyond_grid; ///< the grid of e_beyond
    static constexpr bool anisotropic = false;
    static constexpr const float* delta = nullptr;
    static constexpr const float* delta_average = nullptr;
    [[nodiscard]] static T alpha_x(const beckmann<T>& d) noexcept { return d.m_x(); }
    [[nodiscard]] static T alpha_y(const beckmann<T>& d) noexcept { return d.m_y(); }
};

} // namespace detail

/// shade::rough_dielectric<Distribution> (GGX by default, or Beckmann) compensated for
/// multiple scattering: the single-scattering
/// BSDF f_ss of rough_dielectric (unchanged) plus a lobe f_ms that returns the energy f_ss
/// loses to masking, with Kulla and Conty's reciprocal product form extended to
/// transmission.
///
/// Kulla, Conty 2017, "Revisiting Physically Based Shading at Imageworks", SIGGRAPH 2017
/// course "Physically Based Shading in Theory and Practice" (the multiple-scattering
/// slides: the lobe (1 - E(mu_l)) (1 - E(mu_v)) / (pi (1 - E_avg)), after Kelemen,
/// Szirmay-Kalos 2001, "A Microfacet Based Coupled Specular-Matte BRDF Model with
/// Importance Sampling", Eurographics short presentation; for dielectrics, separate tables
/// for light entering and leaving the denser medium and a split of the lobe between
/// reflection and transmission that keeps reciprocity; the slides number no equations).
/// Here E_s(mu) is the total single-scattering albedo R + T (importance mode) seen from
/// medium s at view cosine mu (shade/bsdf/dielectric_albedo_table.hpp), E_s,avg its
/// cosine-weighted average (integrated from the table when the model is built, 40 lookups
/// per side), eta_s = n_far / n_s, and tau_s the share of the lost energy
/// that crosses the interface. In radiance mode, with v in medium s, mu = |n·w|:
///
///     reflection:    f_ms = (1 - tau_s) (1 - E_s(mu_l)) (1 - E_s(mu_v)) / (pi (1 - E_s,avg))
///     transmission:  f_ms = tau_s (1 - E_far(mu_l)) (1 - E_s(mu_v)) / (eta_s^2 pi (1 - E_far,avg))
///
/// (importance mode: the transmission times eta_s^2, as for f_ss). Integrating over l,
/// f_ms returns exactly 1 - E_s(mu_v) in importance mode, (1 - tau_s) of it reflected and
/// tau_s transmitted, so R + T = E_ss(mu_v) + 1 - E_s(mu_v) = 1 up to the table's error.
/// Adjoint reciprocity, f(l, v) / eta_v^2 = f(v, l) / eta_l^2, holds for f_ms when
///
///     tau_inside (1 - E_inside,avg) eta^2 = tau_outside (1 - E_outside,avg)
///
/// (eta = n_inside / n_outside). tau on the rarer side is 1 - F_avg, F_avg the
/// cosine-weighted hemispherical average of the exact Fresnel reflectance from that side
/// (what a smooth interface transmits of uniform light), and tau on the denser side follows
/// from the relation; if it would exceed 1 it is 1 and the rarer side's follows instead.
///
/// Properties: energy conserving (R + T = 1 in importance mode for every view, to the
/// table's accuracy) and adjoint-reciprocal like rough_dielectric; f_ss keeps its values.
/// Turquin 2019 ("A Practical Energy Compensation for Multiple Scattering in Microfacet
/// Models", Ubisoft tech report) scales f_ss by a factor of the view alone, which would
/// give R + T = 1 as well but not the adjoint relation; hence Kulla and Conty's product.
/// A type of its own rather than a policy of rough_dielectric (as shade::kulla_conty is of
/// cook_torrance), so that rough_dielectric's users do not compile the tables.
/// One table per distribution (GGX and Beckmann, Beckmann's m read as alpha). The GGX table
/// holds point values; the Beckmann table an upper envelope of E_s (it errs high by design,
/// shade/bsdf/dielectric_albedo_table.hpp), so that R + T = 1 + E_true - E_table errs below 1
/// rather than above (measured ranges in docs/properties.md).
/// The tables cover alpha in [1e-4, 1] and eta_hat = max(eta, 1 / eta) in [1.05, 3], and
/// their continuations (point values, dielectric_albedo_beyond_data.hpp, read
/// detail::dielectric_albedo_beyond_lift high) eta_hat from 3 to 1000; outside that range
/// the nearest end is read, so the compensation is approximate there (and partial for
/// alpha > 1).
///
/// Anisotropic GGX (alpha_x != alpha_y): E_s(w) depends on the azimuth of w as well as on
/// mu, and no isotropic roughness reproduces it at every azimuth, so E_s(w) is the
/// isotropic table at sqrt((alpha_x^2 + alpha_y^2) / 2) plus the tabulated correction Delta_s(w) of
/// shade/bsdf/dielectric_anisotropic_albedo_table.hpp, read at each direction's own azimuth
/// (for l on the far side, with the far side's table), and E_s,avg is the cosine-weighted
/// hemispherical average of that same E_s(w). The formulas above hold unchanged with
/// E_s(mu) read as E_s(w): f_ms stays a product of one factor per direction (adjoint
/// reciprocal) and returns 1 - E_s(v) at every view. The correction covers every anisotropy
/// (alpha_min / alpha_max down to 0, OpenPBR's anisotropy 1) for the larger alpha up to
/// sqrt 2, and is an upper envelope of E_s, so that R + T errs below 1 rather than above
/// (measured ranges in docs/properties.md). Isotropic interfaces read no correction (the values are
/// those of the isotropic tables alone). Anisotropic Beckmann has no correction table: it
/// reads the isotropic table at sqrt(m_x m_y) whatever the azimuth, an approximation that
/// departs from R + T = 1 both ways as anisotropic GGX did before its correction.
///
/// Per-interface mode: built with a shade::rough_dielectric_albedo_grid of its own
/// distribution and eta, the model reads E_s(w) and E_s,avg from that grid (integrated for
/// this interface when the grid was built) instead of the tables, with the formulas above
/// unchanged; from a grid of one side only, on that side (the other reads the tables: each
/// side's E_s,avg stays the average of the E_s(w) it reads, so f_ms still returns
/// 1 - E_s(v)). The grid
/// needs no interpolation over the interface's parameters, so it holds R + T near 1 where the
/// anisotropic correction cannot (strong anisotropy, seen from the denser side; measured
/// ranges in docs/properties.md). The model keeps a pointer to the grid: the grid must
/// outlive it and every copy of it.
///
/// Sampling: with probability E_s(mu_v) rough_dielectric's own sampler (uc rescaled), else
/// the multiple-scattering lobe, a cosine-weighted direction on the far side with
/// probability tau_s and on v's side otherwise; pdf and weight are those of the mixture.
/// Flags glossy reflection or glossy transmission.
///
/// Parameters as rough_dielectric: eta = n_inside / n_outside in [1e-4, 1e4], not 1.
template <std::floating_point T, class Distribution = ggx<T>>
class compensated_rough_dielectric {
    using tables = detail::dielectric_albedo_tables_of<Distribution>;
    static_assert(std::same_as<scalar_of<Distribution>, T>, "the distribution's scalar must be T");

public:
    using scalar_type = T;
    using distribution_type = Distribution;
    using single_scattering_type = rough_dielectric<Distribution>;

    /// A compensated interface. Throws shade::invalid_parameter naming "eta" unless eta
    /// lies in [1e-4, 1e4] and is not 1 (as rough_dielectric).
    compensated_rough_dielectric(const Distribution& distribution, T eta) : single_(distribution, eta) { prepare(); }

    /// Unchecked: the caller guarantees eta in [1e-4, 1e4], eta != 1.
    compensated_rough_dielectric(unchecked_t, const Distribution& distribution, T eta) noexcept
        : single_(unchecked, distribution, eta) {
        prepare();
    }

    /// A compensated GGX interface that reads E_s from `grid` (per-interface mode, class
    /// comment) instead of the tables; the grid must outlive the model. Throws
    /// shade::invalid_parameter naming "eta" as the constructor above, or naming "grid"
    /// unless the grid was built for exactly this distribution and eta.
    compensated_rough_dielectric(const Distribution& distribution, T eta, const rough_dielectric_albedo_grid<T>& grid)
        requires std::same_as<Distribution, ggx<T>>
        : single_(distribution, eta), grid_(&grid) {
        // (A discarded branch for another distribution, which this constructor excludes, so
        // that the class stays explicitly instantiable for it.)
        bool matches = false;
        if constexpr (std::same_as<Distribution, ggx<T>>) matches = grid.built_for(distribution, eta);
        if (!matches)
            throw invalid_parameter("grid", "must be built for this model's distribution and eta",
                                    "a grid of alpha " + detail::to_text(grid.distribution().alpha_x()) + " x " +
                                        detail::to_text(grid.distribution().alpha_y()) + ", eta " +
                                        detail::to_text(grid.eta()));
        prepare();
    }

    /// The grid the model reads E_s from, or nullptr when it reads the tables.
    [[nodiscard]] constexpr const rough_dielectric_albedo_grid<T>* albedo_grid() const noexcept { return grid_; }

    /// The single-scattering model this compensates.
    [[nodiscard]] constexpr const single_scattering_type& single_scattering() const noexcept { return single_; }
    /// The distribution of microfacet normals.
    [[nodiscard]] constexpr const Distribution& distribution() const noexcept { return single_.distribution(); }
    /// The relative index of refraction n_inside / n_outside.
    [[nodiscard]] constexpr T eta() const noexcept { return single_.eta(); }

    /// E_s of the tables (or of the grid, in per-interface mode) for a view in medium
    /// `inside` (false: outside) at cosine mu and azimuth 0 (in the plane of n and the
    /// tangent t): the single-scattering R + T the compensation assumes, dimensionless, in
    /// [0, 1].
    [[nodiscard]] T single_scattering_albedo(bool inside, T mu) const noexcept {
        const T m = glm::clamp(mu, T(0), T(1));
        return albedo(inside ? 1 : 0, vec3<T>(std::sqrt((T(1) - m) * (T(1) + m)), T(0), m));
    }

    /// E_s(w) of the tables (or the grid) for the unit direction w on its own side s of the
    /// surface (its azimuth included): the single-scattering R + T the compensation assumes
    /// for a view along w, dimensionless, in [0, 1]; 0 when w lies on the surface.
    [[nodiscard]] T single_scattering_albedo(const vec3<T>& w, const surface_point<T>& at) const noexcept {
        const vec3<T> w_local = at.shading.to_local(w);
        if (!(w_local.z != T(0)) || !std::isfinite(w_local.z)) return T(0);
        return albedo(w_local.z > T(0) ? 0 : 1, w_local);
    }

    /// The share tau of the lost energy that the multiple-scattering lobe transmits, for a
    /// view in medium `inside` (false: outside). In [0, 1].
    [[nodiscard]] T transmitted_share(bool inside) const noexcept { return side_[inside ? 1 : 0].tau; }

    /// The directional albedo of the reflected part for the view v on either side (importance
    /// mode; dimensionless, in [0, 1]): the energy arriving along v that leaves on v's side,
    ///
    ///     R(v) = R_ss(v) + (1 - tau_s) (1 - E_s(v)),
    ///
    /// R_ss the reflected part of single scattering (shade::dielectric_reflection_albedo;
    /// for anisotropic GGX read at sqrt(alpha_x alpha_y), an approximation whose measured
    /// error is in docs/properties.md) and (1 - tau_s) (1 - E_s(v)) what f_ms reflects (the
    /// class comment). 0 when v lies on the surface. GGX only (no reflection table for
    /// Beckmann). Accuracy: that of the reflection table (stated in
    /// shade/bsdf/detail/dielectric_reflection_albedo_data.hpp) against the model's own
    /// sampler; the total-albedo table's error cancels, f_ms being built from the same E_s.
    [[nodiscard]] T reflectance(const vec3<T>& v, const surface_point<T>& at) const noexcept
        requires std::same_as<Distribution, ggx<T>>
    {
        const vec3<T> v_local = at.shading.to_local(v);
        if (!(v_local.z != T(0)) || !std::isfinite(v_local.z)) return T(0);
        const std::size_t s = v_local.z > T(0) ? 0 : 1;
        const T r_ss = single_reflectance(s, v_local);
        if (!enabled_) return r_ss;
        return glm::clamp(r_ss + (T(1) - side_[s].tau) * (T(1) - albedo(s, v_local)), T(0), T(1));
    }

    /// The directional albedo of the transmitted part for the view v on either side
    /// (importance mode: no 1/eta^2; dimensionless, in [0, 1]): the energy arriving along v
    /// that crosses the interface,
    ///
    ///     T(v) = (E_s(v) - R_ss(v)) + tau_s (1 - E_s(v)),
    ///
    /// single scattering's R + T from the total-albedo table less its reflected part, plus
    /// what f_ms transmits; clamped to [0, 1] (the two tables' errors could carry E_s - R_ss
    /// just below 0 where nearly everything is reflected). 0 when v lies on the surface. GGX
    /// only. reflectance + transmittance = 1 (unless a clamp acts) whenever the compensation
    /// is on (1 - E_s,avg above detail::dielectric_compensation_min_loss on both sides).
    /// Accuracy: the total-albedo table's and the reflection table's, added (both stated in
    /// their generated headers).
    [[nodiscard]] T transmittance(const vec3<T>& v, const surface_point<T>& at) const noexcept
        requires std::same_as<Distribution, ggx<T>>
    {
        const vec3<T> v_local = at.shading.to_local(v);
        if (!(v_local.z != T(0)) || !std::isfinite(v_local.z)) return T(0);
        const std::size_t s = v_local.z > T(0) ? 0 : 1;
        const T e = albedo(s, v_local);
        const T multiple_share = enabled_ ? side_[s].tau * (T(1) - e) : T(0);
        return glm::clamp(e - single_reflectance(s, v_local) + multiple_share, T(0), T(1));
    }

    /// The BSDF value in 1/sr without the cosine, radiance mode, f_ss + f_ms, for l and v
    /// on either side; 0 when either lies on the surface.
    [[nodiscard]] rgb<T> f(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const noexcept {
        return f_and_pdf(l, v, at).f;
    }

    /// The density (1/sr, over the sphere) with which sample() draws l for v.
    [[nodiscard]] T pdf(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const noexcept {
        const prepared_view view = prepare(v, at);
        if (!view.valid) return T(0);
        const T p_ss = enabled_ ? view.albedo : T(1);
        return p_ss * single_.pdf(l, v, at) + (T(1) - p_ss) * multiple_pdf(view.side, at.shading.to_local(l), view.v_local);
    }

    /// What depends on the view alone, for a caller that draws and evaluates several
    /// directions for one view (a mixture of lobes): v, v_local (in the shading frame), its
    /// side (0 outside, 1 inside), albedo E_s(v) (single_scattering_albedo(v, at)), and
    /// valid, false when v lies on the surface (or is not finite).
    struct prepared_view {
        vec3<T> v{0, 0, 1}, v_local{0, 0, 1};
        std::size_t side = 0;
        T albedo = 0;
        bool valid = false;
    };

    /// The prepared_view of v at `at` (pass the same `at` with it).
    [[nodiscard]] prepared_view prepare(const vec3<T>& v, const surface_point<T>& at) const noexcept {
        prepared_view p;
        p.v = v;
        p.v_local = at.shading.to_local(v);
        if (!(p.v_local.z != T(0)) || !std::isfinite(p.v_local.z)) return p;
        p.valid = true;
        p.side = p.v_local.z > T(0) ? 0 : 1;
        p.albedo = albedo(p.side, p.v_local);
        return p;
    }

    /// f(l, v, at) and pdf(l, v, at) in one call, the shared terms computed once.
    struct value_and_density {
        rgb<T> f{0}; ///< as f()
        T pdf = 0;   ///< as pdf()
    };
    [[nodiscard]] value_and_density f_and_pdf(const vec3<T>& l, const vec3<T>& v,
                                              const surface_point<T>& at) const noexcept {
        return f_and_pdf(l, prepare(v, at), at);
    }

    /// f_and_pdf(l, view.v, at).
    [[nodiscard]] value_and_density f_and_pdf(const vec3<T>& l, const prepared_view& view,
                                              const surface_point<T>& at) const noexcept {
        if (!view.valid) return {};
        detail::assert_unit_directions(l, view.v, at);
        return evaluate(at.shading.to_local(l), view, transport_mode::radiance);
    }

    /// The reflected part of the multiple-scattering lobe alone, for l on the side of the
    /// prepared view (1/sr without the cosine; the same in both transport modes):
    ///
    ///     f_ms,R(l, v) = (1 - tau_s) (1 - E_s(l)) (1 - E_s(v)) / (pi (1 - E_s,avg)),
    ///
    /// whose integral against |n·l| over v's side is (1 - tau_s) (1 - E_s(v)) (class
    /// comment). 0 for l on the far side or on the surface, for an invalid view, or when the
    /// compensation is off. f_and_pdf(l, view, at).f for such an l is this plus the single-
    /// scattering reflection.
    [[nodiscard]] T multiple_scattering_reflection(const vec3<T>& l, const prepared_view& view,
                                                   const surface_point<T>& at) const noexcept {
        if (!view.valid || !enabled_) return T(0);
        const vec3<T> l_local = at.shading.to_local(l);
        if (!(l_local.z != T(0)) || !std::isfinite(l_local.z)) return T(0);
        if ((l_local.z < T(0)) != (view.v_local.z < T(0))) return T(0);
        const std::size_t s = view.side;
        return side_[s].reflect * (T(1) - albedo(s, l_local)) * (T(1) - view.albedo);
    }

    /// The direction l that sample(v, uc, u, at) draws, without f and pdf (for a mixture
    /// that evaluates itself at l); nullopt where sample()'s direction is.
    [[nodiscard]] std::optional<vec3<T>> draw(const vec3<T>& v, T uc, const vec2<T>& u,
                                              const surface_point<T>& at) const noexcept {
        return draw(prepare(v, at), uc, u, at);
    }

    /// draw(view.v, uc, u, at).
    [[nodiscard]] std::optional<vec3<T>> draw(const prepared_view& view, T uc, const vec2<T>& u,
                                              const surface_point<T>& at) const noexcept {
        if (!view.valid) return std::nullopt;
        const T p_ss = enabled_ ? view.albedo : T(1);
        if (uc < p_ss) {
            const T uc_ss = glm::min(uc / p_ss, T(1) - std::numeric_limits<T>::epsilon() / 2);
            const std::optional<vec3<T>> l_local = single_.draw_local(view.v_local, uc_ss, u);
            if (!l_local) return std::nullopt;
            return at.shading.to_world(*l_local);
        }
        const T uc_ms = (uc - p_ss) / (T(1) - p_ss);
        const bool transmit = uc_ms < side_[view.side].tau;
        vec3<T> w = square_to_cosine_hemisphere(u);
        // Cosine-weighted about v's side (reflection) or the far side (transmission).
        if ((view.v_local.z < T(0)) != transmit) w.z = -w.z;
        return at.shading.to_world(w);
    }

    /// Draws l for v (either side) from the mixture above; f and weight in the given mode,
    /// eta of the sample eta_l / eta_v. nullopt when v lies on the surface or the drawn l
    /// does (or rough_dielectric's sampler draws nothing).
    [[nodiscard]] std::optional<bsdf_sample<T>> sample(const vec3<T>& v, T uc, const vec2<T>& u,
                                                       const surface_point<T>& at,
                                                       transport_mode mode = transport_mode::radiance) const noexcept {
        const prepared_view view = prepare(v, at);
        const std::optional<vec3<T>> drawn = draw(view, uc, u, at);
        if (!drawn) return std::nullopt;
        const vec3<T>& l = *drawn;
        const vec3<T> l_local = at.shading.to_local(l);
        if (!(l_local.z != T(0)) || !std::isfinite(l_local.z)) return std::nullopt;
        const bool transmitted = (l_local.z < T(0)) != (view.v_local.z < T(0));
        detail::assert_unit_directions(l, v, at);
        const value_and_density value = evaluate(l_local, view, mode);
        const std::optional<brdf_sample<T>> r =
            detail::make_brdf_sample(l, value.f, value.pdf, std::abs(l_local.z));
        if (!r) return std::nullopt;
        return bsdf_sample<T>{r->l, r->f, r->pdf, r->weight,
                              transmitted ? bsdf_flags::glossy_transmission : bsdf_flags::glossy_reflection,
                              transmitted ? side_[view.side].eta_s : T(1)};
    }

private:
    /// What the lobe keeps per medium s (0 outside, 1 inside) of the view.
    struct side_state {
        detail::dielectric_albedo_cell<T> cell{}; ///< where E_s is read
        detail::dielectric_albedo_row<T, detail::dielectric_albedo_mu_nodes> row{}; ///< E_s at the cell, along mu
        T eta_s = 1;       ///< n_far / n_s
        T lift = 0;        ///< added to the row's E_s (detail::dielectric_albedo_beyond_lift above eta_hat 3)
        T e_avg = 1;       ///< E_s,avg
        T tau = 0;         ///< share of the lost energy transmitted from s
        T reflect = 0;     ///< (1 - tau_s) / (pi (1 - E_s,avg)), 1/sr
        T transmit = 0;    ///< tau_s / (eta_s^2 pi (1 - E_far,avg)), 1/sr (radiance mode)
    };

    void prepare() noexcept {
        const T eta = single_.eta();
        // Above the main tables' eta_hat 3, their continuations.
        const bool beyond = glm::max(eta, T(1) / eta) > T(tables::grid.eta_max);
        const detail::dielectric_albedo_grid& grid = beyond ? tables::beyond_grid : tables::grid;
        const float* table = beyond ? tables::e_beyond : tables::e;
        const T alpha_x = tables::alpha_x(single_.distribution()), alpha_y = tables::alpha_y(single_.distribution());
        anisotropic_ = tables::anisotropic && alpha_x != alpha_y;
        // The isotropic table's roughness: the correction's base roughness (the root mean
        // square, bent below 1) under the anisotropic correction, else sqrt(alpha_x alpha_y)
        // (alpha itself when isotropic).
        const T alpha = anisotropic_ ? detail::dielectric_anisotropic_base_alpha(alpha_x, alpha_y) : std::sqrt(alpha_x * alpha_y);
        if constexpr (tables::anisotropic)
            if (anisotropic_) anisotropic_cell_ = detail::dielectric_anisotropic_locate(alpha_x, alpha_y, eta);
        for (std::size_t s = 0; s < 2; ++s) {
            side_[s].eta_s = s == 0 ? eta : T(1) / eta;
            side_[s].cell = detail::dielectric_albedo_locate(grid, alpha, side_[s].eta_s);
            side_[s].row = detail::dielectric_albedo_row<T, detail::dielectric_albedo_mu_nodes>(table, grid, side_[s].cell);
            side_[s].lift = beyond ? T(detail::dielectric_albedo_beyond_lift) : T(0);
            // E_s,avg as detail::dielectric_albedo_average integrates it, read through the row.
            const auto& row = side_[s].row;
            const T lift = side_[s].lift;
            side_[s].e_avg = glm::clamp(
                T(gauss_legendre_integral(
                    [&row, lift](double mu) { return 2 * mu * double(glm::clamp(row.at(T(mu)) + lift, T(0), T(1))); }, 0,
                    1, 8)),
                T(0), T(1));
            // The average of the corrected E_s(w): the isotropic average plus Delta_s,avg.
            if constexpr (tables::anisotropic)
                if (anisotropic_) {
                    const T delta_average =
                        detail::dielectric_anisotropic_delta_average(tables::delta_average, anisotropic_cell_, side_[s].cell.side);
                    side_[s].e_avg = glm::clamp(side_[s].e_avg + delta_average, T(0), T(1));
                    // albedo() clamps E_s + Delta_s to 1, which the sum of averages above does
                    // not: where the interface loses little, the reads above 1 it leaves out
                    // are most of the loss (a nearly smooth anisotropic interface read
                    // E_s,avg = 1 and switched the compensation off, while grazing views read
                    // E_s 0.94). There the average is integrated from the clamped reads.
                    if (!(grid_ != nullptr && grid_->integrated(s == 1)) &&
                        T(1) - side_[s].e_avg < T(detail::dielectric_clamped_average_below))
                        side_[s].e_avg = clamped_average(s);
                }
            if (grid_ != nullptr && grid_->integrated(s == 1)) side_[s].e_avg = grid_->average(s == 1);
        }
        const T loss[2] = {T(1) - side_[0].e_avg, T(1) - side_[1].e_avg};
        if (!(loss[0] > T(detail::dielectric_compensation_min_loss)) ||
            !(loss[1] > T(detail::dielectric_compensation_min_loss))) {
            enabled_ = false;
            return;
        }
        enabled_ = true;
        // The rarer side r (eta_s > 1) transmits 1 - F_avg; the denser side d follows from
        // tau_d (1 - E_d,avg) eta_hat^2 = tau_r (1 - E_r,avg).
        const std::size_t r = eta > T(1) ? 0 : 1;
        const std::size_t d = 1 - r;
        const T eta_hat2 = sqr(side_[r].eta_s);
        T tau_r = T(1) - dielectric_fresnel_average(side_[r].eta_s);
        T tau_d = tau_r * loss[r] / (eta_hat2 * loss[d]);
        if (tau_d > T(1)) {
            tau_d = T(1);
            tau_r = eta_hat2 * loss[d] / loss[r];
        }
        side_[r].tau = tau_r;
        side_[d].tau = tau_d;
        for (std::size_t s = 0; s < 2; ++s) {
            side_[s].reflect = (T(1) - side_[s].tau) * inv_pi<T> / loss[s];
            side_[s].transmit = side_[s].tau * inv_pi<T> / (sqr(side_[s].eta_s) * loss[1 - s]);
        }
    }

    /// f_ss + f_ms (in the given mode) and the mixture density at l, given in the shading
    /// frame as l_local, for a valid view.
    [[nodiscard]] value_and_density evaluate(const vec3<T>& l_local, const prepared_view& view,
                                             transport_mode mode) const noexcept {
        const std::size_t s = view.side;
        const auto single = single_.f_and_pdf_local(l_local, view.v_local);
        value_and_density out{single.f, single.pdf};
        if (!enabled_) return out;
        if (!(l_local.z != T(0)) || !std::isfinite(l_local.z)) return out;
        const bool transmitted = (l_local.z < T(0)) != (view.v_local.z < T(0));
        const bool adjoint = transmitted && mode == transport_mode::importance; // times eta_s^2
        if (adjoint) out.f *= sqr(side_[s].eta_s);
        const T e_v = view.albedo;
        const T loss_v = T(1) - e_v;
        T f_ms = transmitted ? side_[s].transmit * (T(1) - albedo(1 - s, l_local)) * loss_v
                             : side_[s].reflect * (T(1) - albedo(s, l_local)) * loss_v;
        out.f += rgb<T>(adjoint ? f_ms * sqr(side_[s].eta_s) : f_ms);
        out.pdf = e_v * single.pdf + (T(1) - e_v) * multiple_pdf(s, l_local, view.v_local);
        return out;
    }

    /// E_s(w) for the local direction w in medium s (only |w.z| and the azimuth are read):
    /// the grid's read in per-interface mode (on a side the grid integrates); else the
    /// isotropic table, plus Delta_s(w) when
    /// anisotropic, clamped to [0, 1] (near a
    /// smooth interface the tables' noise can carry E_s + Delta_s just past 1, and f_ms >= 0
    /// needs 1 - E_s >= 0).
    [[nodiscard]] T albedo(std::size_t s, const vec3<T>& w) const noexcept {
        if (grid_ != nullptr && grid_->integrated(s == 1)) return grid_->albedo(s == 1, w);
        const T mu = std::abs(w.z);
        T e = side_[s].row.at(mu) + side_[s].lift;
        if constexpr (tables::anisotropic)
            if (anisotropic_) e += detail::dielectric_anisotropic_delta(tables::delta, anisotropic_cell_, side_[s].cell.side, w.x, w.y, mu);
        return glm::clamp(e, T(0), T(1));
    }

    /// The cosine-weighted hemispherical average of albedo(s, w) as it reads, clamp included:
    /// (1 / pi) int E_s(w) |n·w| dw = int_0^1 g'(u) int_0^1 4 x^3 E_s(x, u) dx du, with
    /// x = sqrt(mu) and u the azimuth coordinate of the anisotropic correction (2 phi / pi =
    /// g(u) = u (1 + u) / 2 from the smoother axis, dielectric_anisotropic_u), over one
    /// quadrant (E_s is even in both axes): 2-point Gauss-Legendre on every cell of the
    /// correction's x and u nodes (Abramowitz, Stegun 1964, "Handbook of Mathematical
    /// Functions", 25.4.29), where Delta_s is a cubic in x and linear in u before the clamp.
    /// The reads are albedo()'s, with Delta_s from dielectric_anisotropic_delta_nodes.
    [[nodiscard]] T clamped_average(std::size_t s) const noexcept {
        constexpr std::size_t nx = detail::dielectric_anisotropic_mu_nodes, nu = detail::dielectric_anisotropic_azimuth_nodes;
        constexpr double gauss[2] = {0.5 - 0.28867513459481287, 0.5 + 0.28867513459481287}; // (1 -+ 1/sqrt 3) / 2
        constexpr std::size_t nq = 2 * (nx - 1); // x points
        // Delta_s on the correction's nodes (albedo()'s reads, the blend over the interface's
        // parameters done once), and the isotropic part at each x point (no azimuth).
        double nodes[nu * nx];
        detail::dielectric_anisotropic_delta_nodes(tables::delta, anisotropic_cell_, side_[s].cell.side, nodes);
        double isotropic[nq];
        detail::spline_taps<double> taps[nq];
        double weight[nq];
        for (std::size_t q = 0; q < nq; ++q) {
            const std::size_t k = q / 2;
            const double tx = gauss[q % 2];
            const double x = (double(k) + tx) / double(nx - 1);
            isotropic[q] = double(side_[s].row.at(T(x * x)) + side_[s].lift);
            taps[q] = detail::spline_taps<double>(k, tx, nx);
            // 4 x^3 dx over half the cell (each Gauss node weighs half its cell).
            weight[q] = 0.5 * 4.0 * x * x * x / double(nx - 1);
        }
        double sum = 0;
        for (std::size_t i = 0; i + 1 < nu; ++i)
            for (const double tu : gauss) {
                const double u = (double(i) + tu) / double(nu - 1);
                // g'(u) du over half the cell.
                const double g_prime = 0.5 * 0.5 * (1.0 + 2.0 * u) / double(nu - 1);
                const double* row0 = nodes + i * nx;
                const double* row1 = row0 + nx;
                double row_sum = 0;
                for (std::size_t q = 0; q < nq; ++q) {
                    double d0 = 0, d1 = 0;
                    for (int a = 0; a < 4; ++a) {
                        d0 += taps[q].weight[a] * row0[taps[q].node[a]];
                        d1 += taps[q].weight[a] * row1[taps[q].node[a]];
                    }
                    const double e = glm::clamp(isotropic[q] + d0 + tu * (d1 - d0), 0.0, 1.0);
                    row_sum += weight[q] * e;
                }
                sum += g_prime * row_sum;
            }
        return glm::clamp(T(sum), T(0), T(1));
    }

    /// R_ss for the local view v in medium s (shade::dielectric_reflection_albedo at
    /// sqrt(alpha_x alpha_y)); GGX only, as its callers reflectance and transmittance (0 for
    /// another distribution, whose reflection albedo is not tabulated: the branch keeps the
    /// class explicitly instantiable for it).
    [[nodiscard]] T single_reflectance(std::size_t s, const vec3<T>& v) const noexcept {
        if constexpr (std::same_as<Distribution, ggx<T>>) {
            const Distribution& d = single_.distribution();
            return dielectric_reflection_albedo(unchecked, std::abs(v.z), d.alpha_x(), d.alpha_y(), side_[s].eta_s);
        } else {
            (void)s;
            (void)v;
            return T(0);
        }
    }

    /// The density of the multiple-scattering lobe's sampler at local l for a view in
    /// medium s: (1 - tau_s) |cos| / pi on v's side, tau_s |cos| / pi on the far side.
    [[nodiscard]] T multiple_pdf(std::size_t s, const vec3<T>& l, const vec3<T>& v) const noexcept {
        if (!enabled_ || !std::isfinite(l.z)) return T(0);
        const bool same_side = (l.z > T(0)) == (v.z > T(0));
        return (same_side ? T(1) - side_[s].tau : side_[s].tau) * std::abs(l.z) * inv_pi<T>;
    }

    single_scattering_type single_;
    side_state side_[2]{};
    const rough_dielectric_albedo_grid<T>* grid_ = nullptr; ///< E_s per interface, or nullptr: the tables
    detail::dielectric_anisotropic_cell<T> anisotropic_cell_{}; ///< where Delta is read (when anisotropic)
    bool anisotropic_ = false; ///< alpha_x != alpha_y
    bool enabled_ = false;
};

} // namespace shade
