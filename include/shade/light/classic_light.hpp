#pragma once
// shade::classic_light: the classic lighting model's light (shade::light) made from any
// physical light (shade::emitter), by shade::classic_sample.

#include <concepts>
#include <utility>

#include <shade/core/error.hpp>
#include <shade/core/math.hpp>
#include <shade/core/types.hpp>
#include <shade/light/light.hpp>
#include <shade/light/light_sample.hpp>
#include <shade/light/sample_context.hpp>

namespace shade {

/// What the classic mode adds to an emitter's physical samples: an ambient colour and
/// tints of the diffuse and specular colours (linear RGB, each channel finite and >= 0).
/// The defaults (no ambient, white tints) give the classic sample that carries exactly
/// the emitter's light.
template <std::floating_point T>
struct classic_colours {
    using scalar_type = T;

    rgb<T> ambient{0, 0, 0};  ///< ambient colour I_a of every sample (light_sample units)
    rgb<T> diffuse{1, 1, 1};  ///< per-channel factor of the diffuse colour
    rgb<T> specular{1, 1, 1}; ///< per-channel factor of the specular colour
};

/// Returns c unchanged after checking it; throws shade::invalid_parameter naming
/// "ambient", "diffuse" or "specular" if that member is negative or not finite.
template <std::floating_point T>
[[nodiscard]] classic_colours<T> validated(const classic_colours<T>& c) {
    (void)require_non_negative("ambient", c.ambient);
    (void)require_non_negative("diffuse", c.diffuse);
    (void)require_non_negative("specular", c.specular);
    return c;
}

/// The classic light sample of emitter e at p for the sample pair u: the physical sample
/// s = e.sample_incident(p, u) in the units of shade::light_sample, whose colours are the
/// radiance a white Lambertian surface facing the light reflects, E / pi for an
/// irradiance E at normal incidence. One sample estimates that irradiance as
/// s.radiance / s.pdf (for a delta light s.radiance is E and s.pdf is 1), so
///   diffuse  = c.diffuse  x s.radiance / (pi s.pdf),
///   specular = c.specular x s.radiance / (pi s.pdf),
///   ambient  = c.ambient,
/// with l and distance those of s. Averaged over u, a shader linear in the light's
/// colours (every lit BRDF) then converges to the classic contribution of the light, as
/// for shade::area_light's estimator; for a delta light one sample is exact. Where e
/// returns no sample, or the colours are not finite, the sample carries the ambient
/// colour only (l and distance are still set when there is a sample).
/// For a shade light whose emission has equal diffuse and specular colours, this is its
/// own sample(p, u) (same light, up to rounding), with c.ambient = intensity x ambient.
/// Precondition: c validated (shade::validated).
template <emitter E>
[[nodiscard]] light_sample<typename E::scalar_type> classic_sample(const E& e,
                                                                   const classic_colours<typename E::scalar_type>& c,
                                                                   const vec3<typename E::scalar_type>& p,
                                                                   const vec2<typename E::scalar_type>& u) {
    using T = typename E::scalar_type;
    light_sample<T> out;
    out.ambient = c.ambient;
    const auto s = e.sample_incident(p, u);
    if (!s) return out;
    out.l = s->l;
    out.distance = s->distance;
    const rgb<T> white = s->radiance / (pi<T> * s->pdf);
    const rgb<T> diffuse = c.diffuse * white;
    const rgb<T> specular = c.specular * white;
    if (!(s->pdf > T(0)) || !is_finite(diffuse) || !is_finite(specular)) return out;
    out.diffuse = diffuse;
    out.specular = specular;
    return out;
}

/// A shade::light made of a shade::emitter and the classic colours: sample(p, u) is
/// shade::classic_sample(emitter(), colours(), p, u) and is_delta() the emitter's. This
/// is how a light written only in physical units (yours) is used with the classic
/// shading (shade::lit, shade::sum_over_lights). It is still a shade::emitter: the
/// physical members forward to the emitter, so one light list serves both modes.
template <emitter E>
class classic_light {
public:
    using scalar_type = typename E::scalar_type;
    using emitter_type = E;

    /// The emitter e with classic colours c. Throws shade::invalid_parameter naming
    /// "ambient", "diffuse" or "specular" (see shade::validated).
    explicit classic_light(E e, const classic_colours<scalar_type>& c = {})
        : emitter_(std::move(e)), colours_(validated(c)) {}

    /// The physical light.
    [[nodiscard]] const E& emitter() const noexcept { return emitter_; }
    /// The classic colours.
    [[nodiscard]] const classic_colours<scalar_type>& colours() const noexcept { return colours_; }

    /// The classic sample at p for sample pair u (shade::classic_sample).
    [[nodiscard]] light_sample<scalar_type> sample(const vec3<scalar_type>& p, const vec2<scalar_type>& u) const {
        return classic_sample(emitter_, colours_, p, u);
    }

    /// Whether the emitter is a delta light (one sample is exact).
    [[nodiscard]] bool is_delta() const { return emitter_.is_delta(); }

    /// The emitter's physical sample at p, or for a surface point ctx (shade::emitter).
    [[nodiscard]] auto sample_incident(const vec3<scalar_type>& p, const vec2<scalar_type>& u) const {
        return emitter_.sample_incident(p, u);
    }
    [[nodiscard]] auto sample_incident(const light_sample_context<scalar_type>& ctx, const vec2<scalar_type>& u) const {
        return emitter_.sample_incident(ctx, u);
    }
    /// The emitter's density for the unit direction w, at p or for ctx (shade::emitter).
    [[nodiscard]] scalar_type pdf_incident(const vec3<scalar_type>& p, const vec3<scalar_type>& w) const {
        return emitter_.pdf_incident(p, w);
    }
    [[nodiscard]] scalar_type pdf_incident(const light_sample_context<scalar_type>& ctx,
                                           const vec3<scalar_type>& w) const {
        return emitter_.pdf_incident(ctx, w);
    }
    /// The radiance arriving at p along w from the emitter (shade::emitter).
    [[nodiscard]] rgb<scalar_type> incident_radiance(const vec3<scalar_type>& p, const vec3<scalar_type>& w) const {
        return emitter_.incident_radiance(p, w);
    }
    /// The emitter's radiant power in W (shade::emitter).
    [[nodiscard]] rgb<scalar_type> power(scalar_type scene_radius) const { return emitter_.power(scene_radius); }

private:
    E emitter_;
    classic_colours<scalar_type> colours_;
};

} // namespace shade
