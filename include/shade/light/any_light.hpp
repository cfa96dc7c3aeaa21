#pragma once
// shade::any_light: one value that holds any of shade's lights, for heterogeneous light
// lists (std::vector<any_light<T>>).

#include <concepts>
#include <optional>
#include <utility>
#include <variant>

#include <shade/core/types.hpp>
#include <shade/light/area.hpp>
#include <shade/light/directional.hpp>
#include <shade/light/disk.hpp>
#include <shade/light/environment.hpp>
#include <shade/light/incident_sample.hpp>
#include <shade/light/light.hpp>
#include <shade/light/light_sample.hpp>
#include <shade/light/point.hpp>
#include <shade/light/sphere.hpp>
#include <shade/light/spot.hpp>

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
                     disk_light<T>, sphere_light<T>, environment_light<T>>;

    any_light(const directional_light<T>& l) : light_(l) {} // NOLINT: implicit by design
    any_light(const point_light<T>& l) : light_(l) {}       // NOLINT
    any_light(const spot_light<T>& l) : light_(l) {}        // NOLINT
    any_light(const area_light<T>& l) : light_(l) {}        // NOLINT
    any_light(const disk_light<T>& l) : light_(l) {}        // NOLINT
    any_light(const sphere_light<T>& l) : light_(l) {}      // NOLINT
    any_light(const environment_light<T>& l) : light_(l) {} // NOLINT

    /// The held light's sample at p for sample pair u (see shade::light).
    [[nodiscard]] light_sample<T> sample(const vec3<T>& p, const vec2<T>& u) const {
        return std::visit([&](const auto& l) { return l.sample(p, u); }, light_);
    }

    /// The held light's physical sample at p (see shade::emitter).
    [[nodiscard]] std::optional<incident_sample<T>> sample_incident(const vec3<T>& p,
                                                                    const vec2<T>& u) const {
        return std::visit([&](const auto& l) { return l.sample_incident(p, u); }, light_);
    }

    /// The held light's density for direction w at p (see shade::emitter).
    [[nodiscard]] T pdf_incident(const vec3<T>& p, const vec3<T>& w) const {
        return std::visit([&](const auto& l) { return l.pdf_incident(p, w); }, light_);
    }

    /// The radiance arriving at p along w from the held light (see shade::emitter).
    [[nodiscard]] rgb<T> incident_radiance(const vec3<T>& p, const vec3<T>& w) const {
        return std::visit([&](const auto& l) { return l.incident_radiance(p, w); }, light_);
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
