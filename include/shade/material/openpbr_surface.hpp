#pragma once
// shade::openpbr_surface: OpenPBR Surface 1.1 as one sampled BSDF, the specification's
// reduction of its layers to a mixture of public lobes. Not in the umbrella header:
// include it directly.
//
//   shade::openpbr_parameters<float> p;          // the specification's defaults
//   p.base_color = {0.9f, 0.6f, 0.2f};
//   p.coat_weight = 1.0f;
//   const shade::openpbr_surface<float> paint(p);
//   const auto s = shade::sample_bsdf(paint, v, uc, u, at, shade::transport_mode::radiance);

#include <array>
#include <atomic>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <limits>
#include <optional>
#include <type_traits>
#include <utility>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <shade/brdf/anisotropic_multiple_scattering.hpp>
#include <shade/brdf/detail/directions.hpp>
#include <shade/brdf/eon.hpp>
#include <shade/brdf/f82_tint.hpp>
#include <shade/brdf/fresnel.hpp>
#include <shade/brdf/microfacet/cosine_weights.hpp>
#include <shade/brdf/microfacet/detail/thin_film_margin_data.hpp>
#include <shade/brdf/microfacet/ggx.hpp>
#include <shade/brdf/microfacet/masking.hpp>
#include <shade/brdf/microfacet_reflection.hpp>
#include <shade/brdf/sheen.hpp>
#include <shade/brdf/thin_film.hpp>
#include <shade/bsdf/bsdf.hpp>
#include <shade/bsdf/compensated_rough_dielectric.hpp>
#include <shade/bsdf/dielectric_albedo_table.hpp>
#include <shade/bsdf/detail/delta.hpp>
#include <shade/bsdf/detail/dielectric_albedo_row.hpp>
#include <shade/bsdf/detail/lobe_pair.hpp>
#include <shade/bsdf/rough_dielectric_albedo_grid.hpp>
#include <shade/bsdf/dielectric_anisotropic_reflection_albedo.hpp>
#include <shade/bsdf/dielectric_reflection_albedo.hpp>
#include <shade/bsdf/layer.hpp>
#include <shade/bsdf/refract.hpp>
#include <shade/bsdf/smooth_dielectric.hpp>
#include <shade/core/math.hpp>
#include <shade/core/scalar.hpp>
#include <shade/core/surface_point.hpp>
#include <shade/core/types.hpp>
#include <shade/material/openpbr_parameters.hpp>

namespace shade {

namespace detail {

/// A shade::rough_dielectric_albedo_grid on the heap, shared by the copies of the material
/// that built it (reference counted; the grid is immutable, so copies may be used and
/// destroyed on any threads). The grid stays at one address for as long as any copy holds
/// it, so a compensated_rough_dielectric copied along with the material still points to it.
template <std::floating_point T>
class shared_rough_dielectric_albedo_grid {
public:
    shared_rough_dielectric_albedo_grid() noexcept = default;
    /// The grid of rough_dielectric(distribution, eta) (as rough_dielectric_albedo_grid's
    /// constructor, whose exceptions it passes on).
    shared_rough_dielectric_albedo_grid(const ggx<T>& distribution, T eta)
        : block_(new block{rough_dielectric_albedo_grid<T>(distribution, eta)}) {}
    /// The grid of one side only (rough_dielectric_albedo_grid's one-sided constructor).
    shared_rough_dielectric_albedo_grid(const ggx<T>& distribution, T eta, bool inside, const dielectric_side_grid<T>& side)
        : block_(new block{rough_dielectric_albedo_grid<T>(distribution, eta, inside, side)}) {}
    shared_rough_dielectric_albedo_grid(const shared_rough_dielectric_albedo_grid& other) noexcept : block_(other.block_) {
        if (block_ != nullptr) block_->count.fetch_add(1, std::memory_order_relaxed);
    }
    shared_rough_dielectric_albedo_grid(shared_rough_dielectric_albedo_grid&& other) noexcept
        : block_(std::exchange(other.block_, nullptr)) {}
    shared_rough_dielectric_albedo_grid& operator=(shared_rough_dielectric_albedo_grid other) noexcept {
        std::swap(block_, other.block_);
        return *this;
    }
    ~shared_rough_dielectric_albedo_grid() {
        if (block_ != nullptr && block_->count.fetch_sub(1, std::memory_order_acq_rel) == 1) delete block_;
    }
    /// The grid, or nullptr when none was built.
    [[nodiscard]] const rough_dielectric_albedo_grid<T>* get() const noexcept { return block_ ? &block_->grid : nullptr; }

private:
    struct block {
        rough_dielectric_albedo_grid<T> grid;
        std::atomic<long> count{1};
    };
    block* block_ = nullptr;
};

} // namespace detail

namespace openpbr {

/// The smallest GGX alpha of a rough lobe of openpbr_surface (shade::ggx's own lower
/// bound): a lobe whose alpha along the tangent, alpha_t >= alpha_b, is below it is a delta
/// lobe (a mirror or a straight refraction), evaluated exactly.
template <std::floating_point T>
inline constexpr T smallest_alpha = T(1e-4);

/// Gulbrandsen 2014, "Artist Friendly Metallic Fresnel", JCGT 3(4), eqs. 9-10 (the
/// inverse mapping): the complex index n + i k of a conductor whose normal-incidence
/// reflectance is r and whose edge tint is g, per channel,
///
///     n = g (1 - r) / (1 + r) + (1 - g) (1 + sqrt(r)) / (1 - sqrt(r))
///     k^2 = (r (n + 1)^2 - (n - 1)^2) / (1 - r)
///
/// with r clamped to [0, 0.9999] (r = 1 is an infinite index) and g to [0, 1]. openpbr_surface
/// uses it to put a thin film over its F82 metal, which has no complex index of its own.
template <std::floating_point T>
struct conductor_index {
    rgb<T> eta;   ///< n per channel
    rgb<T> kappa; ///< k per channel
};

/// See conductor_index.
template <std::floating_point T>
[[nodiscard]] inline conductor_index<T> gulbrandsen_index(const rgb<T>& reflectance, const rgb<T>& edge_tint) noexcept {
    conductor_index<T> out{rgb<T>(1), rgb<T>(0)};
    for (int c = 0; c < 3; ++c) {
        const T r = glm::clamp(reflectance[c], T(0), T(0.9999));
        const T g = glm::clamp(edge_tint[c], T(0), T(1));
        const T sr = std::sqrt(r);
        const T n = g * (T(1) - r) / (T(1) + r) + (T(1) - g) * (T(1) + sr) / (T(1) - sr);
        const T k2 = (r * sqr(n + T(1)) - sqr(n - T(1))) / (T(1) - r);
        out.eta[c] = glm::clamp(n, T(1e-4), T(1e4));
        out.kappa[c] = std::sqrt(glm::clamp(k2, T(0), T(1e8)));
    }
    return out;
}

/// The Fresnel term of openpbr_surface's dielectric reflection lobe and of its metal
/// (shade::fresnel_term), per channel in [0, 1]:
///
///     F(mu) = tint (lerp(F_base(mu), F_film(mu), w))
///
/// F_base the exact dielectric reflectance at the modulated index eta'_s (section
/// "Dielectric base", equation modulated_ior), tint specular_color; or, for the metal, the
/// F82-tint reflectance times specular_weight (section "Metal"; shade::F_f82_tint) with
/// tint 1. F_film the thin film's reflectance (shade::thin_film_fresnel, section "Thin
/// film": the film over the base dielectric, or over the conductor of gulbrandsen_index)
/// and w thin_film_weight (section "Thin film": the film's Fresnel replaces the base's in
/// proportion to its coverage).
template <std::floating_point T>
class surface_fresnel {
public:
    using scalar_type = T;

    /// The dielectric's: index ratio eta (> 0), tint in [0, 1]^3, and a film of weight
    /// film_weight in [0, 1] (film unused when 0). The caller guarantees the ranges.
    [[nodiscard]] static surface_fresnel dielectric(T eta, const rgb<T>& tint, T film_weight,
                                                    const thin_film_fresnel<T>& film) noexcept {
        surface_fresnel s(film);
        s.eta_ = eta;
        s.tint_ = tint;
        s.film_weight_ = film_weight;
        return s;
    }

    /// The metal's: F82-tint with f0, edge tint and weight in [0, 1], and a film as above.
    [[nodiscard]] static surface_fresnel metal(const f82_tint<T>& f82, T film_weight,
                                               const thin_film_fresnel<T>& film) noexcept {
        surface_fresnel s(film);
        s.metal_ = true;
        s.f82_ = f82;
        s.film_weight_ = film_weight;
        return s;
    }

    /// F(cos_theta) per channel, dimensionless, in [0, 1]; |cos_theta| is used.
    [[nodiscard]] rgb<T> F(T cos_theta) const noexcept {
        const T c = std::abs(cos_theta);
        rgb<T> base = metal_ ? f82_.F(c) : rgb<T>(F_dielectric(c, eta_));
        if (film_weight_ > T(0)) base = glm::mix(base, film_.F(c), film_weight_);
        return metal_ ? base : tint_ * base;
    }

    [[nodiscard]] constexpr bool is_metal() const noexcept { return metal_; }    ///< the metal's term
    [[nodiscard]] constexpr T eta() const noexcept { return eta_; }              ///< eta'_s (dielectric)
    [[nodiscard]] constexpr const rgb<T>& tint() const noexcept { return tint_; } ///< specular_color (dielectric)
    [[nodiscard]] constexpr T film_weight() const noexcept { return film_weight_; } ///< thin_film_weight

private:
    explicit surface_fresnel(const thin_film_fresnel<T>& film) noexcept
        : film_(film), f82_(unchecked, rgb<T>(0), rgb<T>(1), T(1)) {}

