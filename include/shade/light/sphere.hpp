#pragma once
// shade::sphere_light: a spherical emitter, sampled by the cone of directions it subtends.

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
#include <shade/geometry/ray.hpp>
#include <shade/geometry/sphere.hpp>
#include <shade/light/area_emitter.hpp>
#include <shade/light/emission.hpp>
#include <shade/light/incident_sample.hpp>
#include <shade/light/light_sample.hpp>

namespace shade {

/// A sphere light: the sphere of radius R about `center`, a Lambertian emitter of
/// radiance L = emitted().physical() in W/(m^2 sr) from its outside (one_sided) or from
/// both sides (two_sided: also into its inside, e.g. a closed room lit by its walls);
/// area 4 pi R^2, power pi L A per emitting side. As geometry it is a shade::sphere (same
/// uv and dp/du).
///
/// Sampling from a point p outside the sphere (|p - c| = d > R) chooses a direction
/// uniformly inside the cone of directions that meet the sphere, of half-angle theta_max
/// with sin(theta_max) = R / d, and takes the first point of the sphere along it (Shirley,
/// Wang, Zimmerman 1996, "Monte Carlo Techniques for Direct Lighting Calculations", ACM TOG
/// 15(1), §4.2): pdf = 1 / (2 pi (1 - cos theta_max)) per steradian, no sample wasted on
/// the hidden half. 1 - cos theta_max is formed as sin^2 / (1 + cos), without
/// cancellation for small, far spheres. From a point inside or on the sphere the point
/// is chosen uniformly by area, pdf r^2 / (A cos_light).
template <std::floating_point T>
class sphere_light : public detail::area_emitter<sphere_light<T>, T> {
    using base = detail::area_emitter<sphere_light<T>, T>;

public:
    using scalar_type = T;
    using base::radiance;
    using base::sample_incident;
    using base::pdf_incident;

    /// The default emission is the classic model's light (radiance pi W/(m^2 sr));
    /// from_radiance and from_power say their units. Throws shade::invalid_parameter
    /// naming "center" (non-finite), "radius" (not finite and > 0), "sides" or the bad
    /// emission member.
    sphere_light(const vec3<T>& center, T radius, const emission<T>& e = {},
                 sidedness sides = sidedness::one_sided)
        : shape_(center, radius), emission_(validated(e)), sides_(detail::require_sidedness(sides)) {
        area_ = T(4) * pi<T> * radius * radius;
        if (!std::isfinite(area_))
            throw invalid_parameter("radius", "must give a finite area", detail::to_text(radius));
    }

    /// The sphere (geometry and sides as for the constructor) of radiance L in W/(m^2 sr)
    /// (from_radiance), or of power Phi in W, all emitting sides together (from_power:
    /// L = Phi / (pi A) one-sided, Phi / (2 pi A) two-sided, A = 4 pi R^2); no ambient.
    /// Throw shade::invalid_parameter naming what the constructor names, "radiance" or
    /// "power" (as shade::area_light's).
    [[nodiscard]] static sphere_light from_radiance(const vec3<T>& center, T radius, const rgb<T>& radiance,
                                                    sidedness sides = sidedness::one_sided) {
        return sphere_light(center, radius, detail::physical_emission("radiance", radiance), sides);
    }
    [[nodiscard]] static sphere_light from_power(const vec3<T>& center, T radius, const rgb<T>& power,
                                                 sidedness sides = sidedness::one_sided) {
        sphere_light out(center, radius, emission<T>{}, sides);
        out.emission_ = out.emission_of_power(power);
        return out;
    }

    /// The sphere.
    [[nodiscard]] const sphere<T>& shape() const noexcept { return shape_; }
    /// The centre.
    [[nodiscard]] const vec3<T>& center() const noexcept { return shape_.center(); }
    /// The radius.
    [[nodiscard]] T radius() const noexcept { return shape_.radius(); }
    /// The area 4 pi R^2.
    [[nodiscard]] T area() const noexcept { return area_; }
    /// The emitted intensity and colours.
    [[nodiscard]] const emission<T>& emitted() const noexcept { return emission_; }
    /// Whether the outside or both sides emit.
    [[nodiscard]] sidedness sides() const noexcept { return sides_; }

