#pragma once
// The BSDF contract: scattering models that may transmit as well as reflect. Every BRDF
// (shade::brdf, shade/brdf/brdf.hpp) satisfies it unchanged, as the reflection-only case.
//
// A BSDF is a small class with
//   * a member type `scalar_type` (float or double), and
//   * a const member `f(l, v, at)` returning rgb<scalar_type>: the BSDF value in 1/sr,
//     WITHOUT the cosine factor, in radiance mode (below), for unit directions l (toward
//     the light) and v (toward the viewer) on EITHER side of the surface. at.n() points
//     outside; the side opposite it is inside. l and v on the same side give reflection,
//     on opposite sides transmission (a BRDF returns 0 there). A delta (specular) lobe
//     adds nothing to f: it is 0 for any given pair of directions.
//
// A BSDF that can also draw directions (shade::sampled_bsdf) has
//   * `pdf(l, v, at)` -> T: the solid-angle density (1/sr) over the whole sphere with which
//     sample() draws l for this v; delta lobes add nothing to it. It is the same in both
//     transport modes (sample's choice of direction does not depend on the mode), and
//   * either `sample(v, uc, u, at, mode)` -> std::optional<bsdf_sample<T>> (a BSDF's own
//     sampler), or the BRDF sampler `sample(v, uc, u, at)` ->
//     std::optional<brdf_sample<T>>. shade::sample_bsdf calls whichever the model has and
//     always returns a bsdf_sample.
// v may be inside (a ray leaving glass). uc in [0, 1) chooses a lobe, u in [0, 1)^2 places
// the direction within it. nullopt when no direction is drawn (v on the horizon, a
// reflection-only model seen from inside, a drawn direction on the wrong side).
//
// Index of refraction. A model's eta is n_inside / n_outside, inside being the side
// opposite at.n(). A sample's eta is eta_l / eta_v, the index on l's side over the index on
// v's side: 1 for reflection; the model's eta when v is outside and l inside; 1/eta the
// other way.
//
// Transport modes (Veach 1997, "Robust Monte Carlo Methods for Light Transport
// Simulation", PhD thesis, Stanford, sec. 5.2; the same TransportMode as Pharr, Jakob,
// Humphreys 2023, "Physically Based Rendering", 4th ed., sec. 9.5.2). Along a path that
// refracts, radiance L is not invariant but L / eta^2 is (Veach, sec. 5.2), so the BSDF of
// a refracting interface is not symmetric. In radiance mode (paths traced from the camera,
// carrying radiance toward v) f includes the factor (eta_v / eta_l)^2 of a refraction,
// and Veach's eq. 5.14, with omega_i = l and omega_o = v, holds:
//
//     f(l, v) / eta_v^2 = f(v, l) / eta_l^2
//
// (eta_l and eta_v the indices on the sides of l and v). In importance mode (paths traced
// from the lights) the adjoint BSDF is used, by definition
//
//     f_importance(l, v) = f_radiance(v, l),
//
// which for a refraction is the radiance-mode value without the factor (eta_v / eta_l)^2,
// and for a reflection the same value when f is reciprocal. shade::bsdf_f evaluates either;
// sample() weighs its samples in the mode it is given. In importance mode, the expected
// weight of sample() (reflected plus transmitted) is the fraction of the energy arriving
// along v that leaves the surface: at most 1 for a model that conserves energy.
//
// Delta lobes (pbrt-v4's convention, Pharr, Jakob, Humphreys 2023, sec. 9.1.2 and 9.3):
// sample() returns the delta direction with flags containing bsdf_flags::specular, pdf the
// discrete probability of choosing that lobe (not a density), weight the lobe's throughput
// (the fraction of radiance, or importance, it carries from l to v, e.g. the Fresnel
// reflectance R of a mirror) divided by that probability, and f = throughput / |n·l|, so
// that weight = f |n·l| / pdf for every sample. (|n·l| is floored at machine epsilon in
// that division, so f stays finite for a grazing l; weight is computed without it.)
// Multiple importance sampling must not weigh a specular sample against another strategy.

#include <cmath>
#include <concepts>
#include <optional>

#include <glm/geometric.hpp>

#include <shade/brdf/brdf.hpp>
#include <shade/core/scalar.hpp>
#include <shade/core/surface_point.hpp>
#include <shade/core/types.hpp>