    thin_film_fresnel<T> film_;
    f82_tint<T> f82_;
    rgb<T> tint_{1};
    T eta_ = T(1.5);
    T film_weight_ = T(0);
    bool metal_ = false;
};

/// Where openpbr_surface's anisotropic transmission lobe (compensated_rough_dielectric)
/// reads the single-scattering albedo E_s(w) of its interface.
enum class interface_albedo {
    /// The tables (the isotropic table plus its anisotropic correction): nothing more to
    /// build. Below an index ratio of 1 (specular_ior < 1), seen from outside, the denser
    /// side, where the tables' correction errs most, E_s is read instead from a grid of that
    /// side filled in the same pass as its R_ss (which such a material integrates anyway:
    /// 90 to 220 ms in all at -O2, rather than 70 to 140 ms for R_ss alone); the views from
    /// inside read the tables. Near index match (specular_ior within a factor 1.05 of 1, not
    /// index-matched) the whole grid serves instead, the tables holding nothing there.
    tables,
    /// A shade::rough_dielectric_albedo_grid of the interface, built with the material
    /// (0.3 to 0.6 s, shared by the material's copies): R + T in [0.99, 1.001] at 2:1, 10:1
    /// and anisotropy 1 from both sides. For materials built once, not per shading point.
    grid,
};

} // namespace openpbr

/// OpenPBR Surface 1.1 (Andersson, Edmondson, Guertault, Hill, Kutz, Portsmouth, Pharr,
/// et al. 2024, "OpenPBR Surface Specification", Academy Software Foundation, v1.1) as a
/// shade::sampled_bsdf: the specification's section "Reduction to a mixture of lobes",
/// whose layers (fuzz over coat over a base substrate) are combined by albedo scaling,
/// written as a weighted sum of public lobes:
///
///     f = alpha f_surface + (1 - alpha) f_transparent                      (opacity)
///     f_surface = F f_fuzz + (1 - F E_fuzz(v)) f_coated                    (fuzz)
///     f_coated  = C f_coat + lerp(1, T_coat (1 - E_coat(v)), C) D f_base  (coat)
///     f_base    = M f_metal + (1 - M) (f_spec + (1 - E_spec(v)) f_T)       (metal, dielectric base)
///     f_T       = T f_transmission + (1 - T) (S f_subsurface + (1 - S) f_diffuse)
///
/// alpha geometry_opacity, F fuzz_weight, C coat_weight, M base_metalness, T
/// transmission_weight, S subsurface_weight; E_X(v) the directional albedo of lobe X at the
/// view (white, for the fuzz); T_coat the coat's absorption along the two refracted paths
/// (openpbr::coat_absorption) and D its darkening (openpbr::coat_darkening_factor). The
/// lobes, each a public model:
///
///   * f_fuzz: shade::zeltner_sheen (fuzz_color, fuzz_roughness); E_fuzz its albedo table.
///   * f_coat: shade::microfacet_reflection over anisotropic GGX with the exact dielectric
///     Fresnel of coat_ior (coat_roughness, coat_roughness_anisotropy; openpbr::
///     roughness_to_alpha); E_coat = shade::dielectric_reflection_albedo (anisotropic: its
///     form at the view's azimuth; isotropic below an index ratio of 1 as E_spec reads
///     R_ss there, below).
///   * f_metal: microfacet_reflection with the F82-tint Fresnel (base_weight base_color,
///     specular_color, specular_weight clamped to 1 so the metal creates no energy) and
///     Kulla-Conty compensation at every azimuth (shade::kulla_conty_anisotropic), so a white
///     metal reflects everything; roughness specular_roughness widened by the coat
///     (openpbr::coat_roughened).
///   * f_spec: microfacet_reflection with openpbr::surface_fresnel (specular_color times the
///     exact Fresnel of the modulated index eta'_s, openpbr::modulated_ior_ratio of
///     openpbr::specular_ior_ratio; with a thin film); E_spec its albedo:
///     specular_color times dielectric_reflection_albedo at eta'_s (anisotropic: at the
///     view's azimuth, from detail::anisotropic_reflection_albedo_grid, which integrates
///     R_ss for the interface when the material is built below a ratio of 1, above it at
///     strong anisotropy, and its correction above 3; isotropic below 1: the table raised
///     by a margin, and for a narrow lobe integrated on a window of views around the
///     critical cosine, detail::kink_view_window) plus, with a film,
///     thin_film_weight times the integral of F_film - F (F the exact dielectric Fresnel at
///     eta'_s) against the lobe's measure of c = v·h (shade/brdf/microfacet/cosine_weights.hpp,
///     summed once per material), raised by the node sum's largest shortfall over the
///     specification's films (detail/thin_film_margin_data.hpp), so that it reads high,
///     never low; for eta'_s < 1, whose F has a total-reflection kink finer than the
///     nodes, F_film's integral minus R_ss; over a base of specular_ior < 1 a narrow lobe
///     reads the integral around the film's own kink from a window of views as well. An
///     anisotropic lobe with a film
///     integrates its R_ss per interface and the film's part in the same pass instead: the
///     integral of F_film - F against the same visible normals at the same view nodes
///     (detail::anisotropic_reflection_albedo_grid with the film's Fresnel term,
///     difference()).
///   * f_transmission: the transmitted part of shade::compensated_rough_dielectric at the
///     index specular_ior (anisotropic with openpbr::interface_albedo::grid: in its
///     per-interface mode, a shade::rough_dielectric_albedo_grid built with the material,
///     shared by its copies; anisotropic below 1 in the tables mode: a grid of the outside
///     alone, openpbr::interface_albedo), divided by its transmittance from v, so that it carries all
///     the energy the specular reflection leaves (the specification's "the transmission
///     Fresnel factor can be omitted"), tinted by transmission_color when
///     transmission_depth = 0 (otherwise the colour belongs to the interior medium,
///     interior()). Below an index ratio of 1 (specular_ior < 1) the lobe also carries the
///     interface's multiple-scattering reflection (compensated_rough_dielectric::
///     multiple_scattering_reflection, untinted) and is divided by that part's albedo
///     as well, 1 - R_ss(v) in all: there most views lie in the cone of total reflection,
///     where the transmittance alone is a small difference of two tables whose inverse
///     would amplify their error. For an anisotropic interface that R_ss (as E_spec's) is
///     integrated for the interface when the material is built
///     (detail::anisotropic_reflection_albedo_grid below 1), and under a thin film, where
///     E_spec is the film's share and no longer cancels R_ss's error, read without its
///     margin.
///   * f_diffuse: shade::eon (base_weight base_color, base_diffuse_roughness).
///   * f_subsurface: shade::eon (subsurface_color, base_diffuse_roughness): the surface
///     part of subsurface scattering as a diffuse lobe; the interior is reported by
///     interior() (openpbr::subsurface_medium) for a renderer's volume integrator.
///
/// Roughness 0 (alpha below openpbr::smallest_alpha): the coat, metal, specular reflection
/// and transmission become delta lobes (exact mirrors and refractions; no clamped lobe).
/// geometry_opacity < 1 adds a delta pass-through.
///
/// Thin-walled (geometry_thin_walled): both sides look the same (a view from below is
/// answered as the mirror image of one from above, the specification's "the surface always
/// flipped so that incident rays enter top-down"); the transmission lobe is the
/// straight-through lobe of a thin sheet: the Kulla-Conty-compensated GGX mirror lobe with
/// F = 1, mirrored through the surface (albedo 1 at every view, so the sheet reflects
/// E_spec and transmits the rest: no energy lost or created at any roughness), or a delta
/// straight through at roughness 0; subsurface becomes diffuse reflection and transmission
/// S (1 -+ g) / 2 (equation thin_wall_subsurface), g subsurface_scatter_anisotropy.
///
/// Seen from inside (not thin-walled, v below the surface): the bare interface,
/// compensated_rough_dielectric (or shade::smooth_dielectric at roughness 0) at
/// specular_ior, when the material transmits at all ((1 - M) T > 0), times alpha; the
/// coat, fuzz and opaque base are not seen from inside (the specification's section
/// "Entering versus exiting" allows this).
///
/// Energy: the white furnace of the specification's section "White furnace testing"
/// holds by construction wherever E_X is the lobe's exact albedo (each layer passes on
/// exactly what its top reflects); what remains is the accuracy of the albedo tables (the
/// thin film's share included: cosine_weights.hpp). Reciprocal: no (albedo scaling depends on v; the
/// specification's choice); f in importance mode is the adjoint f(v, l) (shade/bsdf/bsdf.hpp).
///
/// Sampling: one lobe chosen with probability proportional to its share of the energy at
/// the view (its weight times its albedo, largest channel), then the lobe's own sampler;
/// pdf is the mixture density of the non-delta lobes, weight f |n·l| / pdf with the whole
/// f. A delta sample (pbrt-v4's convention) has pdf the lobe's probability and weight its
/// throughput over that probability.
template <std::floating_point T>
class openpbr_surface {
public:
    using scalar_type = T;
    using fuzz_lobe = zeltner_sheen<T>;
    using coat_lobe = microfacet_reflection<ggx<T>, dielectric_fresnel<T>, smith_height_correlated<T>>;
    using specular_lobe = microfacet_reflection<ggx<T>, openpbr::surface_fresnel<T>, smith_height_correlated<T>>;
    using metal_lobe = microfacet_reflection<ggx<T>, openpbr::surface_fresnel<T>, smith_height_correlated<T>,
                                             cook_torrance_form::walter, kulla_conty_anisotropic>;
    using transmission_lobe = compensated_rough_dielectric<T>;
    using sheet_lobe = microfacet_reflection<ggx<T>, schlick<T>, smith_height_correlated<T>,
                                             cook_torrance_form::walter, kulla_conty_anisotropic>;
    using diffuse_lobe = eon<T>;

    /// The lobes of the mixture, in the order of the class comment.
    enum class lobe : std::size_t {
        fuzz,
        coat,
        metal,
        specular,
        transmission,
        diffuse,
        subsurface_reflection,
        subsurface_transmission,
        transparent,
        count
    };

    /// Builds the material. Throws shade::invalid_parameter naming the first parameter
    /// outside the specification's range (openpbr_parameters::validate). `albedo` says where
    /// an anisotropic transmission lobe reads E_s (openpbr::interface_albedo; isotropic
    /// lobes always read the tables, which hold the band there).
    explicit openpbr_surface(const openpbr_parameters<T>& parameters, layering form = layering::albedo_scaling,
                             openpbr::interface_albedo albedo = openpbr::interface_albedo::tables)
        : p_(parameters), form_(form), albedo_(albedo) {
        p_.validate();
        build();
    }

    [[nodiscard]] constexpr const openpbr_parameters<T>& parameters() const noexcept { return p_; } ///< as given
    [[nodiscard]] constexpr bool thin_walled() const noexcept { return p_.geometry_thin_walled; } ///< a thin shell
    [[nodiscard]] constexpr layering form() const noexcept { return form_; } ///< how the layers are combined
    /// Where an anisotropic transmission lobe reads E_s (as given).
    [[nodiscard]] constexpr openpbr::interface_albedo albedo_source() const noexcept { return albedo_; }

    /// The medium inside the surface for a renderer's volume integrator: the translucent
    /// base's (openpbr::transmission_medium) when transmission_weight > 0, otherwise the
    /// subsurface's (openpbr::subsurface_medium) when subsurface_weight > 0; none
    /// (present false) for a thin-walled or opaque material.
    [[nodiscard]] openpbr::homogeneous_medium<T> interior() const noexcept {
        if (p_.geometry_thin_walled) return {};
        if (p_.transmission_weight > T(0)) return openpbr::transmission_medium(p_);
        if (p_.subsurface_weight > T(0)) return openpbr::subsurface_medium(p_);
        return {};
    }

    /// The base dielectric's index of refraction at the wavelength lambda_nm (nanometres),
    /// section "Dispersion": openpbr::dispersed_ior of specular_ior with the Abbe number
    /// openpbr::abbe_number (specular_ior itself when transmission_dispersion_scale is 0).
    /// For a spectral renderer that traces one wavelength per path; the RGB model above
    /// refracts with specular_ior.
    [[nodiscard]] T specular_ior_at(T lambda_nm) const noexcept {
        return openpbr::dispersed_ior(p_.specular_ior, openpbr::abbe_number(p_), lambda_nm);
    }

    /// Emitted radiance toward v in nits (cd/m^2) per channel: emission_luminance
    /// emission_color from the base, passed through the coat and the fuzz as their layers
    /// pass light from below (section "Emission": lerp(1, T_coat (1 - E_coat(v)), C) with
    /// T_coat the coat's one-way transmittance coat_color^(1 / (2 mu_t)), mu_t the refracted
    /// cosine, and 1 - F E_fuzz(v)), times geometry_opacity. 0 from below unless
    /// thin-walled.
    [[nodiscard]] rgb<T> emission(const vec3<T>& v, const surface_point<T>& at) const noexcept {
        if (!(p_.emission_luminance > T(0))) return rgb<T>(0);
        T mu = glm::dot(at.n(), v);
        if (p_.geometry_thin_walled) mu = std::abs(mu);
        if (!(mu > T(0))) return rgb<T>(0);
        mu = glm::min(mu, T(1));
        // The layers' factor (each in [0, 1]) first and the luminance last, so that a
        // luminance times colour beyond the largest T gives inf, never inf x 0 = NaN.
        rgb<T> passed(p_.geometry_opacity);
        if (p_.coat_weight > T(0)) {
            const rgb<T> one_way = glm::sqrt(openpbr::coat_absorption(p_.coat_color, mu, mu, coat_eta_));
            passed *= glm::mix(rgb<T>(1), one_way * (T(1) - coat_albedo(mu)), p_.coat_weight);
        }
        passed *= T(1) - p_.fuzz_weight * fuzz_albedo(mu);
        return (passed * p_.emission_color) * p_.emission_luminance;
    }