    /// The physical sample at p (see the class comment). Nothing for a sample worth zero
    /// (from inside, the inner side of a one-sided sphere does not emit), an overflowing
    /// density, or a p outside so close to the surface that the distance underflows to 0.
    [[nodiscard]] std::optional<incident_sample<T>> sample_incident(const vec3<T>& p,
                                                                    const vec2<T>& u) const noexcept {
        const cone c = cone_from(p);
        if (!c.outside) {
            const vec3<T> n_x = square_to_uniform_sphere(u);
            return detail::area_incident(p, vec3<T>(center() + radius() * n_x), n_x, area_,
                                         this->radiance(), sides_);
        }
        const vec3<T> local = square_to_uniform_cone(u, c.one_minus_cos_max);
        const frame<T> f = frame<T>::from_normal(c.axis);
        const vec3<T> l = glm::normalize(local.x * f.t + local.y * f.b + local.z * f.n);
        // Distance to the near side along l: d cos - sqrt(R^2 - d^2 sin^2), with
        // d^2 sin^2 = |cross(l, c - p)|^2 (no cancellation); the max(0, .) absorbs
        // rounding at the cone's edge, where the ray grazes the sphere. Since
        // (d cos)^2 - (R^2 - d^2 sin^2) = d^2 - R^2, it is evaluated as
        // (d - R) ((d + R) / (d cos + sqrt(R^2 - d^2 sin^2))): without the cancellation of
        // the difference when p is close to the surface, without d^2 (which could
        // overflow), and > 0 for every p outside (d > R) unless the product underflows,
        // in which case there is no sample.
        const vec3<T> to_center = center() - p;
        const vec3<T> perpendicular = glm::cross(l, to_center);
        const T along = glm::dot(l, to_center);
        const T chord2 = radius() * radius() - glm::dot(perpendicular, perpendicular);
        incident_sample<T> s;
        s.l = l;
        s.distance = (c.distance - radius()) *
                     ((c.distance + radius()) / (along + std::sqrt(chord2 > T(0) ? chord2 : T(0))));
        if (!(s.distance > T(0)) || !std::isfinite(s.distance)) return std::nullopt;
        s.radiance = this->radiance();
        s.pdf = T(1) / (T(2) * pi<T> * c.one_minus_cos_max);
        if (!std::isfinite(s.pdf)) return std::nullopt;
        return s;
    }

    /// The solid-angle density of sample_incident choosing l at p (1/sr): the cone's
    /// 1 / (2 pi (1 - cos theta_max)) when p is outside and the ray (p, l) meets the
    /// sphere, r^2 / (A cos_light) at the ray's first point when p is inside, else 0.
    [[nodiscard]] T pdf_incident(const vec3<T>& p, const vec3<T>& l) const noexcept {
        const cone c = cone_from(p);
        if (!c.outside) return base::pdf_incident(p, l);
        const vec3<T> to_center = center() - p;
        const vec3<T> perpendicular = glm::cross(l, to_center);
        if (!(glm::dot(l, to_center) > T(0)) ||
            !(glm::dot(perpendicular, perpendicular) <= radius() * radius()))
            return T(0);
        const T pdf = T(1) / (T(2) * pi<T> * c.one_minus_cos_max);
        return std::isfinite(pdf) ? pdf : T(0);
    }

    /// pdf_incident(p, l) when the caller already has h = intersect(ray{p, l}) (l unit): the
    /// cone's density from outside (the ray is known to meet the sphere), the area density
    /// at h from inside; no second intersection.
    [[nodiscard]] T pdf_incident(const vec3<T>& p, const vec3<T>& l, const hit<T>& h) const noexcept {
        const cone c = cone_from(p);
        if (!c.outside) return base::pdf_incident(p, l, h);
        const T pdf = T(1) / (T(2) * pi<T> * c.one_minus_cos_max);
        return std::isfinite(pdf) ? pdf : T(0);
    }

    /// The classic light sample of sample_incident(p, u), weighted by 1 / pdf.
    [[nodiscard]] light_sample<T> sample(const vec3<T>& p, const vec2<T>& u) const noexcept {
        return detail::classic_from(emission_, sample_incident(p, u));
    }

    /// The first hit of r with the sphere (shade::intersect).
    [[nodiscard]] std::optional<hit<T>> intersect(const ray<T>& r) const noexcept {
        return shade::intersect(r, shape_);
    }

private:
    struct cone {
        bool outside = false;      ///< p strictly outside the sphere
        vec3<T> axis{0, 0, 1};     ///< unit direction from p to the centre
        T distance = T(0);         ///< |c - p|
        T one_minus_cos_max = T(0); ///< 1 - cos(theta_max)
    };

    [[nodiscard]] cone cone_from(const vec3<T>& p) const noexcept {
        cone c;
        const auto [axis, d] = detail::split_direction(vec3<T>(center() - p));
        if (!(d > radius())) return c;
        const T sin2_max = (radius() / d) * (radius() / d);
        const T cos_max = std::sqrt(T(1) - sin2_max);
        c.outside = true;
        c.axis = axis;
        c.distance = d;
        c.one_minus_cos_max = sin2_max / (T(1) + cos_max);
        return c;
    }

    sphere<T> shape_;
    emission<T> emission_;
    sidedness sides_;
    T area_ = T(0);
};

} // namespace shade
