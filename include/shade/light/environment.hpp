#pragma once
// shade::environment_light: uniform radiance from every direction, infinitely far away.

#include <concepts>
#include <optional>

#include <glm/geometric.hpp>

#include <shade/core/error.hpp>
#include <shade/core/frame.hpp>
#include <shade/core/math.hpp>
#include <shade/core/sampling.hpp>
#include <shade/core/types.hpp>
#include <shade/light/emission.hpp>
#include <shade/light/incident_sample.hpp>
#include <shade/light/light_sample.hpp>
#include <shade/light/sample_context.hpp>

namespace shade {

/// A constant environment light: radiance L = emitted().physical() in W/(m^2 sr) arrives
/// from every direction, from infinitely far away (a ray that leaves the scene sees L).
/// The irradiance it gives an unoccluded surface is pi L. sample_incident(p, u) chooses a
/// direction uniformly on the sphere (density 1 / (4 pi) per steradian; half the samples
/// fall below any given surface and are worth zero there). The classic sample(p, u) is
/// that direction weighted by 1 / pdf = 4 pi. For a surface point,
/// sample_incident(light_sample_context, u) samples the hemisphere above its normal instead.
template <std::floating_point T>
class environment_light {
public:
    using scalar_type = T;

    /// The environment of emission e (the default is the classic model's light,
    /// radiance pi W/(m^2 sr); from_radiance says its unit). Throws
    /// shade::invalid_parameter naming the bad emission member.
    explicit environment_light(const emission<T>& e = {}) : emission_(validated(e)) {}

    /// The environment of radiance L in W/(m^2 sr) from every direction; no ambient. Throws
    /// shade::invalid_parameter naming "radiance" (negative or not finite in a channel).
    [[nodiscard]] static environment_light from_radiance(const rgb<T>& radiance) {
        return environment_light(detail::physical_emission("radiance", radiance));
    }

    /// The emitted intensity and colours.
    [[nodiscard]] const emission<T>& emitted() const noexcept { return emission_; }
    /// The radiance L in W/(m^2 sr).
    [[nodiscard]] rgb<T> radiance() const noexcept { return emission_.physical(); }

    /// The power in W sent into a scene within a sphere of radius scene_radius: 4 pi r^2 x
    /// pi L, the sphere's area times the irradiance pi L (the light itself has no finite
    /// power). Throws shade::invalid_parameter naming "scene_radius" unless finite, >= 0.
    [[nodiscard]] rgb<T> power(T scene_radius) const {
        const T r = detail::require_scene_radius(scene_radius);
        return (T(4) * pi<T> * pi<T> * r * r) * radiance();
    }

    /// Always false: the environment is sampled many times.
    [[nodiscard]] static constexpr bool is_delta() noexcept { return false; }

    /// The physical sample at p: a uniform direction on the sphere, at infinity, radiance
    /// L, pdf 1 / (4 pi). Nothing when L is zero.
    [[nodiscard]] std::optional<incident_sample<T>> sample_incident(const vec3<T>& p,
                                                                    const vec2<T>& u) const noexcept {
        (void)p;
        if (radiance() == rgb<T>(0)) return std::nullopt;
        incident_sample<T> s;
        s.l = square_to_uniform_sphere(u);
        s.radiance = radiance();
        s.pdf = T(1) / (T(4) * pi<T>);
        return s;
    }

    /// 1 / (4 pi) for every direction (1/sr).
    [[nodiscard]] static constexpr T pdf_incident(const vec3<T>& p, const vec3<T>& l) noexcept {
        (void)p;
        (void)l;
        return T(1) / (T(4) * pi<T>);
    }

    /// L for every direction: the radiance a ray that leaves the scene along l sees.
    [[nodiscard]] rgb<T> incident_radiance(const vec3<T>& p, const vec3<T>& l) const noexcept {
        (void)p;
        (void)l;
        return radiance();
    }

    /// The physical sample for a surface point: a direction above ctx.n drawn with density
    /// cos / pi (cos = n·l; Malley's method, square_to_cosine_hemisphere), radiance L, so
    /// that L cos / pdf = pi L for every sample: the irradiance with no variance. Without
    /// a surface (ctx.n zero), sample_incident(ctx.p, u). Nothing when L is zero or the
    /// direction is exactly on the horizon.
    [[nodiscard]] std::optional<incident_sample<T>> sample_incident(const light_sample_context<T>& ctx,
                                                                    const vec2<T>& u) const noexcept {
        if (ctx.n == vec3<T>(0)) return sample_incident(ctx.p, u);
        if (radiance() == rgb<T>(0)) return std::nullopt;
        incident_sample<T> s;
        s.l = frame<T>::from_normal(ctx.n).to_world(square_to_cosine_hemisphere(u));
        s.radiance = radiance();
        // From the world direction, as pdf_incident computes it, so the two agree bit for
        // bit (what MIS weights need).
        s.pdf = pdf_incident(ctx, s.l);
        if (!(s.pdf > T(0))) return std::nullopt;
        return s;
    }

    /// The density of sample_incident(ctx, .) for the unit direction l: max(n·l, 0) / pi,
    /// or 1 / (4 pi) without a surface.
    [[nodiscard]] T pdf_incident(const light_sample_context<T>& ctx, const vec3<T>& l) const noexcept {
        if (ctx.n == vec3<T>(0)) return pdf_incident(ctx.p, l);
        const T c = glm::dot(ctx.n, l);
        return c > T(0) ? c / pi<T> : T(0);
    }

    /// The classic light sample of sample_incident(p, u) (a uniform direction), weighted by
    /// 1 / pdf = 4 pi (detail::classic_from); ambient only when L is zero.
    [[nodiscard]] light_sample<T> sample(const vec3<T>& p, const vec2<T>& u) const noexcept {
        return detail::classic_from(emission_, sample_incident(p, u));
    }

private:
    emission<T> emission_;
};

} // namespace shade