    /// BSDF value in 1/sr without the cosine, radiance mode, for l and v on either side
    /// (class comment); delta lobes add nothing.
    [[nodiscard]] rgb<T> f(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const noexcept {
        const oriented o = orient(v, at);
        if (!o.valid) return rgb<T>(0);
        if (o.inside) return p_.geometry_opacity * inside_f(l, v, o.at);
        const view w = view_at(v, o.at, false);
        return p_.geometry_opacity * surface_eval<true, false>(l, v, o.at, w).f;
    }

    /// The density (1/sr) with which sample() draws l for v: the mixture of the non-delta
    /// lobes' densities.
    [[nodiscard]] T pdf(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const noexcept {
        const oriented o = orient(v, at);
        if (!o.valid) return T(0);
        if (o.inside) return inside_pdf(l, v, o.at);
        const view w = view_at(v, o.at);
        return surface_eval<false, true>(l, v, o.at, w).pdf;
    }

    /// The probability with which sample() chooses lobe k for the view v (dimensionless;
    /// the probabilities of all lobes sum to 1, or are all 0 for a black material).
    [[nodiscard]] T lobe_probability(lobe k, const vec3<T>& v, const surface_point<T>& at) const noexcept {
        const oriented o = orient(v, at);
        if (!o.valid) return T(0);
        if (o.inside) {
            if (k == lobe::transparent) return inside_probability(true);
            return k == lobe::transmission ? inside_probability(false) : T(0);
        }
        return view_at(v, o.at).p[std::size_t(k)];
    }

    /// Draws l for v in the given mode (class comment). nullopt when v lies on the surface,
    /// the material is black from v, or the chosen lobe draws nothing.
    [[nodiscard]] std::optional<bsdf_sample<T>> sample(const vec3<T>& v, T uc, const vec2<T>& u,
                                                       const surface_point<T>& at,
                                                       transport_mode mode = transport_mode::radiance) const {
        const oriented o = orient(v, at);
        if (!o.valid) return std::nullopt;
        if (o.inside) return inside_sample(v, uc, u, o, mode);
        const view w = view_at(v, o.at);
        // The lobe: the first whose cumulative probability exceeds uc; uc rescaled within it.
        std::size_t k = 0;
        T start = T(0);
        for (; k < lobe_count; ++k) {
            if (w.p[k] > T(0) && uc < start + w.p[k]) break;
            start += w.p[k];
        }
        if (k == lobe_count) {
            // uc at the very top (rounding): the last lobe with a probability.
            for (k = lobe_count; k-- > 0;)
                if (w.p[k] > T(0)) break;
            if (k == std::size_t(-1)) return std::nullopt;
            start -= w.p[k];
        }
        const T uc_lobe = glm::max(T(0), detail::remap_lobe_choice(uc - start, w.p[k], true));
        return sample_lobe(lobe(k), v, uc_lobe, u, o, w, mode);
    }

private:
    static constexpr std::size_t lobe_count = std::size_t(lobe::count);

    // The surface point the material is evaluated at: flipped for a thin-walled view from
    // below; inside for a solid seen from below.
    struct oriented {
        surface_point<T> at;
        bool valid = false;
        bool inside = false;
        bool flipped = false;
    };

    // What the mixture's weights need at the view v (above the surface of `at`).
    struct view {
        T mu = 0;                          // n·v, in (0, 1]
        vec3<T> v_local{0, 0, 1};          // v in the shading frame
        T fuzz_keep = 1;                   // 1 - F E_fuzz(mu)
        T coat_albedo = 0;                 // E_coat(mu)
        rgb<T> darkening{1};               // D, per channel
        rgb<T> specular_albedo{0};         // E_spec(v), per channel
        T transmittance = 1;               // the albedo the transmission lobe is divided by
        T interface_reflection = 0;        // share of the interface's R_ss in it (interface_draws_)
        typename transmission_lobe::prepared_view transmission_view{}; // when transmission_ and T > 0
        typename diffuse_lobe::prepared_view diffuse_view{}; // with the probabilities, when p[diffuse] > 0
        std::array<T, lobe_count> p{};     // lobe probabilities
    };

    [[nodiscard]] oriented orient(const vec3<T>& v, const surface_point<T>& at) const noexcept {
        oriented o{at};
        const T n_dot_v = glm::dot(at.n(), v);
        if (!(n_dot_v != T(0)) || !std::isfinite(n_dot_v)) return o;
        o.valid = true;
        if (n_dot_v < T(0)) {
            if (p_.geometry_thin_walled) {
                o.at.shading.n = -at.shading.n;
                o.at.shading.b = -at.shading.b;
                o.flipped = true;
            } else {
                o.inside = true;
            }
        }
        return o;
    }

    // E_fuzz(mu): the fuzz lobe's directional albedo (white); 0 without fuzz.
    [[nodiscard]] T fuzz_albedo(T mu) const noexcept {
        if (fuzz_) return fuzz_->albedo(mu);
        if (fuzz_reciprocal_) return fuzz_reciprocal_->albedo(mu);
        return T(0);
    }

    // The reciprocal form's factor under the coat for the light l (cosine mu_l, local
    // direction l_local) and the view w (per channel):
    // (1 - C E_coat(l)) (1 - C E_coat(v)) / (1 - C E_coat,avg) lerp(1, T_coat, C)
    // sqrt(D(l) D(v)); E_coat read alike at l and v (anisotropic: at each one's azimuth), so
    // that the factor is symmetric in l and v.
    [[nodiscard]] rgb<T> reciprocal_under_coat(T mu_l, const vec3<T>& l_local, const view& w) const noexcept {
        const T C = p_.coat_weight;
        if (C == T(0)) return rgb<T>(1);
        const rgb<T> absorbed = coat_absorbed(mu_l, w.mu);
        const rgb<T> darkening_l = openpbr::coat_darkening_factor(
            base_albedo_, coat_eta_, coat_rough_reflection_, mu_l, base_roughness_estimate_, C, p_.coat_darkening);
        const T keep = (T(1) - C * coat_albedo(mu_l, l_local)) * (T(1) - C * w.coat_albedo) * coat_loss_inverse_;
        return keep * glm::mix(rgb<T>(1), absorbed, C) * glm::sqrt(darkening_l * w.darkening);
    }

    // E_coat(mu): the coat's directional albedo (white).
    [[nodiscard]] T coat_albedo(T mu, const vec3<T>& w_local = vec3<T>(0)) const noexcept {
        if (coat_ && coat_anisotropic_ && w_local != vec3<T>(0))
            return coat_albedo_anisotropic_.at(w_local);
        if (coat_) return reflection_read(coat_albedo_.at(mu), coat_window_, coat_row_margin_, mu);
        return F_dielectric(mu, coat_eta_);
    }

    // The film's margin (thin_film_margin_data.hpp) at alpha row j and view node i: the
    // larger of the tables of the film indices around thin_film_ior.
    [[nodiscard]] double film_node_margin(std::size_t j, std::size_t i) const noexcept {
        constexpr std::size_t rows = detail::cosine_weight_alpha_nodes, n = detail::cosine_weight_nodes;
        float largest = 0;
        for (std::size_t f = film_margin_first_; f <= film_margin_last_; ++f)
            largest = glm::max(largest, detail::thin_film_albedo_margin[((f * 2 + film_margin_table_) * rows + j) * n + i]);
        return double(largest);
    }

    // The margin film_albedo_ is raised by at each view node: the smaller of two estimates of
    // what the node sums miss at the specular lobe's roughness. One is the film margin's
    // table (film_node_margin, the largest shortfall over every film of the index, as thick
    // as 10 um). The other is this film's own: the sums integrate F_film - F (film_nodes_)
    // read linearly between the nodes, so they fall short of the integral by at most the
    // lobe's mass on each interval between two nodes times the largest amount e_k by which
    // F_film - F rises above that line inside it (its largest channel); the mass on interval
    // k is at most w_k + w_k+1, so sum_k w_k (e_k-1 + e_k), a node sum of g_k = e_k-1 + e_k
    // with the same weights, bounds it. e_k comes from the curvature: where F'' is about
    // constant over an interval of width h (in x = c^(2/3), as the nodes are uniform), F
    // rises above the line by at most -F'' h^2 / 8 = -(second difference) / 8; e_k is 1.5
    // times the larger of the two nodes' (clamped at 0). For the film's fringes, F ~ cos of
    // the phase 2 pi OPD / lambda (OPD = 2 d sqrt(n_f^2 - 1 + c^2), lambda >= 380 nm), the
    // second difference gives the peak within 10 % while the phase turns by at most 1.2
    // radians over an interval (its width in c is at most 1.5 / 63; so up to d = 1.5 um):
    // a thicker film, or one alone over an index ratio below 1 (whose F_film has the
    // total-reflection kink), keeps the table's margin. To the estimate are added, for the
    // weights' own error (their quadrature and their interpolation in alpha and mu), the
    // table's margin of a smooth F (film index 1, table 1: a Fresnel factor without a film,
    // read by the same weights) and film_weights_allowance, for a film's F_film - F, which
    // varies more than a Fresnel factor alone.
    [[nodiscard]] std::array<double, detail::cosine_weight_nodes> film_row_margin(T thickness_nm) const {
        constexpr std::size_t n = detail::cosine_weight_nodes, rows = detail::cosine_weight_alpha_nodes;
        const double s = std::sqrt(glm::clamp(double(specular_alpha_), 0.0, 1.0)) * double(rows - 1);
        const std::size_t j = glm::min(std::size_t(s), rows - 2);
        const double t = s - double(j);
        std::array<double, n> margin{};
        for (std::size_t i = 0; i < n; ++i) margin[i] = (1 - t) * film_node_margin(j, i) + t * film_node_margin(j + 1, i);
        const double turn = 4 * pi<double> * double(thickness_nm) / 380.0 * (1.5 / double(n - 1));
        if (!(turn <= 1.2) || film_alone_) return margin;
        std::array<double, n> bend{}; // -(second difference) / 8 at each node, at least 0
        for (std::size_t k = 1; k + 1 < n; ++k) {
            const rgb<T> d2 = film_nodes_[k + 1] - T(2) * film_nodes_[k] + film_nodes_[k - 1];
            bend[k] = glm::max(0.0, -double(glm::min(d2.x, glm::min(d2.y, d2.z)))) / 8;
        }
        bend[0] = bend[1];
        bend[n - 1] = bend[n - 2];
        std::array<double, n - 1> excess{};
        for (std::size_t k = 0; k + 1 < n; ++k) excess[k] = 1.5 * glm::max(bend[k], bend[k + 1]);
        std::array<rgb<T>, n> g{};
        for (std::size_t k = 0; k < n; ++k)
            g[k] = rgb<T>(T((k > 0 ? excess[k - 1] : 0.0) + (k + 1 < n ? excess[k] : 0.0)));
        const detail::fresnel_albedo_row<T> bound(specular_alpha_, g);
        constexpr std::size_t smooth = (0 * 2 + 1) * rows; // film index 1 (the grid's first), table 1
        for (std::size_t i = 0; i < n; ++i) {
            const double weights_error = (1 - t) * double(detail::thin_film_albedo_margin[(smooth + j) * n + i]) +
                                         t * double(detail::thin_film_albedo_margin[(smooth + j + 1) * n + i]);
            margin[i] = glm::min(margin[i], weights_error + film_weights_allowance +
                                                double(bound.at(T(detail::cosine_weight_node(i))).x));
        }
        return margin;
    }

    // The film's share D(v) per channel at the local view w where it is integrated with R_ss
    // (film_on_grid_).
    [[nodiscard]] rgb<T> film_grid_difference(const vec3<T>& w) const noexcept {
        const std::array<T, 3> d = specular_albedo_anisotropic_.differences_against_at(w);
        return rgb<T>(d[0], d[1], d[2]);
    }

    // Whether the transmission lobe of an anisotropic interface reads R_ss without its grid's
    // margin at the local view w: where E_spec is not that interface's R_ss (another index,
    // or a film whose share is not on the same grid), and with the film's share on the grid
    // in the window around the critical cosine, where 1 - R_ss is small and a high read of
    // R_ss, divided into 1 - R_true, scales the lobe up most (elsewhere the grid's margin
    // in R_ss offsets the share's margins, which read E_spec high).
    [[nodiscard]] bool anisotropic_reflection_without_margin(const vec3<T>& w) const noexcept {
        if (!transmission_reflection_shared_) return true;
        if (!film_dielectric_) return false;
        return !film_on_grid_ || transmission_reflection_anisotropic_.windowed_at(w);
    }

    // R_ss of an isotropic rough interface at view cosine mu from its row's value there:
    // below an index ratio of 1 (margin > 0) raised by that margin, and for a narrow lobe
    // read from its window around the critical cosine instead (below_one_reflection).
    [[nodiscard]] static T reflection_read(T row_value, const detail::kink_view_window<T>& window, T margin,
                                           T mu) noexcept {
        if (window.contains(mu)) return glm::min(window.at(mu).x, T(1));
        return glm::min(row_value + margin, T(1));
    }

    // What reflection_read needs of an isotropic interface of roughness alpha and index
    // ratio eta: below 1 the margin below_one_margin and, for alpha up to
    // film_window_alpha_max, a kink_view_window of F(c, eta) itself within
    // below_one_window_reach row cells of the critical cosine (the film's quadrature and
    // margin). The reflection row (the dielectric reflection table's 33 view nodes) reads
    // R_ss low there: by up to 3.3e-3 at grazing views (roughness 0.1-0.2) and, within a
    // few table cells of the critical cosine, by up to 7.6e-2 for narrow lobes (eta 0.3,
    // roughness 0.05), where an opaque material's white furnace reads 1 + true - read.
    static void below_one_reflection(T alpha, T eta, detail::kink_view_window<T>& window, T& margin) {
        if (!(eta < T(1))) return;
        margin = T(below_one_margin);
        if (!(alpha <= T(film_window_alpha_max))) return;
        window = dielectric_window(alpha, eta, below_one_window_reach);
    }

    // The kink_view_window of F(c, eta) (eta < 1) for an isotropic interface of roughness
    // alpha around its critical cosine, within `reach` row cells of it (the film's
    // quadrature and margin).
    [[nodiscard]] static detail::kink_view_window<T> dielectric_window(T alpha, T eta, std::size_t reach) {
        const double e = double(eta);
        return detail::kink_view_window<T>(
            double(alpha), [e](double c) { return rgb<double>(F_dielectric(c, e)); }, std::sqrt((1.0 - e) * (1.0 + e)),
            reach, film_window_strata, film_window_margin);
    }

    // R_ss of the isotropic specular lobe's interface at view cosine mu (reflection_read).
    [[nodiscard]] T specular_reflection_at(T mu) const noexcept {
        return reflection_read(specular_albedo_.at(mu), specular_window_, specular_row_margin_, mu);
    }

    // E_spec(v): the specular reflection lobe's directional albedo per channel.
    [[nodiscard]] rgb<T> specular_albedo(T mu, const vec3<T>& w_local = vec3<T>(0)) const noexcept {
        const T e_dielectric =
            specular_eta_ == T(1) ? T(0)
            : specular_ && specular_anisotropic_ && w_local != vec3<T>(0)
                ? specular_albedo_anisotropic_.at(w_local)
            : specular_ ? specular_reflection_at(mu)
                        : F_dielectric(mu, specular_eta_);
        rgb<T> e(e_dielectric);
        if (p_.thin_film_weight > T(0)) {
            // The film's part: the lobe's albedo with F_film is R_ss plus the integral of
            // F_film - F against the lobe's measure of c = v·h (cosine_weights.hpp), summed
            // once per material in film_albedo_ and raised by the margin of
            // thin_film_margin_data.hpp (the white furnace reads 1 + true - read: a share
            // read low would create energy); exact for a smooth lobe (c = mu).
            // Below an index ratio of 1 the row sums F_film alone (film_alone_) and the
            // table's R_ss, which holds F's total-reflection kink, is subtracted here.
            // Around the film's own kink over a base below 1 an isotropic lobe reads the
            // same sum from film_window_.
            // An anisotropic lobe (film_on_grid_): D(v) of the same pass as R_ss, margins
            // included.
            const rgb<T> film_part =
                !specular_ ? film_dielectric_->F(mu) - rgb<T>(e_dielectric)
                : film_on_grid_ && w_local != vec3<T>(0)
                    ? film_grid_difference(w_local)
                    : (film_window_.contains(mu) ? film_window_.at(mu) : film_albedo_.at(mu)) -
                          rgb<T>(film_alone_ ? e_dielectric : T(0));
            e = glm::clamp(e + p_.thin_film_weight * film_part, rgb<T>(0), rgb<T>(1));
        }
        return p_.specular_color * e;
    }

    // openpbr::coat_absorption of the coat's colour for cosines mu_l, mu_v: exactly 1 for a
    // white coat (1^x = 1, also at a grazing refracted cosine), which is not computed.
    [[nodiscard]] rgb<T> coat_absorbed(T mu_l, T mu_v) const noexcept {
        if (coat_white_) return rgb<T>(1);
        return openpbr::coat_absorption(p_.coat_color, mu_l, mu_v, coat_eta_);
    }

    // The base's factor under the coat for cosines mu_l, mu_v (per channel):
    // lerp(1, T_coat (1 - E_coat(v)), C) D.
    [[nodiscard]] rgb<T> under_coat(T mu_l, const view& w) const noexcept {
        if (p_.coat_weight == T(0)) return rgb<T>(1);
        const rgb<T> absorbed = coat_absorbed(glm::min(mu_l, T(1)), w.mu);
        return glm::mix(rgb<T>(1), absorbed * (T(1) - w.coat_albedo), p_.coat_weight) * w.darkening;
    }

    // The view's terms; the lobe probabilities too when `probabilities` (pdf and sample).
    [[nodiscard]] view view_at(const vec3<T>& v, const surface_point<T>& at, bool probabilities = true) const noexcept {
        view w;
        w.mu = glm::min(glm::dot(at.n(), v), T(1));
        w.v_local = at.shading.to_local(v);
        const T F = p_.fuzz_weight;
        const T C = p_.coat_weight;
        const T M = p_.base_metalness;
        const T Tw = p_.transmission_weight;
        const T S = p_.subsurface_weight;
        const T e_fuzz = fuzz_albedo(w.mu);
        w.fuzz_keep = T(1) - F * e_fuzz;
        if (C > T(0)) {
            // F(mu, eta_c), computed once: the smooth coat's albedo, the rough coat's
            // albedo table's own Fresnel term, and the darkening's K_s.
            const T fresnel = F_dielectric(w.mu, coat_eta_);
            w.coat_albedo = coat_ && coat_anisotropic_ ? coat_albedo_anisotropic_.at(w.v_local)
                            : coat_ ? reflection_read(coat_albedo_.at(w.mu, fresnel), coat_window_, coat_row_margin_, w.mu)
                                                       : fresnel;
            w.darkening = openpbr::coat_darkening_factor_of_reflectances(
                base_albedo_, fresnel, coat_rough_reflection_, base_roughness_estimate_, C, p_.coat_darkening);
        }
        if (M < T(1)) {
            w.specular_albedo = specular_albedo(w.mu, w.v_local);
            if (transmission_ && Tw > T(0)) {
                w.transmission_view = transmission_->prepare(v, at);
                const T e_s = w.transmission_view.albedo;
                const T r_ss = transmission_anisotropic_
                                   ? (anisotropic_reflection_without_margin(w.v_local)
                                          ? transmission_reflection_anisotropic_.at_without_margin(w.v_local)
                                          : transmission_reflection_anisotropic_.at(w.v_local))
                               : transmission_reflection_is_specular_ ? w.specular_albedo.x
                               : transmission_reflection_windowed_ && specular_window_.contains(w.mu)
                                   ? glm::max(specular_window_.at_or_below(w.mu).x, T(0))
                               : transmission_window_.contains(w.mu)
                                   ? glm::max(transmission_window_.at_or_below(w.mu).x, T(0))
                                   : transmission_reflection_.at(w.mu);
                // The single-scattering part e_s - R_ss cannot be negative; where the two tables
                // read it so (near the total-reflection kink of an anisotropic interface below
                // an index ratio of 1, where both are near 1), it counts as 0, and the
                // transmission lobe is not scaled by the inverse of a vanishing difference.
                // With interface_draws_ the lobe carries the multiple scattering's reflected
                // part too (all of 1 - e_s instead of tau (1 - e_s)), and where that leaves it
                // less than 1 - E_spec (largest channel) to carry, the share of the interface's
                // single-scattering reflection R_ss that makes up the difference (class
                // comment), so that the lobe is never scaled up. With a film E_spec is the
                // film's share, not R_ss, and at another index than the transmission's (a
                // coat's TIR fix, specular_weight) it is another interface's: the lobe then
                // carries (1 - R_true) / (1 - R_ss) of what it is given, and an anisotropic
                // interface reads R_ss without its grid's margin (at_without_margin; where no
                // grid integrates, the same as at(); anisotropic_reflection_without_margin).
                const T lost = T(1) - e_s;
                const T carried = glm::max(e_s - r_ss, T(0)) +
                                  (interface_draws_ ? lost : transmission_->transmitted_share(false) * lost);
                w.transmittance = glm::max(carried, T(1e-6));
                if (interface_draws_) {
                    const T needed = max_channel(rgb<T>(1) - w.specular_albedo);
                    if (needed > carried && r_ss > T(0)) {
                        w.interface_reflection = glm::min((needed - carried) / r_ss, T(1));
                        w.transmittance = glm::max(carried + w.interface_reflection * r_ss, T(1e-6));
                    }
                }
            }
        }
        if (!probabilities) return w;
        // The energy each lobe sends back toward v (largest channel), whose shares are
        // the lobe probabilities.
        const T below = w.fuzz_keep * max_channel(under_coat(w.mu, w));
        const T dielectric = below * (T(1) - M);
        const T rest = dielectric * max_channel(rgb<T>(1) - w.specular_albedo);
        std::array<T, lobe_count> e{};
        e[std::size_t(lobe::fuzz)] = F * e_fuzz * max_channel(p_.fuzz_color);
        e[std::size_t(lobe::coat)] = w.fuzz_keep * C * w.coat_albedo;
        if (M > T(0)) e[std::size_t(lobe::metal)] = below * M * max_channel(metal_fresnel_->F(w.mu));
        e[std::size_t(lobe::specular)] = dielectric * max_channel(w.specular_albedo);
        e[std::size_t(lobe::transmission)] = rest * Tw * max_channel(transmission_tint_);
        const T opaque = rest * (T(1) - Tw);
        if (diffuse_) e[std::size_t(lobe::diffuse)] = opaque * (T(1) - S) * max_channel(diffuse_->rho());
        const T sss = subsurface_ ? opaque * S * max_channel(p_.subsurface_color) : T(0);
        if (p_.geometry_thin_walled) {
            const T g = p_.subsurface_scatter_anisotropy;
            e[std::size_t(lobe::subsurface_reflection)] = sss * T(0.5) * (T(1) - g);
            e[std::size_t(lobe::subsurface_transmission)] = sss * T(0.5) * (T(1) + g);
        } else {
            e[std::size_t(lobe::subsurface_reflection)] = sss;
        }
        T total = T(0);
        for (std::size_t k = 0; k + 1 < lobe_count; ++k) total += e[k];
        const T alpha = p_.geometry_opacity;
        if (total > T(0)) {
            for (std::size_t k = 0; k + 1 < lobe_count; ++k) w.p[k] = alpha * e[k] / total;
            w.p[std::size_t(lobe::transparent)] = T(1) - alpha;
        } else {
            w.p[std::size_t(lobe::transparent)] = alpha < T(1) ? T(1) : T(0);
        }
        if (interface_draws_ && M < T(1) && Tw > T(0)) {
            // Half the specular lobe's share goes to the transmission lobe, which then draws
            // from the whole interface (interface_draws_).
            const T moved = T(0.5) * w.p[std::size_t(lobe::specular)];
            w.p[std::size_t(lobe::specular)] -= moved;
            w.p[std::size_t(lobe::transmission)] += moved;
        }
        if (w.p[std::size_t(lobe::diffuse)] > T(0)) w.diffuse_view = diffuse_->prepare_local(w.v_local);
        return w;
    }

    [[nodiscard]] static T max_channel(const rgb<T>& c) noexcept { return glm::max(c.x, glm::max(c.y, c.z)); }

    // The local direction w mirrored through the surface (thin-walled transmission).
    [[nodiscard]] static vec3<T> mirrored(const vec3<T>& l, const surface_point<T>& at) noexcept {
        return l - T(2) * glm::dot(at.n(), l) * at.n();
    }

    // f_surface (without alpha) and the mixture density of the non-delta lobes, v above
    // `at`, each when asked for (the microfacet lobes share their half vector and D).
    struct value_and_density {
        rgb<T> f{0};
        T pdf = 0;
    };

    template <bool with_f, bool with_pdf>
    [[nodiscard]] value_and_density surface_eval(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at,
                                                 const view& w) const noexcept {
        value_and_density out;
        const T n_dot_l = glm::dot(at.n(), l);
        if (!(n_dot_l != T(0)) || !std::isfinite(n_dot_l)) return out;
        if (n_dot_l > T(0)) {
            reflect<with_f, with_pdf>(l, v, n_dot_l, at, w, out);
        } else if constexpr (with_f && with_pdf) {
            if (transmission_ && !p_.geometry_thin_walled && p_.transmission_weight > T(0)) {
                // The solid's transmission lobe alone below the surface: its f and pdf in one call.
                const auto value = transmission_->f_and_pdf(l, w.transmission_view, at);
                out.f = through_f(l, v, n_dot_l, at, w, &value.f);
                out.pdf = w.p[std::size_t(lobe::transmission)] * value.pdf;
            } else {
                out.f = through_f(l, v, n_dot_l, at, w);
                out.pdf = through_pdf(l, v, at, w);
            }
        } else {
            if constexpr (with_f) out.f = through_f(l, v, n_dot_l, at, w);
            if constexpr (with_pdf) out.pdf = through_pdf(l, v, at, w);
        }
        return out;
    }

    // A microfacet lobe's f and its density at the local pair, whose half vector is `half`
    // (the lobe's own pdf uses the same cosine share q).
    template <bool with_f, bool with_pdf, class Lobe>
    static void microfacet(const Lobe& lobe, const vec3<T>& l_local, const vec3<T>& v_local,
                           const detail::half_angle<T>& half, T weight, T probability, rgb<T>& f, T& pdf) noexcept {
        const bool density = with_pdf && probability > T(0);
        if (!with_f && !density) return;
        T q = T(0);
        if constexpr (std::derived_from<typename Lobe::scattering_type, kulla_conty>)
            q = lobe.multiple_scattering_probability(v_local.z);
        const auto parts = lobe.template evaluate_local<with_f, with_pdf>(l_local, v_local, half, rgb<T>(1), q);
        if constexpr (with_f) f = weight * (parts.single + parts.multiple);
        if constexpr (with_pdf) pdf += probability * parts.pdf;
    }

    // The reflected part (l above the surface).
    template <bool with_f, bool with_pdf>
    void reflect(const vec3<T>& l, const vec3<T>& v, T n_dot_l, const surface_point<T>& at, const view& w,
                 value_and_density& out) const noexcept {
        const T M = p_.base_metalness;
        const T Tw = p_.transmission_weight;
        const T S = p_.subsurface_weight;
        const auto p = [&](lobe k) { return with_pdf ? w.p[std::size_t(k)] : T(0); };
        const vec3<T> l_local = at.shading.to_local(l);
        const vec3<T>& v_local = w.v_local;
        // The half vector of the pair, computed once for all the microfacet lobes (each
        // reads it only where l and v are both above the surface).
        const detail::half_angle<T> half = (coat_ || metal_ || specular_) && l_local.z > T(0) && v_local.z > T(0)
                                               ? detail::half_vector_and_cos(l_local, v_local)
                                               : detail::half_angle<T>{};
        rgb<T> top(0), lobe_f(0);
        if (fuzz_) {
            if constexpr (with_f) top += p_.fuzz_weight * fuzz_->f(l, v, at);
            if (p(lobe::fuzz) > T(0)) out.pdf += p(lobe::fuzz) * fuzz_->pdf(l, v, at);
        }
        if (fuzz_reciprocal_) {
            if constexpr (with_f) top += p_.fuzz_weight * fuzz_reciprocal_->f(l, v, at);
            if (p(lobe::fuzz) > T(0)) out.pdf += p(lobe::fuzz) * fuzz_reciprocal_->pdf(l, v, at);
        }
        // The factors each layer puts on what lies below it (class comment).
        T fuzz_keep = w.fuzz_keep;
        rgb<T> coat_keep(1);
        rgb<T> specular_keep = rgb<T>(1) - w.specular_albedo;
        if constexpr (with_f) {
            if (form_ == layering::reciprocal) {
                const T mu_l = glm::min(n_dot_l, T(1));
                const T F = p_.fuzz_weight;
                fuzz_keep = (T(1) - F * fuzz_albedo(mu_l)) * w.fuzz_keep * fuzz_loss_inverse_;
                coat_keep = reciprocal_under_coat(mu_l, l_local, w);
                if (M < T(1)) specular_keep *= (rgb<T>(1) - specular_albedo(mu_l, l_local)) * specular_loss_inverse_;
            } else {
                coat_keep = under_coat(n_dot_l, w);
            }
        }
        if (coat_) {
            microfacet<with_f, with_pdf>(*coat_, l_local, v_local, half, fuzz_keep * p_.coat_weight, p(lobe::coat),
                                         lobe_f, out.pdf);
            if constexpr (with_f) top += lobe_f;
        }
        rgb<T> base(0);
        if (metal_ && M > T(0)) {
            microfacet<with_f, with_pdf>(*metal_, l_local, v_local, half, M, p(lobe::metal), lobe_f, out.pdf);
            if constexpr (with_f) base += lobe_f;
        }
        if (M < T(1)) {
            rgb<T> dielectric(0);
            if (interface_draws_ && Tw > T(0) && (with_f || p(lobe::transmission) > T(0))) {
                // The transmission lobe's reflected part (interface_draws_): the interface's
                // multiple-scattering reflection plus the share w.interface_reflection of its
                // single-scattering reflection (f_and_pdf's f less the former).
                const auto interface = transmission_->f_and_pdf(l, w.transmission_view, at);
                out.pdf += p(lobe::transmission) * interface.pdf;
                if constexpr (with_f) {
                    const T multiple = transmission_->multiple_scattering_reflection(l, w.transmission_view, at);
                    const T single = glm::max(interface.f.x - multiple, T(0));
                    dielectric += (Tw / w.transmittance) * (rgb<T>(1) - w.specular_albedo) *
                                  (multiple + w.interface_reflection * single);
                }
            }
            if (specular_) {
                microfacet<with_f, with_pdf>(*specular_, l_local, v_local, half, T(1), p(lobe::specular), lobe_f,
                                             out.pdf);
                if constexpr (with_f) dielectric += lobe_f;
            }
            if (Tw < T(1)) {
                rgb<T> opaque(0);
                if (diffuse_) {
                    if constexpr (with_f) opaque += (T(1) - S) * diffuse_->f(l, v, at);
                    if (p(lobe::diffuse) > T(0)) out.pdf += p(lobe::diffuse) * diffuse_->pdf_local(l_local, w.diffuse_view);
                }
                if (subsurface_) {
                    if constexpr (with_f)
                        opaque += S * subsurface_reflection_weight_ * subsurface_tint_ * subsurface_->f(l, v, at);
                    if (p(lobe::subsurface_reflection) > T(0))
                        out.pdf += p(lobe::subsurface_reflection) * subsurface_->pdf(l, v, at);
                }
                if constexpr (with_f) dielectric += specular_keep * ((T(1) - Tw) * opaque);
            }
            if constexpr (with_f) base += (T(1) - M) * dielectric;
        }
        if constexpr (with_f) out.f = top + fuzz_keep * coat_keep * base;
    }

    // f of the transmitted part (l below the surface); transmission_f, when given, is the
    // transmission lobe's f(l, v, at) already evaluated.
    [[nodiscard]] rgb<T> through_f(const vec3<T>& l, const vec3<T>& v, T n_dot_l, const surface_point<T>& at,
                                   const view& w, const rgb<T>* transmission_f = nullptr) const noexcept {
        const T M = p_.base_metalness;
        const T Tw = p_.transmission_weight;
        const T S = p_.subsurface_weight;
        if (M == T(1)) return rgb<T>(0);
        rgb<T> through(0);
        if (Tw > T(0)) {
            if (p_.geometry_thin_walled) {
                if (sheet_) through += Tw * transmission_tint_ * sheet_->f(mirrored(l, at), v, at);
            } else if (transmission_) {
                through += (Tw / w.transmittance) * transmission_tint_ *
                           (transmission_f ? *transmission_f : transmission_->f(l, v, at));
            }
        }
        if (p_.geometry_thin_walled && subsurface_ && Tw < T(1))
            through += ((T(1) - Tw) * S * subsurface_transmission_weight_) * subsurface_tint_ * subsurface_->f(mirrored(l, at), v, at);
        return w.fuzz_keep * under_coat(-n_dot_l, w) * ((T(1) - M) * (rgb<T>(1) - w.specular_albedo)) * through;
    }

    // The density of the transmitted part (l below the surface).
    [[nodiscard]] T through_pdf(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at,
                                const view& w) const noexcept {
        const auto p = [&](lobe k) { return w.p[std::size_t(k)]; };
        T density = T(0);
        if (p(lobe::transmission) > T(0)) {
            if (p_.geometry_thin_walled) {
                if (sheet_) density += p(lobe::transmission) * sheet_->pdf(mirrored(l, at), v, at);
            } else if (transmission_) {
                density += p(lobe::transmission) * transmission_->pdf(l, v, at);
            }
        }
        if (p(lobe::subsurface_transmission) > T(0))
            density += p(lobe::subsurface_transmission) * subsurface_->pdf(mirrored(l, at), v, at);
        return density;
    }

    // The bsdf_sample of a non-delta direction l drawn for v: the whole f and pdf (w the
    // view's terms for a view from outside, nullptr from inside).
    [[nodiscard]] std::optional<bsdf_sample<T>> finish(const vec3<T>& l, const vec3<T>& v, const oriented& o,
                                                       bsdf_flags kind, T eta, transport_mode mode,
                                                       const view* w) const {
        const surface_point<T> original = unflipped(o);
        T density;
        rgb<T> value;
        if (w && mode == transport_mode::radiance) {
            const value_and_density both = surface_eval<true, true>(l, v, o.at, *w);
            density = both.pdf;
            value = p_.geometry_opacity * both.f;
        } else {
            density = w ? surface_eval<false, true>(l, v, o.at, *w).pdf : inside_pdf(l, v, o.at);
            value = mode == transport_mode::importance ? f(v, l, original) : p_.geometry_opacity * inside_f(l, v, o.at);
        }
        const T abs_n_dot_l = std::abs(glm::dot(original.n(), l));
        // make_brdf_sample's weight stays exact when f and pdf are both subnormal (a subnormal
        // geometry_opacity scales both); nullopt for a density that is not finite and > 0.
        const std::optional<brdf_sample<T>> s = detail::make_brdf_sample(l, value, density, abs_n_dot_l);
        if (!s) return std::nullopt;
        const bool same_side = (glm::dot(original.n(), l) > T(0)) == (glm::dot(original.n(), v) > T(0));
        return bsdf_sample<T>{l, value, density, s->weight,
                              kind | (same_side ? bsdf_flags::reflection : bsdf_flags::transmission), eta};
    }

    [[nodiscard]] static surface_point<T> unflipped(const oriented& o) noexcept {
        if (!o.flipped) return o.at;
        surface_point<T> at = o.at;
        at.shading.n = -at.shading.n;
        at.shading.b = -at.shading.b;
        return at;
    }

    // Draws from lobe k for v above o.at (class comment).
    [[nodiscard]] std::optional<bsdf_sample<T>> sample_lobe(lobe k, const vec3<T>& v, T uc, const vec2<T>& u,
                                                            const oriented& o, const view& w,
                                                            transport_mode mode) const {
        const surface_point<T>& at = o.at;
        const T p_k = w.p[std::size_t(k)];
        const vec3<T> mirror = detail::reflect_about(v, at.n());
        // The lobe's direction only (finish evaluates the whole mixture at it): a microfacet
        // lobe's draw_local as its sample() draws, EON's draw, any other lobe's sample().
        const auto from_brdf = [&](const auto& model, bsdf_flags kind,
                                   bool through) -> std::optional<bsdf_sample<T>> {
            using model_type = std::remove_cvref_t<decltype(model)>;
            vec3<T> l;
            if constexpr (requires { typename model_type::scattering_type; }) {
                const vec3<T>& v_local = w.v_local;
                if (!(v_local.z > T(0))) return std::nullopt;
                bool from_cosine = false;
                if constexpr (std::derived_from<typename model_type::scattering_type, kulla_conty>)
                    from_cosine = uc < model.multiple_scattering_probability(v_local.z);
                l = at.shading.to_world(model.draw_local(v_local, from_cosine, u));
            } else if constexpr (std::same_as<model_type, diffuse_lobe>) {
                const std::optional<vec3<T>> drawn = model.draw(v, uc, u, at);
                if (!drawn) return std::nullopt;
                l = *drawn;
            } else {
                const auto s = model.sample(v, uc, u, at);
                if (!s) return std::nullopt;
                l = s->l;
            }
            // Every reflection lobe draws above the surface (a microfacet lobe's mirror
            // direction can fall below it: no draw, as its sample() has it).
            if (!(glm::dot(at.n(), l) > T(0))) return std::nullopt;
            if (through) l = mirrored(l, at);
            return finish(l, v, o, kind, T(1), mode, &w);
        };
        const T M = p_.base_metalness;
        switch (k) {
        case lobe::fuzz:
            if (fuzz_reciprocal_) return from_brdf(*fuzz_reciprocal_, bsdf_flags::glossy, false);
            return from_brdf(*fuzz_, bsdf_flags::glossy, false);
        case lobe::coat:
            if (coat_) return from_brdf(*coat_, bsdf_flags::glossy, false);
            return delta(mirror, rgb<T>(w.fuzz_keep * p_.coat_weight * F_dielectric(w.mu, coat_eta_)), p_k, o,
                         bsdf_flags::reflection, T(1));
        case lobe::metal:
            if (metal_) return from_brdf(*metal_, bsdf_flags::glossy, false);
            return delta(mirror, w.fuzz_keep * under_coat(w.mu, w) * (M * metal_fresnel_->F(w.mu)), p_k, o,
                         bsdf_flags::reflection, T(1));
        case lobe::specular:
            if (specular_) return from_brdf(*specular_, bsdf_flags::glossy, false);
            return delta(mirror, w.fuzz_keep * under_coat(w.mu, w) * ((T(1) - M) * specular_fresnel_->F(w.mu)), p_k,
                         o, bsdf_flags::reflection, T(1));
        case lobe::transmission: {
            const rgb<T> carried = w.fuzz_keep * ((T(1) - M) * p_.transmission_weight) *
                                   (rgb<T>(1) - w.specular_albedo) * transmission_tint_;
            if (p_.geometry_thin_walled) {
                if (sheet_) return from_brdf(*sheet_, bsdf_flags::glossy, true);
                return delta(-v, carried * under_coat(w.mu, w), p_k, o, bsdf_flags::transmission, T(1));
            }
            const T eta = p_.specular_ior;
            if (transmission_) {
                // The interface's direction only, kept when it crosses (its reflections
                // belong to the specular lobe) or, with interface_draws_, either way.
                const std::optional<vec3<T>> l = transmission_->draw(w.transmission_view, uc, u, at);
                if (!l) return std::nullopt;
                const T n_dot_l = glm::dot(at.n(), *l);
                if (interface_draws_ && n_dot_l > T(0)) return finish(*l, v, o, bsdf_flags::glossy, T(1), mode, &w);
                if (!(n_dot_l < T(0))) return std::nullopt;
                return finish(*l, v, o, bsdf_flags::glossy, transmission_->eta(), mode, &w);
            }
            if (index_matched_) return delta(-v, carried * under_coat(w.mu, w), p_k, o, bsdf_flags::transmission, T(1));
            const std::optional<vec3<T>> l = refract(v, at.n(), eta);
            // Beyond the critical angle of specular_ior < 1 (under a coat, E_spec is read at
            // a ratio above 1 and can leave this lobe energy there) the interface reflects
            // totally: what the lobe carries leaves along the mirror direction.
            if (!l) return delta(mirror, carried * under_coat(w.mu, w), p_k, o, bsdf_flags::reflection, T(1));
            const T mu_l = -glm::dot(at.n(), *l);
            const T radiance = mode == transport_mode::radiance ? T(1) / (eta * eta) : T(1);
            return delta(*l, carried * under_coat(mu_l, w) * radiance, p_k, o, bsdf_flags::transmission, eta);
        }
        case lobe::diffuse: {
            const std::optional<vec3<T>> l = diffuse_->draw(w.diffuse_view, uc, u, at);
            if (!l) return std::nullopt;
            return finish(*l, v, o, bsdf_flags::diffuse, T(1), mode, &w);
        }
        case lobe::subsurface_reflection:
            return from_brdf(*subsurface_, bsdf_flags::diffuse, false);
        case lobe::subsurface_transmission:
            return from_brdf(*subsurface_, bsdf_flags::diffuse, true);
        case lobe::transparent:
            if (!(p_k > T(0))) return std::nullopt;
            return detail::make_specular_sample(-v, rgb<T>(T(1) - p_.geometry_opacity), p_k, unflipped(o),
                                                bsdf_flags::transmission, T(1));
        case lobe::count:
            break;
        }
        return std::nullopt;
    }

    // A delta sample of the surface (throughput before opacity, which it applies), chosen
    // with probability p.
    [[nodiscard]] std::optional<bsdf_sample<T>> delta(const vec3<T>& l, const rgb<T>& throughput, T p,
                                                      const oriented& o, bsdf_flags kind, T eta) const noexcept {
        if (!(p > T(0))) return std::nullopt;
        return detail::make_specular_sample(l, p_.geometry_opacity * throughput, p, unflipped(o), kind, eta);
    }

    // Seen from inside a solid: the bare interface times alpha, and the pass-through.
    [[nodiscard]] T inside_probability(bool transparent) const noexcept {
        const bool interface = inside_transmits_;
        const T alpha = p_.geometry_opacity;
        if (transparent) return interface ? T(1) - alpha : (alpha < T(1) ? T(1) : T(0));
        return interface ? alpha : T(0);
    }

    [[nodiscard]] rgb<T> inside_f(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const noexcept {
        if (!inside_transmits_ || !transmission_) return rgb<T>(0);
        return transmission_->f(l, v, at);
    }

    [[nodiscard]] T inside_pdf(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const noexcept {
        if (!inside_transmits_ || !transmission_) return T(0);
        return inside_probability(false) * transmission_->pdf(l, v, at);
    }

    [[nodiscard]] std::optional<bsdf_sample<T>> inside_sample(const vec3<T>& v, T uc, const vec2<T>& u,
                                                              const oriented& o, transport_mode mode) const {
        const T p_through = inside_probability(true);
        if (uc < p_through) {
            return detail::make_specular_sample(-v, rgb<T>(T(1) - p_.geometry_opacity), p_through, o.at,
                                                bsdf_flags::transmission, T(1));
        }
        const T p_interface = inside_probability(false);
        if (!(p_interface > T(0))) return std::nullopt;
        const T uc_interface = glm::max(T(0), detail::remap_lobe_choice(uc - p_through, p_interface, true));
        if (transmission_) {
            const auto s = transmission_->sample(v, uc_interface, u, o.at, mode);
            if (!s) return std::nullopt;
            if (is_specular(s->flags)) return std::nullopt;
            return finish(s->l, v, o, bsdf_flags::glossy, s->eta, mode, nullptr);
        }
        if (index_matched_)
            return detail::make_specular_sample(-v, rgb<T>(p_.geometry_opacity), p_interface, o.at,
                                                bsdf_flags::transmission, T(1));
        const auto s = smooth_dielectric<T>(unchecked, p_.specular_ior).sample(v, uc_interface, u, o.at, mode);
        if (!s) return std::nullopt;
        const T throughput_over_p = p_.geometry_opacity / p_interface;
        bsdf_sample<T> out = *s;
        out.pdf *= p_interface;
        out.f *= p_.geometry_opacity;
        out.weight *= throughput_over_p;
        return out;
    }

    void build();

    openpbr_parameters<T> p_;
    layering form_;
    openpbr::interface_albedo albedo_ = openpbr::interface_albedo::tables;
    std::optional<fuzz_lobe> fuzz_;
    std::optional<zeltner_sheen_reciprocal<T>> fuzz_reciprocal_;
    std::optional<coat_lobe> coat_;
    std::optional<metal_lobe> metal_;
    std::optional<specular_lobe> specular_;
    std::optional<transmission_lobe> transmission_;
    detail::shared_rough_dielectric_albedo_grid<T> transmission_grid_; // E_s of an anisotropic transmission_
    // Seen from outside an interface whose index ratio is below 1 (specular_ior < 1), most
    // views lie in the cone of total internal reflection: the interface transmits a small
    // T(v), and a transmission lobe chosen with a probability ~ T(v) whose draw crosses with
    // a probability ~ T(v) again gives its crossings weights ~ 1 / T(v) (hundreds). There
    // the transmission lobe also gets half the specular lobe's probability and keeps the
    // interface's reflections as well (their density joins the mixture's for reflected
    // directions), so that its crossings are drawn several times more often; and its f
    // includes the interface's multiple-scattering reflection (class comment).
    bool interface_draws_ = false;
    std::optional<sheet_lobe> sheet_;
    std::optional<diffuse_lobe> diffuse_;
    std::optional<diffuse_lobe> subsurface_;
    std::optional<openpbr::surface_fresnel<T>> metal_fresnel_;
    std::optional<openpbr::surface_fresnel<T>> specular_fresnel_;
    std::optional<thin_film_fresnel<T>> film_dielectric_;
    detail::fresnel_albedo_row<T> film_albedo_{}; // integral of F_film - F at eta'_s (rough, with a film)
    bool film_alone_ = false;                      // film_albedo_ integrates F_film alone (eta'_s < 1)
    std::array<rgb<T>, detail::cosine_weight_nodes> film_nodes_{}; // what film_albedo_ sums, at the nodes
    // What film_row_margin adds to its own estimate of a film's shortfall for the weights' error
    // beyond that of a smooth Fresnel factor: the largest shortfall without it, over the
    // films of tests/sweep/test_openpbr_film_sweep.cpp and 900 random films (index 1.01-3,
    // 0.03-2.5 um over 1.05-3, specular_weight 0.2-1, roughness 0.01-1, mu 0.1-1), was
    // 6.6e-4 (index 3, 0.25 um over 1.33, roughness 0.2, mu 1), rounded up.
    static constexpr double film_weights_allowance = 8e-4;
    // The quadrature of a film's total-reflection kink over a base of index below 1: columns x
    // rows visits per view node for the masses in the kink cell (kink_cell_correction),
    // strata^2 per point for the view cells within the reach (kink_view_shortfall), and what
    // the row is raised by for the masses' error: the largest shortfall left, over 180 random
    // films (index 1.2-2.5, 0.05-2 um over 0.33-0.99, roughness 0.1-1, mu 0.05-1), was 2.8e-3.
    static constexpr std::size_t film_kink_columns = 32;
    static constexpr std::size_t film_kink_rows = 128;
    static constexpr std::size_t film_kink_view_strata = 16;
    static constexpr std::size_t film_kink_view_reach = 2;
    static constexpr double film_kink_margin = 3e-3;
    // The film's share around a kink over a base below 1 for narrow isotropic lobes
    // (specular_albedo), the largest alpha that reads it, its quadrature's cells per side,
    // and its margin: the midpoint rule's error on a kinked F at 32^2 cells against 200^2,
    // -3.3e-3 to +3e-3 up to alpha 0.1 (larger above it: -8e-3 at alpha 0.36, where the
    // row's own kink corrections serve).
    detail::kink_view_window<T> film_window_{};
    static constexpr double film_window_alpha_max = 0.1;
    static constexpr std::size_t film_window_strata = 32;
    static constexpr double film_window_margin = 4e-3;
    // The film's share of an anisotropic lobe whose R_ss is integrated per interface is
    // integrated in the same pass (specular_albedo_anisotropic_.difference); F_film is read
    // there from this many cosine intervals, linearly.
    static constexpr std::size_t film_fresnel_nodes = 4096;
    bool film_on_grid_ = false;
    std::size_t film_margin_first_ = 0, film_margin_last_ = 0;      // the margin's film indices
    std::size_t film_margin_table_ = 0;                             // the margin's table (0: eta'_s = specular_ior)
    rgb<T> transmission_tint_{1};
    rgb<T> subsurface_tint_{1};
    rgb<T> base_albedo_{1};
    T subsurface_reflection_weight_ = 1;
    T subsurface_transmission_weight_ = 0;
    T coat_eta_ = T(1.6);
    bool coat_white_ = false;       // coat_color = (1, 1, 1): no absorption
    T coat_rough_reflection_ = 0;   // K_r of the coat (openpbr::coat_rough_reflection)
    T coat_alpha_ = 0;
    detail::reflection_albedo_row<T> coat_albedo_{};          // E_coat(mu)
    detail::kink_view_window<T> coat_window_{};               // reflection_read's, coat_ior < 1
    T coat_row_margin_ = 0;                                   // reflection_read's, coat_ior < 1
    detail::reflection_albedo_row<T> specular_albedo_{};      // R_ss(mu) at eta'_s
    // Below an index ratio of 1 (isotropic rough lobe): reflection_read's window and margin
    // for the specular lobe (below_one_reflection).
    detail::kink_view_window<T> specular_window_{};
    T specular_row_margin_ = 0;
    static constexpr double below_one_margin = 4e-3;
    static constexpr std::size_t below_one_window_reach = 3;
    detail::reflection_albedo_row<T> transmission_reflection_{}; // R_ss(mu) at specular_ior
    detail::anisotropic_reflection_albedo_grid<T> coat_albedo_anisotropic_{};         // E_coat(v), anisotropic coat
    detail::anisotropic_reflection_albedo_grid<T> specular_albedo_anisotropic_{};     // R_ss(v) at eta'_s, anisotropic
    detail::anisotropic_reflection_albedo_grid<T> transmission_reflection_anisotropic_{}; // R_ss(v), anisotropic
    bool transmission_reflection_shared_ = false; // E_spec reads R_ss at the transmission's index (same_index)
    bool transmission_anisotropic_ = false;
    bool transmission_reflection_is_specular_ = false; // transmission_reflection_ = E_spec (build)
    // The transmission's interface is the isotropic specular lobe's below 1 (the same index
    // and roughness) but E_spec is not its R_ss (a film, a tint): R_ss around the critical
    // cosine is read from the lobe's window at or below its value (view_at).
    bool transmission_reflection_windowed_ = false;
    // Below an index ratio of 1/3, beyond the reflection table's index range, where the row
    // reads R_ss up to 6e-2 high (roughness 0.5): the isotropic interface's R_ss over every
    // view cosine (a kink_view_window reaching the whole range), read at or below it by the
    // transmission lobe when E_spec is not that R_ss (view_at).
    detail::kink_view_window<T> transmission_window_{};
    bool coat_anisotropic_ = false;
    bool specular_anisotropic_ = false;
    T specular_eta_ = T(1.5);
    T specular_alpha_ = 0;
    T transmission_alpha_ = 0;
    T base_roughness_estimate_ = 0;
    T fuzz_loss_inverse_ = 1;       // reciprocal form: 1 / (1 - F E_fuzz,avg)
    T coat_loss_inverse_ = 1;       // reciprocal form: 1 / (1 - C E_coat,avg)
    rgb<T> specular_loss_inverse_{1}; // reciprocal form: 1 / (1 - E_spec,avg) per channel
    bool index_matched_ = false;
    bool inside_transmits_ = false;
};

template <std::floating_point T>
void openpbr_surface<T>::build() {
    const openpbr_parameters<T>& p = p_;
    const T C = p.coat_weight;
    // A GGX of the alphas of roughness r and anisotropy a, or nothing below smallest_alpha.
    const auto distribution = [](T r, T a) -> std::optional<ggx<T>> {
        const openpbr::alpha_pair<T> alpha = openpbr::roughness_to_alpha(r, a);
        if (!(alpha.t >= openpbr::smallest_alpha<T>)) return std::nullopt;
        return ggx<T>(unchecked, alpha.t, glm::max(alpha.b, openpbr::smallest_alpha<T>));
    };
    const auto iso = [](const ggx<T>& d) { return std::sqrt(d.alpha_x() * d.alpha_y()); };

    // Fuzz.
    if (p.fuzz_weight > T(0)) {
        if (form_ == layering::reciprocal)
            fuzz_reciprocal_.emplace(p.fuzz_color, p.fuzz_roughness);
        else
            fuzz_.emplace(p.fuzz_color, p.fuzz_roughness);
    }

    // Coat.
    coat_eta_ = p.coat_ior;
    coat_white_ = p.coat_color == rgb<T>(1);
    if (C > T(0)) coat_rough_reflection_ = openpbr::coat_rough_reflection(coat_eta_);
    if (C > T(0)) {
        if (const auto d = distribution(p.coat_roughness, p.coat_roughness_anisotropy)) {
            coat_.emplace(unchecked, *d, dielectric_fresnel<T>(unchecked, coat_eta_));
            coat_alpha_ = iso(*d);
            coat_albedo_ = detail::reflection_albedo_row<T>(coat_alpha_, coat_eta_);
            coat_anisotropic_ = d->alpha_x() != d->alpha_y();
            if (!coat_anisotropic_) below_one_reflection(coat_alpha_, coat_eta_, coat_window_, coat_row_margin_);
            if (coat_anisotropic_)
                coat_albedo_anisotropic_ =
                    detail::anisotropic_reflection_albedo_grid<T>(d->alpha_x(), d->alpha_y(), coat_eta_);
        }
    }

    // Thin film (section "Thin film"): thickness in micrometres, the film's index over the
    // ambient medium (index 1).
    const T thickness_nm = glm::min(p.thin_film_thickness * T(1000), T(1e5));
    const T film_ior = glm::clamp(p.thin_film_ior, T(1e-4), T(1e4));
    // The film's base index over the ambient medium; below 1 the film/base interface reflects
    // totally under the base's critical cosine (by Snell's invariant, at the angle of the
    // bare interface): F_film's kink, 0 for none.
    const T film_base_ior = glm::clamp(p.specular_ior, T(1e-4), T(1e4));
    const double film_kink =
        film_base_ior < T(1) ? std::sqrt((1.0 - double(film_base_ior)) * (1.0 + double(film_base_ior))) : 0.0;
    const thin_film_fresnel<T> film_over_dielectric =
        thin_film_fresnel<T>::over_dielectric(film_base_ior, film_ior, thickness_nm);
    const T film_weight = p.thin_film_weight;
    if (film_weight > T(0)) film_dielectric_.emplace(film_over_dielectric);

    // The base's roughness, widened by the coat.
    const T r_base = openpbr::coat_roughened(p.specular_roughness, p.coat_roughness, C);
    const std::optional<ggx<T>> base_distribution = distribution(r_base, p.specular_roughness_anisotropy);

    // Metal.
    const rgb<T> f0 = glm::clamp(p.base_weight * p.base_color, rgb<T>(0), rgb<T>(1));
    const f82_tint<T> f82(unchecked, f0, p.specular_color, glm::min(p.specular_weight, T(1)));
    const openpbr::conductor_index<T> index = openpbr::gulbrandsen_index(f0, p.specular_color);
    metal_fresnel_.emplace(openpbr::surface_fresnel<T>::metal(
        f82, film_weight,
        film_weight > T(0) ? thin_film_fresnel<T>::over_conductor(index.eta, index.kappa, film_ior, thickness_nm)
                           : film_over_dielectric));
    if (p.base_metalness > T(0) && base_distribution) metal_.emplace(unchecked, *base_distribution, *metal_fresnel_);

    // Dielectric base: the specular reflection.
    const T eta_s = openpbr::specular_ior_ratio(p.specular_ior, T(1), p.coat_ior, C);
    specular_eta_ = openpbr::modulated_ior_ratio(eta_s, p.specular_weight);
    // The transmission lobe's interface (below), and whether it reads E_s on the outside
    // from a grid filled in the same pass as that side's R_ss: anisotropic in the tables
    // mode below an index ratio of 1 (away from index match, where a whole grid serves).
    const T interface_eta = glm::clamp(p.specular_ior, dielectric_eta_min<T>, dielectric_eta_max<T>);
    const T interface_eta_hat = interface_eta > T(1) ? interface_eta : T(1) / interface_eta;
    const bool near_match = interface_eta_hat < T(detail::dielectric_albedo_eta_min);
    index_matched_ = std::abs(p.specular_ior - T(1)) < T(1e-4);
    const bool transmits = p.transmission_weight > T(0) && p.base_metalness < T(1);
    const bool transmission_total_grid = base_distribution && transmits && !p.geometry_thin_walled && !index_matched_ &&
                                         base_distribution->alpha_x() != base_distribution->alpha_y() &&
                                         albedo_ == openpbr::interface_albedo::tables && interface_eta < T(1) &&
                                         !near_match;
    // eta'_s is specular_ior up to rounding when uncoated at specular_weight 1
    // (modulated_ior_ratio's round trip through F0): equal within 8 ulp here.
    const bool same_index =
        std::abs(specular_eta_ - interface_eta) <= T(8) * std::numeric_limits<T>::epsilon() * interface_eta;
    specular_fresnel_.emplace(
        openpbr::surface_fresnel<T>::dielectric(specular_eta_, p.specular_color, film_weight, film_over_dielectric));
    if (base_distribution) {
        specular_.emplace(unchecked, *base_distribution, *specular_fresnel_);
        specular_alpha_ = iso(*base_distribution);
        specular_albedo_ = detail::reflection_albedo_row<T>(specular_alpha_, specular_eta_);
        specular_anisotropic_ = base_distribution->alpha_x() != base_distribution->alpha_y();
        if (!specular_anisotropic_)
            below_one_reflection(specular_alpha_, specular_eta_, specular_window_, specular_row_margin_);
        // Below an index ratio of 1, and above it at strong anisotropy, the grid integrates
        // R_ss for this interface (100-180 ms below, 20-50 ms above; its class comment); the
        // transmission lobe, below, reads the same grid when its index is the same.
        // With a thin film on such a grid, the same pass integrates the film's share too:
        // D(v) = int (F_film - F) G2 / G1 over the same visible normals (the grid's rows dense
        // in mu, for a thick film's fringes), F_film read from a table of film_fresnel_nodes
        // + 1 cosines (the film's F per call would cost several times the pass), so that
        // E_spec = tint (R_ss + w D) (specular_albedo).
        // Every anisotropic lobe with a film builds it (at eta'_s = 1, specular_weight 0, the
        // lobe reflects through the film alone: the grid holds D alone, R_ss = 0).
        const T ax = base_distribution->alpha_x(), ay = base_distribution->alpha_y();
        const bool film_grid = film_dielectric_ && specular_anisotropic_;
        if (specular_anisotropic_ && (specular_eta_ != T(1) || film_grid)) {
            const bool total = transmission_total_grid && same_index;
            if (film_grid) {
                std::vector<std::array<double, 3>> film_table(film_fresnel_nodes + 1);
                for (std::size_t i = 0; i <= film_fresnel_nodes; ++i) {
                    const rgb<T> f = film_dielectric_->F(T(double(i) / double(film_fresnel_nodes)));
                    film_table[i] = {double(f.x), double(f.y), double(f.z)};
                }
                const auto film_fresnel = [&film_table](double c) {
                    const double x = glm::clamp(c, 0.0, 1.0) * double(film_fresnel_nodes);
                    const std::size_t i = glm::min(std::size_t(x), film_fresnel_nodes - 1);
                    const double t = x - double(i);
                    std::array<double, 3> f{};
                    for (std::size_t k = 0; k < 3; ++k) f[k] = film_table[i][k] + t * (film_table[i + 1][k] - film_table[i][k]);
                    return f;
                };
                // Around F_film's kink (film_kink) the grid integrates the film's albedo on a
                // window too, for a narrow lobe.
                specular_albedo_anisotropic_ = detail::anisotropic_reflection_albedo_grid<T>(
                    ax, ay, specular_eta_, total, film_fresnel, film_kink);
                film_on_grid_ = true;
            } else {
                specular_albedo_anisotropic_ = detail::anisotropic_reflection_albedo_grid<T>(ax, ay, specular_eta_, total);
            }
        }
        if (film_dielectric_) {
            const T eta = specular_eta_;
            const thin_film_fresnel<T>& film = *film_dielectric_;
            // Below 1, F is 1 under the critical cosine and falls steeply above it, a kink the
            // nodes' linear interpolation misses (overestimating F near it): the row then sums
            // F_film alone and specular_albedo subtracts the table's R_ss.
            // The margin: table 0 where eta'_s is the film's own base index (uncoated at
            // specular_weight 1), table 1 for any eta'_s (a coat, another specular_weight).
            film_alone_ = eta < T(1);
            const bool film_over_eta = C == T(0) && p.specular_weight == T(1) && !film_alone_;
            const auto film_difference = [&](T c) {
                return film.F(c) - rgb<T>(film_alone_ || eta == T(1) ? T(0) : F_dielectric(c, eta));
            };
            for (std::size_t k = 0; k < detail::cosine_weight_nodes; ++k)
                film_nodes_[k] = film_difference(T(detail::cosine_weight_node(k)));
            film_albedo_ = detail::fresnel_albedo_row<T>(specular_alpha_, film_nodes_);
            // Over a base of specular_ior below 1 the film/base interface reflects totally
            // under the base's critical cosine (by Snell's invariant, at the angle of the bare
            // interface), a kink of F_film between two nodes that the row's interpolation cuts
            // off, in c and, for narrow lobes, in mu: the row gets the kink cell's integral
            // (kink_cell_correction, up to its quadrature's error, which film_kink_margin
            // covers) and is lifted where it still reads low around the critical cosine
            // (kink_view_shortfall). About 12 ms, only for such films on isotropic lobes: an
            // anisotropic lobe's share is integrated on its grid (film_on_grid_). F's own kink
            // (eta'_s < 1) is not in the nodes: below 1 they hold F_film alone.
            if (film_kink > 0 && !specular_anisotropic_) {
                const double kink = film_kink;
                film_albedo_.add(
                    detail::kink_cell_correction(specular_alpha_, film_nodes_, film_difference, kink, film_kink_columns,
                                                 film_kink_rows));
                film_albedo_.add(detail::kink_view_shortfall(specular_alpha_, film_albedo_, film_difference, kink,
                                                             film_kink_view_reach, film_kink_view_strata));
                std::array<double, detail::cosine_weight_nodes> kink_margin;
                kink_margin.fill(film_kink_margin);
                film_albedo_.raise(kink_margin);
                // For a narrow lobe (alpha up to film_window_alpha_max) the views within
                // film_kink_view_reach cells of the kink read the window instead
                // (detail::kink_view_window: the sum steps there within about alpha of the
                // critical cosine, which the row's view nodes bridge from above only across
                // a whole cell), its F from film_fresnel_nodes + 1 cosines (about 20 ms).
                if (specular_alpha_ <= T(film_window_alpha_max)) {
                    std::vector<rgb<double>> table(film_fresnel_nodes + 1);
                    for (std::size_t i = 0; i <= film_fresnel_nodes; ++i)
                        table[i] = rgb<double>(film_difference(T(double(i) / double(film_fresnel_nodes))));
                    const auto difference_at = [&table](double c) {
                        const double x = glm::clamp(c, 0.0, 1.0) * double(film_fresnel_nodes);
                        const std::size_t i = glm::min(std::size_t(x), film_fresnel_nodes - 1);
                        return table[i] + (x - double(i)) * (table[i + 1] - table[i]);
                    };
                    film_window_ = detail::kink_view_window<T>(double(specular_alpha_), difference_at, kink,
                                                               film_kink_view_reach, film_window_strata,
                                                               film_window_margin);
                }
            }
            // The margin's film indices around thin_film_ior (the larger margin of the two,
            // or the one it equals); outside the grid's range, the largest of all.
            constexpr std::size_t nf = detail::thin_film_margin_iors;
            const double n_f = double(film_ior);
            std::size_t first = 0, last = nf - 1;
            if (n_f >= detail::thin_film_margin_ior[0] && n_f <= detail::thin_film_margin_ior[nf - 1]) {
                while (first + 1 < nf && detail::thin_film_margin_ior[first + 1] <= n_f) ++first;
                last = detail::thin_film_margin_ior[first] == n_f ? first : first + 1;
            }
            film_margin_first_ = first;
            film_margin_last_ = last;
            film_margin_table_ = film_over_eta ? 0 : 1;
            film_albedo_.raise(film_row_margin(thickness_nm));
        }
    }

    // Transmission.
    transmission_tint_ = (p.geometry_thin_walled || !(p.transmission_depth > T(0))) ? p.transmission_color : rgb<T>(1);
    inside_transmits_ = transmits && !p.geometry_thin_walled;
    if (base_distribution && transmits) {
        if (p.geometry_thin_walled) {
            sheet_.emplace(unchecked, *base_distribution, schlick<T>(unchecked, rgb<T>(1)));
        } else if (!index_matched_) {
            transmission_anisotropic_ = base_distribution->alpha_x() != base_distribution->alpha_y();
            // R_ss of the interface at the view (anisotropic): the specular lobe's grid when
            // it is the same interface, else one of its own (with E_s on the same nodes for
            // transmission_total_grid).
            if (transmission_anisotropic_ && specular_albedo_anisotropic_.integrated() && same_index &&
                (!transmission_total_grid || specular_albedo_anisotropic_.total_albedo() != nullptr))
                transmission_reflection_anisotropic_ = specular_albedo_anisotropic_; // the same interface
            else if (transmission_anisotropic_)
                transmission_reflection_anisotropic_ = detail::anisotropic_reflection_albedo_grid<T>(
                    base_distribution->alpha_x(), base_distribution->alpha_y(), interface_eta, transmission_total_grid);
            // Near index match (eta_hat below the total-albedo tables' first index, 1.05)
            // the tables read E_s at 1.05, far from this interface's (the white furnace of
            // rough glass read 0.95 to 1.10 at specular_ior 0.97 to 1.03): the grid serves
            // there whatever the mode (about 16 ms isotropic, 0.3 s anisotropic).
            if ((albedo_ == openpbr::interface_albedo::grid && transmission_anisotropic_) || near_match) {
                // E_s from a grid of this interface (compensated_rough_dielectric's
                // per-interface mode), which holds R + T where the tables' anisotropic
                // correction does not, and near index match.
                transmission_grid_ = detail::shared_rough_dielectric_albedo_grid<T>(*base_distribution, interface_eta);
                transmission_.emplace(*base_distribution, interface_eta, *transmission_grid_.get());
            } else if (transmission_total_grid && transmission_reflection_anisotropic_.total_albedo() != nullptr) {
                // Anisotropic below 1 in the tables mode: the views from outside, where the
                // tables' correction reads E_s up to 0.016 high at grazing views across the
                // smoother axis (a white furnace 0.98 there), read E_s from the R_ss grid's
                // pass; the views from inside read the tables.
                transmission_grid_ = detail::shared_rough_dielectric_albedo_grid<T>(
                    *base_distribution, interface_eta, false, *transmission_reflection_anisotropic_.total_albedo());
                transmission_.emplace(*base_distribution, interface_eta, *transmission_grid_.get());
            } else {
                transmission_.emplace(unchecked, *base_distribution, interface_eta);
            }
            transmission_alpha_ = iso(*base_distribution);
            const T eta = transmission_->eta();
            interface_draws_ = eta < T(1);
            transmission_reflection_ = detail::reflection_albedo_row<T>(transmission_alpha_, eta);
            transmission_reflection_shared_ = same_index;
            // R_ss at the view is the specular lobe's E_spec itself when both read the same
            // row and E_spec has no tint or film: one lookup serves both.
            transmission_reflection_is_specular_ = specular_ && !specular_anisotropic_ && !transmission_anisotropic_ &&
                                                   specular_alpha_ == transmission_alpha_ && same_index &&
                                                   p.specular_color == rgb<T>(1) && !(film_weight > T(0));
            transmission_reflection_windowed_ = specular_ && !specular_anisotropic_ && !transmission_anisotropic_ &&
                                                specular_alpha_ == transmission_alpha_ && same_index;
            if (!transmission_anisotropic_ && !transmission_reflection_is_specular_ &&
                eta < T(1.0 / detail::dielectric_albedo_eta_max))
                transmission_window_ = dielectric_window(transmission_alpha_, eta, detail::cosine_weight_nodes);
        }
    }

    // Diffuse and subsurface.
    const bool opaque_base = p.base_metalness < T(1) && p.transmission_weight < T(1);
    if (opaque_base && p.subsurface_weight < T(1))
        diffuse_.emplace(unchecked, glm::clamp(p.base_weight * p.base_color, rgb<T>(0), rgb<T>(1)),
                         p.base_diffuse_roughness);
    if (opaque_base && p.subsurface_weight > T(0)) {
        if (p.geometry_thin_walled) {
            subsurface_.emplace(unchecked, rgb<T>(1), p.base_diffuse_roughness);
            subsurface_tint_ = p.subsurface_color;
            const T g = p.subsurface_scatter_anisotropy;
            subsurface_reflection_weight_ = T(0.5) * (T(1) - g);
            subsurface_transmission_weight_ = T(0.5) * (T(1) + g);
        } else {
            subsurface_.emplace(unchecked, p.subsurface_color, p.base_diffuse_roughness);
        }
    }

    // The base's normal-incidence albedo for the coat's darkening (section "Coat",
    // "Darkening": E_b), and the estimated base roughness.
    const T r0 = F_dielectric(T(1), specular_eta_);
    // The translucent base's albedo: its colour at the surface (depth 0), or, with an
    // interior medium, what the medium's scattering can send back (transmission_scatter).
    const rgb<T> translucent = p.transmission_depth > T(0) ? p.transmission_scatter : p.transmission_color;
    const rgb<T> below = glm::mix(glm::mix(p.base_weight * p.base_color, p.subsurface_color, p.subsurface_weight),
                                  translucent, p.transmission_weight);
    const rgb<T> dielectric_albedo = p.specular_color * r0 + (rgb<T>(1) - p.specular_color * r0) * below;
    base_albedo_ = glm::clamp(glm::mix(dielectric_albedo, metal_fresnel_->F(T(1)), p.base_metalness), rgb<T>(0),
                              rgb<T>(1));
    base_roughness_estimate_ =
        openpbr::base_roughness_estimate(p.specular_roughness, p.base_metalness, p.specular_weight, eta_s);

    // The reciprocal form's averages E_avg = (1 / pi) integral E(w) mu dw, by the midpoint
    // rule on 32 cells of x = sqrt(mu) (E_avg = 4 integral E(x^2) x^3 dx for an E of mu
    // alone), normalised so that a constant E is exact; an anisotropic E (read at each
    // direction's azimuth, as the layers read it) also by the midpoint rule on 4 cells of the
    // azimuth over a quarter turn (E is even in each of the direction's local x and y). A loss
    // of 0 (a layer that reflects everything) leaves nothing below it: its inverse is taken
    // as 0.
    if (form_ == layering::reciprocal) {
        const auto inverse_loss = [](T loss) { return loss > T(0) ? T(1) / loss : T(0); };
        if (fuzz_reciprocal_) fuzz_loss_inverse_ = inverse_loss(T(1) - p.fuzz_weight * fuzz_reciprocal_->average_albedo());
        constexpr int cells = 32;
        constexpr int azimuths = 4;
        const bool anisotropic = (coat_ && coat_anisotropic_) || (specular_ && specular_anisotropic_);
        T coat_sum = 0, weights = 0;
        rgb<T> specular_sum(0);
        for (int k = 0; k < cells; ++k) {
            const T x = (T(k) + T(0.5)) / T(cells);
            const T w = x * x * x;
            const T mu = x * x;
            if (!anisotropic) {
                coat_sum += w * coat_albedo(mu);
                specular_sum += w * specular_albedo(mu);
            } else {
                const T sin_theta = std::sqrt((T(1) - mu) * (T(1) + mu));
                for (int j = 0; j < azimuths; ++j) {
                    const T phi = (T(j) + T(0.5)) * (pi<T> / T(2)) / T(azimuths);
                    const vec3<T> w_local(sin_theta * std::cos(phi), sin_theta * std::sin(phi), mu);
                    coat_sum += w / T(azimuths) * coat_albedo(mu, w_local);
                    specular_sum += w / T(azimuths) * specular_albedo(mu, w_local);
                }
            }
            weights += w;
        }
        coat_loss_inverse_ = inverse_loss(T(1) - C * coat_sum / weights);
        for (int c = 0; c < 3; ++c) specular_loss_inverse_[c] = inverse_loss(T(1) - specular_sum[c] / weights);
    }
}

} // namespace shade
