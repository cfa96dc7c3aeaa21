#pragma once
// shade::any_light: one value that holds any of shade's lights, for heterogeneous light
// lists (std::vector<any_light<T>>).

#include <concepts>
#include <optional>
#include <utility>
#include <variant>

#include <shade/core/math.hpp>
#include <shade/core/types.hpp>
#include <shade/geometry/hit.hpp>
#include <shade/geometry/ray.hpp>
#include <shade/light/area.hpp>
#include <shade/light/directional.hpp>
#include <shade/light/disk.hpp>
#include <shade/light/environment.hpp>
#include <shade/light/incident_sample.hpp>
#include <shade/light/light.hpp>
#include <shade/light/light_sample.hpp>
#include <shade/light/point.hpp>
#include <shade/light/sample_context.hpp>
#include <shade/light/sphere.hpp>
#include <shade/light/spot.hpp>
#include <shade/light/triangle.hpp>

namespace shade {

/// Any of shade's lights, held by value in a std::variant, so that a scene's lights fit in
/// one std::vector<any_light<T>>. It is itself a shade::light and a shade::emitter; every
/// call dispatches to the held light with std::visit. Implicitly constructible from each
/// light.
template <std::floating_point T>
class any_light {
public:
    using scalar_type = T;
    /// The variant of all light types.
    using variant_type =
        std::variant<directional_light<T>, point_light<T>, spot_light<T>, area_light<T>,
                     disk_light<T>, sphere_light<T>, environment_light<T>, triangle_light<T>>;

    any_light(const directional_light<T>& l) : light_(l) {} // NOLINT: implicit by design
    any_light(const point_light<T>& l) : light_(l) {}       // NOLINT
    any_light(const spot_light<T>& l) : light_(l) {}        // NOLINT
    any_light(const area_light<T>& l) : light_(l) {}        // NOLINT
    any_light(const disk_light<T>& l) : light_(l) {}        // NOLINT
    any_light(const sphere_light<T>& l) : light_(l) {}      // NOLINT
    any_light(const environment_light<T>& l) : light_(l) {} // NOLINT
    any_light(const triangle_light<T>& l) : light_(l) {}    // NOLINT

    /// The held light's sample at p for sample pair u (see shade::light).
    [[nodiscard]] light_sample<T> sample(const vec3<T>& p, const vec2<T>& u) const {
        return std::visit([&](const auto& l) { return l.sample(p, u); }, light_);
    }

    /// The held light's physical sample at p (see shade::emitter).
    [[nodiscard]] std::optional<incident_sample<T>> sample_incident(const vec3<T>& p,
                                                                    const vec2<T>& u) const {
        return std::visit([&](const auto& l) { return l.sample_incident(p, u); }, light_);
    }

    /// The held light's physical sample for a surface point (shade::light_sample_context):
    /// lights that use the surface (the constant environment) take it, the others sample
    /// as for ctx.p (see shade::emitter).
    [[nodiscard]] std::optional<incident_sample<T>> sample_incident(const light_sample_context<T>& ctx,
                                                                    const vec2<T>& u) const {
        return std::visit([&](const auto& l) { return l.sample_incident(ctx, u); }, light_);
    }

    /// The density of sample_incident(ctx, .) for the unit direction w.
    [[nodiscard]] T pdf_incident(const light_sample_context<T>& ctx, const vec3<T>& w) const {
        return std::visit([&](const auto& l) { return l.pdf_incident(ctx, w); }, light_);
    }

    /// The held light's density for direction w at p (see shade::emitter).
    [[nodiscard]] T pdf_incident(const vec3<T>& p, const vec3<T>& w) const {
        return std::visit([&](const auto& l) { return l.pdf_incident(p, w); }, light_);
    }

    /// The radiance arriving at p along w from the held light (see shade::emitter).
    [[nodiscard]] rgb<T> incident_radiance(const vec3<T>& p, const vec3<T>& w) const {
        return std::visit([&](const auto& l) { return l.incident_radiance(p, w); }, light_);
    }

    /// Where r meets the held light's surface (rectangle, disk, sphere and triangle lights),
    /// or nothing: point, spot and directional lights have no surface, and the environment
    /// is met by every ray that leaves the scene, not by intersection. For a path tracer
    /// whose BSDF-sampled ray may have hit an emitter.
    [[nodiscard]] std::optional<hit<T>> intersect(const ray<T>& r) const {
        return std::visit(
            [&](const auto& l) -> std::optional<hit<T>> {
                if constexpr (requires { l.intersect(r); })
                    return l.intersect(r);
                else
                    return std::nullopt;
            },
            light_);
    }

    /// The radiance the held light emits from h, a point of its surface found by
    /// intersect(), toward the unit direction w (pointing away from the surface); 0 for
    /// lights without a surface.
    [[nodiscard]] rgb<T> radiance(const hit<T>& h, const vec3<T>& w) const {
        return std::visit(
            [&](const auto& l) -> rgb<T> {
                if constexpr (requires { l.intersect(ray<T>{}); })
                    return l.radiance(h, w);
                else
                    return rgb<T>(0);
            },
            light_);
    }

    /// pdf_incident(p, l) when the caller already has h = intersect(ray{p, l}) with l unit:
    /// the same density without a second intersection (0 for lights without a surface).
    [[nodiscard]] T pdf_incident(const vec3<T>& p, const vec3<T>& l, const hit<T>& h) const {
        return std::visit(
            [&](const auto& light) -> T {
                if constexpr (requires { light.intersect(ray<T>{}); })
                    return light.pdf_incident(p, l, h);
                else
                    return T(0);
            },
            light_);
    }

    /// The radiant power in W. Lights at infinity send their power through the scene:
    /// `scene_radius` is the radius of a sphere around it, through whose cross-section
    /// pi r^2 a directional light of irradiance E sends pi r^2 E, and onto which an
    /// environment of radiance L sends 4 pi r^2 pi L (every point of the sphere receives
    /// pi L); other lights ignore it. Point: 4 pi I; spot: its cone's share of that; area
    /// lights: pi L A per emitting side. Throws shade::invalid_parameter naming
    /// "scene_radius" unless it is finite and >= 0.
    [[nodiscard]] rgb<T> power(T scene_radius) const {
        return std::visit([&](const auto& l) { return l.power(scene_radius); }, light_);
    }

    /// Whether the held light is a delta light.
    [[nodiscard]] bool is_delta() const {
        return std::visit([](const auto& l) { return l.is_delta(); }, light_);
    }

    /// The underlying variant, for std::visit with the concrete light type (e.g. to
    /// sample an area light with its own stratification).
    [[nodiscard]] const variant_type& get() const noexcept { return light_; }
    /// f(light) with the held light as its concrete type (std::visit), returning what f
    /// returns: a loop over many samples of one light inside f dispatches once, not per
    /// sample (shade::sum_over_lights does this).
    template <class F>
    decltype(auto) visit(F&& f) const {
        return std::visit(std::forward<F>(f), light_);
    }

private:
    variant_type light_;
};

} // namespace shade
