#pragma once
// shade::disk_light: a round, flat emitter (a disk), sampled uniformly by area.

#include <cmath>
#include <concepts>
#include <optional>

#include <glm/geometric.hpp>

#include <shade/core/error.hpp>
#include <shade/core/frame.hpp>
#include <shade/core/math.hpp>
#include <shade/core/sampling.hpp>
#include <shade/core/types.hpp>
#include <shade/geometry/hit.hpp>
#include <shade/geometry/plane.hpp>
#include <shade/geometry/ray.hpp>
#include <shade/light/area_emitter.hpp>
#include <shade/light/emission.hpp>
#include <shade/light/incident_sample.hpp>
#include <shade/light/light_sample.hpp>

namespace shade {

/// A disk light: the disk of radius R about `center` perpendicular to the unit `normal`,
/// emitting toward the side the normal points to (or both sides). A Lambertian emitter
/// of radiance L = emitted().physical() in W/(m^2 sr), area pi R^2, power pi L A per
/// emitting side.
///
/// sample_incident(p, u) maps u to the disk with the concentric map (Shirley, Chiu 1997,
/// uniform by area: density 1 / A) and reports the solid-angle density r^2 / (A cos_light).
/// The classic sample(p, u) is the same point weighted by 1 / pdf (see shade::area_light's
/// estimator). As geometry: hits have uv = ((1 + x / R) / 2, (1 + y / R) / 2) for the
/// point center + x t + y b, with (t, b, normal) = frame::from_normal(normal), so
/// dp/du = 2 R t.
template <std::floating_point T>
class disk_light : public detail::area_emitter<disk_light<T>, T> {
public:
    using scalar_type = T;
    using detail::area_emitter<disk_light<T>, T>::radiance;
    using detail::area_emitter<disk_light<T>, T>::sample_incident;
    using detail::area_emitter<disk_light<T>, T>::pdf_incident;

    /// The default emission is the classic model's light (radiance pi W/(m^2 sr));
    /// from_radiance and from_power say their units. Throws shade::invalid_parameter
    /// naming "center" (non-finite), "normal" (zero or non-finite), "radius" (not finite
    /// and > 0), "sides" or the bad emission member.
    disk_light(const vec3<T>& center, const vec3<T>& normal, T radius, const emission<T>& e = {},
               sidedness sides = sidedness::one_sided)
        : center_(require_finite("center", center)),
          axes_(frame<T>::from_normal(require_direction("normal", normal))),
          radius_(require_positive("radius", radius)), emission_(validated(e)),
          sides_(detail::require_sidedness(sides)) {
        area_ = pi<T> * radius_ * radius_;
        if (!std::isfinite(area_))
            throw invalid_parameter("radius", "must give a finite area", detail::to_text(radius));
    }

    /// The disk (geometry and sides as for the constructor) of radiance L in W/(m^2 sr)
    /// (from_radiance), or of power Phi in W, all emitting sides together (from_power:
    /// L = Phi / (pi A) one-sided, Phi / (2 pi A) two-sided, A = pi R^2); no ambient.
    /// Throw shade::invalid_parameter naming what the constructor names, "radiance" or
    /// "power" (as shade::area_light's).
    [[nodiscard]] static disk_light from_radiance(const vec3<T>& center, const vec3<T>& normal, T radius,
                                                  const rgb<T>& radiance, sidedness sides = sidedness::one_sided) {
        return disk_light(center, normal, radius, detail::physical_emission("radiance", radiance), sides);
    }
    [[nodiscard]] static disk_light from_power(const vec3<T>& center, const vec3<T>& normal, T radius,
                                               const rgb<T>& power, sidedness sides = sidedness::one_sided) {
        disk_light out(center, normal, radius, emission<T>{}, sides);
        out.emission_ = out.emission_of_power(power);
        return out;
    }

    /// The centre.
    [[nodiscard]] const vec3<T>& center() const noexcept { return center_; }
    /// The unit normal: the emitting side if one-sided.
    [[nodiscard]] const vec3<T>& normal() const noexcept { return axes_.n; }
    /// The radius.
    [[nodiscard]] T radius() const noexcept { return radius_; }
    /// The area pi R^2.
    [[nodiscard]] T area() const noexcept { return area_; }
    /// The emitted intensity and colours.
    [[nodiscard]] const emission<T>& emitted() const noexcept { return emission_; }
    /// Whether one or both sides emit.
    [[nodiscard]] sidedness sides() const noexcept { return sides_; }

    /// The point of the disk at sample pair u in [0,1)^2 (concentric map).
    [[nodiscard]] vec3<T> point_at(const vec2<T>& u) const noexcept {
        const vec2<T> d = square_to_concentric_disk(u);
        return center_ + radius_ * (d.x * axes_.t + d.y * axes_.b);
    }

    /// The physical sample at p toward point_at(u) (see the class comment). Nothing for p
    /// on the light, the back of a one-sided light or an overflowing density.
    [[nodiscard]] std::optional<incident_sample<T>> sample_incident(const vec3<T>& p,
                                                                    const vec2<T>& u) const noexcept {
        return detail::area_incident(p, point_at(u), axes_.n, area_, this->radiance(), sides_);
    }

    /// The classic light sample toward point_at(u), weighted by 1 / pdf.
    [[nodiscard]] light_sample<T> sample(const vec3<T>& p, const vec2<T>& u) const noexcept {
        return detail::classic_from(emission_, sample_incident(p, u));
    }

    /// The hit of r with the disk, either side (uv and dpdu: see the class comment).
    [[nodiscard]] std::optional<hit<T>> intersect(const ray<T>& r) const noexcept {
        std::optional<hit<T>> out;
        const T n_dot_d = glm::dot(axes_.n, r.direction);
        if (n_dot_d == T(0)) return out;
        const T t = glm::dot(axes_.n, center_ - r.origin) / n_dot_d;
        if (!(t >= r.t_min && t <= r.t_max) || !std::isfinite(t)) return out;
        const vec3<T> p = r.at(t);
        const T x = glm::dot(p - center_, axes_.t);
        const T y = glm::dot(p - center_, axes_.b);
        if (!(x * x + y * y <= radius_ * radius_)) return out;
        out.emplace();
        out->t = t;
        out->p = p;
        out->n = axes_.n;
        out->p_error = detail::plane_hit_error(r.origin, center_, t, r.direction);
        out->front_face = n_dot_d < T(0);
        out->uv = vec2<T>((T(1) + x / radius_) / T(2), (T(1) + y / radius_) / T(2));
        out->dpdu = (T(2) * radius_) * axes_.t;
        return out;
    }

private:
    vec3<T> center_;
    frame<T> axes_;
    T radius_;
    emission<T> emission_;
    sidedness sides_;
    T area_ = T(0);
};

} // namespace shade
