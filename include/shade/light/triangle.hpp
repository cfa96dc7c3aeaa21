#pragma once
// shade::triangle_light: one emitting triangle, sampled uniformly by solid angle where it
// looks large and by area where it looks small. A mesh's
// emissive triangles become one triangle_light each (in a std::vector<any_light<T>>), so
// an emissive ceiling can be part of the scene's mesh.

#include <cmath>
#include <concepts>
#include <optional>

#include <glm/geometric.hpp>

#include <shade/core/error.hpp>
#include <shade/core/math.hpp>
#include <shade/core/spherical_triangle.hpp>
#include <shade/core/types.hpp>
#include <shade/geometry/hit.hpp>
#include <shade/geometry/ray.hpp>
#include <shade/geometry/triangle.hpp>
#include <shade/light/area_emitter.hpp>
#include <shade/light/emission.hpp>
#include <shade/light/incident_sample.hpp>
#include <shade/light/light_sample.hpp>

namespace shade {

/// A triangle light with vertices v0, v1, v2, emitting toward the side its normal
/// shade::triangle::normal() = normalize((v1 - v0) x (v2 - v0)) points to (counter-clockwise
/// seen from that side), or both sides. A Lambertian emitter of radiance
/// L = emitted().physical() in W/(m^2 sr), area A = |(v1 - v0) x (v2 - v0)| / 2, power
/// pi L A per emitting side.
///
/// sample_incident(p, u) chooses one of two ways by the solid angle Omega the triangle
/// subtends at p (shade::make_spherical_triangle):
///   * Omega in [min_spherical_solid_angle, max_spherical_solid_angle]: a direction uniform
///     in the spherical triangle (shade::sample_spherical_triangle, Arvo 1995), density
///     1 / Omega. Seen from close by, area sampling wastes samples: its solid-angle density
///     r^2 / (A cos_light) varies across the triangle as much as r^2 does, while the
///     irradiance estimate L cos / pdf of a uniform-by-solid-angle sample varies only with
///     the receiver's cosine;
///   * otherwise a point uniform by area, barycentrics (1 - sqrt(u_0), sqrt(u_0) (1 - u_1),
///     sqrt(u_0) u_1) (Turk 1990, "Generating Random Points in Triangles", Graphics Gems;
///     density 1 / A), reported with the solid-angle density r^2 / (A cos_light). A small
///     triangle is nearly uniform in solid angle already, and the spherical construction
///     costs inverse trigonometric functions in double; past max_spherical_solid_angle (p
///     almost in the triangle's plane, over it) Arvo's construction loses accuracy.
/// pdf_incident makes the same choice at p, so it always returns the density
/// sample_incident used. As geometry it is the triangle: intersect(r) is shade::intersect
/// with Moller-Trumbore, so its hits carry barycentrics' uv and the rounding bound p_error.
template <std::floating_point T>
class triangle_light : public detail::area_emitter<triangle_light<T>, T> {
public:
    using scalar_type = T;
    using detail::area_emitter<triangle_light<T>, T>::radiance;
    using detail::area_emitter<triangle_light<T>, T>::sample_incident;
    using detail::area_emitter<triangle_light<T>, T>::pdf_incident;

    /// Below this solid angle (sr) seen from p, sample_incident samples by area.
    static constexpr double min_spherical_solid_angle = 1e-3;
    /// Above this solid angle (sr; the largest possible is 2 pi, about 6.283), by area too.
    static constexpr double max_spherical_solid_angle = 6.2;

    /// Throws shade::invalid_parameter naming "v0", "v1" or "v2" (non-finite), "v2" when the
    /// three are collinear or the area is not a finite number > 0, "sides" or the bad
    /// emission member.
    triangle_light(const vec3<T>& v0, const vec3<T>& v1, const vec3<T>& v2, const emission<T>& e = {},
                   sidedness sides = sidedness::one_sided)
        : triangle_{require_finite("v0", v0), require_finite("v1", v1), require_finite("v2", v2)},
          emission_(validated(e)), sides_(detail::require_sidedness(sides)) {
        const vec3<T> c = glm::cross(v1 - v0, v2 - v0);
        area_ = T(0.5) * glm::length(c);
        normal_ = triangle_.normal();
        if (!(area_ > T(0)) || !std::isfinite(area_) || !detail::is_unit_normal(normal_))
            throw invalid_parameter("v2", "must not be collinear with v0 and v1 (the area must be finite and > 0)",
                                    detail::to_text(v2));
    }

    /// The triangle (vertices and sides as for the constructor, whose default emission is
    /// the classic model's light, radiance pi) of radiance L in W/(m^2 sr) (from_radiance),
    /// or of power Phi in W, all emitting sides together (from_power: L = Phi / (pi A)
    /// one-sided, Phi / (2 pi A) two-sided); no ambient. Throw shade::invalid_parameter
    /// naming what the constructor names, "radiance" or "power" (as shade::area_light's).
    [[nodiscard]] static triangle_light from_radiance(const vec3<T>& v0, const vec3<T>& v1, const vec3<T>& v2,
                                                      const rgb<T>& radiance, sidedness sides = sidedness::one_sided) {
        return triangle_light(v0, v1, v2, detail::physical_emission("radiance", radiance), sides);
    }
    [[nodiscard]] static triangle_light from_power(const vec3<T>& v0, const vec3<T>& v1, const vec3<T>& v2,
                                                   const rgb<T>& power, sidedness sides = sidedness::one_sided) {
        triangle_light out(v0, v1, v2, emission<T>{}, sides);
        out.emission_ = out.emission_of_power(power);
        return out;
    }