namespace shade {

/// Which quantity a path carries through a BSDF (see the header comment): radiance (paths
/// from the camera) or importance (paths from the lights, which use the adjoint BSDF).
enum class transport_mode {
    radiance,  ///< f(l, v) as is: the 1/eta^2 scaling of radiance through a refraction included
    importance ///< the adjoint f(v, l): no eta^2 factor on a refraction
};

/// What kind of scattering a bsdf_sample is: one of reflection and transmission, combined
/// with one of diffuse, glossy and specular (a delta lobe). Bits, after pbrt-v4's BxDFFlags
/// (Pharr, Jakob, Humphreys 2023, sec. 9.1.2); combine with | and test with the is_*
/// helpers below.
enum class bsdf_flags : unsigned {
    none = 0,
    reflection = 1u << 0,   ///< l on v's side of the surface
    transmission = 1u << 1, ///< l on the other side
    diffuse = 1u << 2,      ///< from a lobe spread over the hemisphere (e.g. Lambertian)
    glossy = 1u << 3,       ///< from a lobe with a density, concentrated around a direction
    specular = 1u << 4,     ///< from a delta lobe: pdf is a probability, not a density
    diffuse_reflection = diffuse | reflection,
    glossy_reflection = glossy | reflection,
    specular_reflection = specular | reflection,
    diffuse_transmission = diffuse | transmission,
    glossy_transmission = glossy | transmission,
    specular_transmission = specular | transmission,
};

/// The union of the bits of a and b.
[[nodiscard]] constexpr bsdf_flags operator|(bsdf_flags a, bsdf_flags b) noexcept {
    return static_cast<bsdf_flags>(static_cast<unsigned>(a) | static_cast<unsigned>(b));
}

/// The bits a and b have in common.
[[nodiscard]] constexpr bsdf_flags operator&(bsdf_flags a, bsdf_flags b) noexcept {
    return static_cast<bsdf_flags>(static_cast<unsigned>(a) & static_cast<unsigned>(b));
}

/// True when flags has every bit of bits.
[[nodiscard]] constexpr bool has_flags(bsdf_flags flags, bsdf_flags bits) noexcept {
    return (flags & bits) == bits;
}

/// True for a reflection (l on v's side).
[[nodiscard]] constexpr bool is_reflection(bsdf_flags f) noexcept { return has_flags(f, bsdf_flags::reflection); }
/// True for a transmission (l on the other side of the surface).
[[nodiscard]] constexpr bool is_transmission(bsdf_flags f) noexcept { return has_flags(f, bsdf_flags::transmission); }
/// True for a sample of a diffuse lobe.
[[nodiscard]] constexpr bool is_diffuse(bsdf_flags f) noexcept { return has_flags(f, bsdf_flags::diffuse); }
/// True for a sample of a glossy lobe.
[[nodiscard]] constexpr bool is_glossy(bsdf_flags f) noexcept { return has_flags(f, bsdf_flags::glossy); }
/// True for a sample of a delta lobe (its pdf is a probability, not a density).
[[nodiscard]] constexpr bool is_specular(bsdf_flags f) noexcept { return has_flags(f, bsdf_flags::specular); }
/// True for a sample with a density (diffuse or glossy): one that multiple importance
/// sampling may weigh against another strategy.
[[nodiscard]] constexpr bool is_non_specular(bsdf_flags f) noexcept {
    return (f & (bsdf_flags::diffuse | bsdf_flags::glossy)) != bsdf_flags::none;
}

/// A direction drawn by a BSDF's sample(): what a path tracer needs to continue the path
/// without evaluating the BSDF again (pbrt-v4's BSDFSample, Pharr, Jakob, Humphreys 2023,
/// sec. 9.1.2). For a delta lobe, see the header comment: pdf is a probability and f is
/// the throughput divided by |n·l|.
template <std::floating_point T>
struct bsdf_sample {
    using scalar_type = T;

