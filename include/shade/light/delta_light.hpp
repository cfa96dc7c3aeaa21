#pragma once
// shade::detail::delta_light: what every delta light (point, spot, directional) answers
// the same way, written once.

#include <concepts>
#include <optional>

#include <shade/core/types.hpp>
#include <shade/light/incident_sample.hpp>
#include <shade/light/light_sample.hpp>
#include <shade/light/sample_context.hpp>

namespace shade::detail {

/// Base of the delta lights (CRTP: Light derives from delta_light<Light, T> and defines
/// sample(p) and sample_incident(p); it brings the base's sample and sample_incident
/// into scope with using-declarations). A delta light sends light along one direction per
/// shaded point, so its sample pair u is ignored, no direction chosen by another strategy
/// (a BRDF sample) ever reaches it, and its pdf for any given direction is 0.
template <class Light, std::floating_point T>
class delta_light {
public:
    using scalar_type = T;

    /// Always true: one sample is exact.
    [[nodiscard]] static constexpr bool is_delta() noexcept { return true; }

    /// The classic sample(p); u is ignored (shade::light, shared with area lights).
    [[nodiscard]] light_sample<T> sample(const vec3<T>& p, const vec2<T>& u) const noexcept {
        (void)u;
        return self().sample(p);
    }

    /// The physical sample_incident(p); u is ignored (shade::emitter).
    [[nodiscard]] std::optional<incident_sample<T>> sample_incident(const vec3<T>& p,
                                                                    const vec2<T>& u) const noexcept {
        (void)u;
        return self().sample_incident(p);
    }

    /// sample_incident(ctx.p): the surface does not change a delta light's sample.
    [[nodiscard]] std::optional<incident_sample<T>> sample_incident(const light_sample_context<T>& ctx,
                                                                    const vec2<T>& u) const noexcept {
        (void)u;
        return self().sample_incident(ctx.p);
    }

    /// 0, as pdf_incident(ctx.p, l).
    [[nodiscard]] static constexpr T pdf_incident(const light_sample_context<T>& ctx, const vec3<T>& l) noexcept {
        (void)ctx;
        (void)l;
        return T(0);
    }

    /// self().power(), the same for every scene_radius (shade::emitter's uniform form; the
    /// directional light has its own). Throws shade::invalid_parameter naming
    /// "scene_radius" unless it is finite and >= 0.
    [[nodiscard]] rgb<T> power(T scene_radius) const {
        (void)require_scene_radius(scene_radius);
        return self().power();
    }

    /// 0: a given direction has probability zero of being the light's one direction.
    [[nodiscard]] static constexpr T pdf_incident(const vec3<T>& p, const vec3<T>& l) noexcept {
        (void)p;
        (void)l;
        return T(0);
    }

    /// 0: a ray along a given direction never meets a delta light.
    [[nodiscard]] static constexpr rgb<T> incident_radiance(const vec3<T>& p, const vec3<T>& l) noexcept {
        (void)p;
        (void)l;
        return rgb<T>(0);
    }

private:
    [[nodiscard]] const Light& self() const noexcept { return static_cast<const Light&>(*this); }
};

} // namespace shade::detail