    /// The triangle.
    [[nodiscard]] const triangle<T>& shape() const noexcept { return triangle_; }
    /// The unit normal: the emitting side if one-sided.
    [[nodiscard]] const vec3<T>& normal() const noexcept { return normal_; }
    /// The area |(v1 - v0) x (v2 - v0)| / 2.
    [[nodiscard]] T area() const noexcept { return area_; }
    /// The emitted intensity and colours.
    [[nodiscard]] const emission<T>& emitted() const noexcept { return emission_; }
    /// Whether one or both sides emit.
    [[nodiscard]] sidedness sides() const noexcept { return sides_; }

    /// The point of the triangle at sample pair u in [0,1)^2, uniform by area (see above).
    [[nodiscard]] vec3<T> point_at(const vec2<T>& u) const noexcept {
        const T su = std::sqrt(u.x);
        const T b1 = su * (T(1) - u.y);
        const T b2 = su * u.y;
        return (T(1) - su) * triangle_.v0 + b1 * triangle_.v1 + b2 * triangle_.v2;
    }

    /// Whether sample_incident(p, .) samples by solid angle (see the class comment) for a
    /// triangle that subtends solid_angle (sr) at p.
    [[nodiscard]] static constexpr bool samples_solid_angle(double solid_angle) noexcept {
        return solid_angle >= min_spherical_solid_angle && solid_angle <= max_spherical_solid_angle;
    }

    /// The physical sample at p (see the class comment for how it is drawn). Nothing for p
    /// on the light's plane or the back of a one-sided light, or an overflowing density.
    [[nodiscard]] std::optional<incident_sample<T>> sample_incident(const vec3<T>& p,
                                                                    const vec2<T>& u) const noexcept {
        const spherical_triangle st = make_spherical_triangle(p, triangle_.v0, triangle_.v1, triangle_.v2);
        if (!samples_solid_angle(st.area))
            return detail::area_incident(p, point_at(u), normal_, area_, this->radiance(), sides_);
        // The direction, and where it meets the triangle's plane, in double.
        const glm::dvec3 w = detail::sample_spherical_triangle(st, double(u.x), double(u.y));
        const glm::dvec3 n(normal_);
        const double t = glm::dot(glm::dvec3(triangle_.v0) - glm::dvec3(p), n) / glm::dot(w, n);
        const vec3<T> l(w);
        if (!(t > 0) || !std::isfinite(t) || !(detail::emitting_cosine(normal_, vec3<T>(-l), sides_) > T(0)))
            return std::nullopt;
        incident_sample<T> s;
        s.l = l;
        s.distance = T(t);
        s.radiance = this->radiance();
        s.pdf = T(1 / st.area);
        if (!(s.pdf > T(0)) || !std::isfinite(s.pdf)) return std::nullopt;
        return s;
    }

    /// The solid-angle density (1/sr) sample_incident(p, .) has for the unit direction l:
    /// 1 / Omega or r^2 / (A cos_light) by the choice at p (class comment) where the ray
    /// (p, l) meets an emitting side of the triangle, else 0.
    [[nodiscard]] T pdf_incident(const vec3<T>& p, const vec3<T>& l) const noexcept {
        const auto h = intersect(ray<T>{p, l});
        return h ? pdf_incident(p, l, *h) : T(0);
    }

    /// pdf_incident(p, l) when the caller already has h = intersect(ray{p, l}) (so h.t is
    /// the distance): the same density without intersecting again.
    [[nodiscard]] T pdf_incident(const vec3<T>& p, const vec3<T>& l, const hit<T>& h) const noexcept {
        const T cos_light = detail::emitting_cosine(h.n, vec3<T>(-l), sides_);
        if (!(cos_light > T(0))) return T(0);
        const spherical_triangle st = make_spherical_triangle(p, triangle_.v0, triangle_.v1, triangle_.v2);
        if (!samples_solid_angle(st.area)) return detail::solid_angle_pdf(h.t, cos_light, area_);
        const T pdf = T(1 / st.area);
        return std::isfinite(pdf) ? pdf : T(0);
    }

    /// The classic light sample from sample_incident(p, u), weighted by 1 / pdf.
    [[nodiscard]] light_sample<T> sample(const vec3<T>& p, const vec2<T>& u) const noexcept {
        return detail::classic_from(emission_, sample_incident(p, u));
    }

    /// The hit of r with the triangle, either side (shade::intersect, Moller-Trumbore).
    [[nodiscard]] std::optional<hit<T>> intersect(const ray<T>& r) const noexcept {
        const auto h = shade::intersect(r, triangle_);
        if (!h) return std::nullopt;
        return hit<T>(*h);
    }

private:
    triangle<T> triangle_;
    emission<T> emission_;
    sidedness sides_;
    T area_ = T(0);
    vec3<T> normal_{0, 0, 1};
};

} // namespace shade