    vec3<T> l{0, 0, 1};                  ///< sampled unit direction toward the light, world space, either side
    rgb<T> f{0};                         ///< the BSDF value at l in the sample's mode, 1/sr, without the cosine
    T pdf{0};                            ///< solid-angle density of l (1/sr), or the lobe's probability if specular; > 0
    rgb<T> weight{0};                    ///< f |n·l| / pdf: the Monte-Carlo weight (throughput) of this sample
    bsdf_flags flags{bsdf_flags::none};  ///< reflection or transmission; diffuse, glossy or specular
    T eta{1};                            ///< eta_l / eta_v, the relative index crossed: 1 for reflection
};

/// B is a BSDF: `b.f(l, v, at)` returns the BSDF value (1/sr, no cosine, radiance mode) as
/// linear RGB for l and v on either side of the surface. The same requirement as
/// shade::brdf; what differs is the promise: a BRDF's f is 0 unless both are above.
template <class B>
concept bsdf = has_scalar_type<B> &&
    requires(const B& b, const vec3<typename B::scalar_type>& w,
             const surface_point<typename B::scalar_type>& at) {
        { b.f(w, w, at) } -> std::same_as<rgb<typename B::scalar_type>>;
    };

/// B has a BSDF's own sampler: `b.sample(v, uc, u, at, mode)` returns
/// std::optional<bsdf_sample<T>> and `b.pdf(l, v, at)` the density of l.
template <class B>
concept bsdf_sampler = bsdf<B> &&
    requires(const B& b, const vec3<typename B::scalar_type>& w, typename B::scalar_type uc,
             const vec2<typename B::scalar_type>& u,
             const surface_point<typename B::scalar_type>& at, transport_mode mode) {
        { b.sample(w, uc, u, at, mode) } -> std::same_as<std::optional<bsdf_sample<typename B::scalar_type>>>;
        { b.pdf(w, w, at) } -> std::same_as<typename B::scalar_type>;
    };

/// B is a BSDF that can draw directions and report their density: it has a BSDF's own
/// sampler (shade::bsdf_sampler) or is a sampled BRDF (shade::sampled_brdf). Call
/// shade::sample_bsdf to draw from either as a bsdf_sample.
template <class B>
concept sampled_bsdf = bsdf<B> && (bsdf_sampler<B> || sampled_brdf<B>);

/// The bsdf_sample of a BRDF's sample: the same l, f, pdf and weight; flags
/// glossy_reflection (a brdf_sample does not say which lobe drew it, and glossy, a lobe
/// with a density, is the kind that assumes least about it), eta 1.
template <std::floating_point T>
[[nodiscard]] constexpr bsdf_sample<T> to_bsdf_sample(const brdf_sample<T>& s) noexcept {
    return bsdf_sample<T>{s.l, s.f, s.pdf, s.weight, bsdf_flags::glossy_reflection, T(1)};
}

/// The value of BSDF b in the given transport mode, 1/sr without the cosine:
/// b.f(l, v, at) in radiance mode, the adjoint b.f(v, l, at) in importance mode (see the
/// header comment). For every model, so f_importance(l, v) = f_radiance(v, l) exactly.
/// Throws only what b.f throws.
template <bsdf B>
[[nodiscard]] rgb<scalar_of<B>> bsdf_f(const B& b, const vec3<scalar_of<B>>& l, const vec3<scalar_of<B>>& v,
                                       const surface_point<scalar_of<B>>& at, transport_mode mode) {
    return mode == transport_mode::radiance ? b.f(l, v, at) : b.f(v, l, at);
}

/// Draws a direction l from b for the view v in the given transport mode, as a
/// bsdf_sample: b's own sample(v, uc, u, at, mode) when it has one; for a sampled BRDF,
/// its sample(v, uc, u, at) as to_bsdf_sample makes it, in importance mode with f the
/// adjoint b.f(v, l, at) and the weight recomputed from it (the density is the same).
/// nullopt when b draws nothing. Throws only what b's sample or f throws.
template <sampled_bsdf B>
[[nodiscard]] std::optional<bsdf_sample<scalar_of<B>>>
sample_bsdf(const B& b, const vec3<scalar_of<B>>& v, scalar_of<B> uc, const vec2<scalar_of<B>>& u,
            const surface_point<scalar_of<B>>& at, transport_mode mode) {
    using T = scalar_of<B>;
    if constexpr (bsdf_sampler<B>) {
        return b.sample(v, uc, u, at, mode);
    } else {
        const std::optional<brdf_sample<T>> s = b.sample(v, uc, u, at);
        if (!s) return std::nullopt;
        if (mode == transport_mode::radiance) return to_bsdf_sample(*s);
        const std::optional<brdf_sample<T>> adjoint =
            detail::make_brdf_sample(s->l, b.f(v, s->l, at), s->pdf, std::abs(glm::dot(at.n(), s->l)));
        if (!adjoint) return std::nullopt;
        return to_bsdf_sample(*adjoint);
    }
}

} // namespace shade
