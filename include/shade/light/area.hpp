#pragma once
// shade::area_light: a rectangular (parallelogram) emitter sampled by area for soft
// shadows (stratified with shade::stratified_u of shade/core/sampling.hpp).

#include <cmath>
#include <concepts>
#include <limits>
#include <optional>
#include <string>
#include <utility>

#include <glm/geometric.hpp>

#include <shade/core/error.hpp>
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

/// An area light: the parallelogram {corner + s edge_u + t edge_v : s, t in [0,1]}
/// (usually a rectangle), emitting toward the side of n = normalize(cross(edge_u, edge_v)),
/// or toward both sides. Each unit of area emits like a point light of the light's
/// intensity and colours with inverse-square falloff, times the cosine at the light; in
/// physical terms the emitted radiance is L_e = pi x intensity x colour (light_sample
/// units: the classic colour is irradiance / pi).
///
/// Estimator (Shirley, Wang, Zimmerman 1996, "Monte Carlo Techniques for Direct Lighting
/// Calculations", ACM TOG 15(1), sampling a luminaire uniformly by area): the direct light
/// at p is the integral over the light of the point-light contribution of each dA,
///   integral_A  shade(l(x)) * cos_light(x) / |x - p|^2  dA(x),
/// where cos_light = dot(n, -l) (|.| when two-sided, 0 on the back side). sample(p, u)
/// picks x = corner + u.x edge_u + u.y edge_v, uniform in area (pdf = 1/A), and returns
/// the light sample toward x whose diffuse and specular colours are scaled by
///   intensity * cos_light * A / |x - p|^2     (= integrand / pdf).
/// For any shader linear in the light's colours (every lit BRDF), the average of shade()
/// over N samples therefore converges to the area light's contribution, and stratifying u
/// (stratified_u, for_each_sample) reduces the variance. The ambient colour is not a
/// directional quantity: every sample carries intensity x ambient, so the average is too.
///
/// Degenerate samples carry the ambient colour only, no Inf/NaN: p on the light (l is then
/// a placeholder and distance +inf), the back side of a one-sided light, and overflow of
/// 1/|x - p|^2 (l and distance still set).
///
/// Physical mode: a Lambertian emitter of radiance L = emitted().physical() in
/// W/(m^2 sr) on its emitting side(s), power pi L A per side; sample_incident chooses
/// x uniformly by area (the same point_at(u)) and reports the solid-angle density
/// r^2 / (A cos_light). As geometry its hits have uv = (s, t) of
/// corner + s edge_u + t edge_v and dp/du = edge_u.
template <std::floating_point T>
class area_light : public detail::area_emitter<area_light<T>, T> {
public:
    using scalar_type = T;
    using detail::area_emitter<area_light<T>, T>::radiance;
    using detail::area_emitter<area_light<T>, T>::sample_incident;
    using detail::area_emitter<area_light<T>, T>::pdf_incident;

    /// A parallelogram light with the given corner and edges (the default emission is the
    /// classic model's light, radiance pi W/(m^2 sr); from_radiance and from_power say
    /// their units). Throws
    /// shade::invalid_parameter naming "corner" (non-finite), "edge_u" / "edge_v" (zero or
    /// non-finite), "edge_v" (parallel to edge_u), "sides" or the bad emission member.
    area_light(const vec3<T>& corner, const vec3<T>& edge_u, const vec3<T>& edge_v,
               const emission<T>& e = {}, sidedness sides = sidedness::one_sided)
        : corner_(require_finite("corner", corner)), edge_u_(edge_u), edge_v_(edge_v),
          emission_(validated(e)), sides_(sides) {
        const vec3<T> u_hat = require_direction("edge_u", edge_u);
        const vec3<T> v_hat = require_direction("edge_v", edge_v);
        const vec3<T> cross_hat = glm::cross(u_hat, v_hat); // length = sin(angle)
        // Edges closer than ~sqrt(epsilon) radians to parallel span a sliver whose normal
        // is dominated by the rounding of the cross product; reject rather than guess.
        if (!(glm::length(cross_hat) > std::sqrt(std::numeric_limits<T>::epsilon())))
            throw invalid_parameter("edge_v", "must not be parallel to edge_u",
                                    detail::to_text(edge_v));
        normal_ = glm::normalize(cross_hat);
        // Dual vectors of the edges in the light's plane: dot(x - corner, dual_u_) = s and
        // dot(x - corner, dual_v_) = t for x = corner + s edge_u + t edge_v.
        const vec3<T> across_v = glm::cross(edge_v, normal_);
        const vec3<T> across_u = glm::cross(normal_, edge_u);
        dual_u_ = across_v / glm::dot(edge_u, across_v);
        dual_v_ = across_u / glm::dot(edge_v, across_u);
        area_ = glm::length(edge_u) * glm::length(edge_v) * glm::length(cross_hat);
        if (!std::isfinite(area_) || !(area_ > T(0)))
            throw invalid_parameter("edge_u", "and edge_v must span a finite, non-zero area",
                                    detail::to_text(area_));
        (void)detail::require_sidedness(sides);
    }

    /// The light (geometry and sides as for the constructor) of radiance L in W/(m^2 sr)
    /// (from_radiance), or of power Phi in W, all emitting sides together (from_power:
    /// L = Phi / (pi A) one-sided, Phi / (2 pi A) two-sided, so power() == Phi); no
    /// ambient. Throw shade::invalid_parameter naming what the constructor names,
    /// "radiance" or "power" (negative or not finite in a channel, or an L that overflows).
    [[nodiscard]] static area_light from_radiance(const vec3<T>& corner, const vec3<T>& edge_u, const vec3<T>& edge_v,
                                                  const rgb<T>& radiance, sidedness sides = sidedness::one_sided) {
        return area_light(corner, edge_u, edge_v, detail::physical_emission("radiance", radiance), sides);
    }
    [[nodiscard]] static area_light from_power(const vec3<T>& corner, const vec3<T>& edge_u, const vec3<T>& edge_v,
                                               const rgb<T>& power, sidedness sides = sidedness::one_sided) {
        area_light out(corner, edge_u, edge_v, emission<T>{}, sides);
        out.emission_ = out.emission_of_power(power);
        return out;
    }

    /// The corner the edges start from.
    [[nodiscard]] const vec3<T>& corner() const noexcept { return corner_; }
    /// The first edge vector.
    [[nodiscard]] const vec3<T>& edge_u() const noexcept { return edge_u_; }
    /// The second edge vector.
    [[nodiscard]] const vec3<T>& edge_v() const noexcept { return edge_v_; }
    /// The unit normal normalize(cross(edge_u, edge_v)): the emitting side if one-sided.
    [[nodiscard]] const vec3<T>& normal() const noexcept { return normal_; }
    /// The area |cross(edge_u, edge_v)|.
    [[nodiscard]] T area() const noexcept { return area_; }
    /// The emitted intensity and colours (per unit area, see the class comment).
    [[nodiscard]] const emission<T>& emitted() const noexcept { return emission_; }
    /// Whether one or both sides emit.
    [[nodiscard]] sidedness sides() const noexcept { return sides_; }

    /// The point of the light at sample pair u in [0,1]^2.
    [[nodiscard]] vec3<T> point_at(const vec2<T>& u) const noexcept {
        return corner_ + u.x * edge_u_ + u.y * edge_v_;
    }

    /// One Monte Carlo light sample toward point_at(u), weighted for estimation (see the
    /// class comment): its colours are intensity * cos_light * area / r^2 times the
    /// light's colours. Precondition: u in [0,1]^2.
    [[nodiscard]] light_sample<T> sample(const vec3<T>& p, const vec2<T>& u) const noexcept {
        const auto [l, r] = detail::split_direction(vec3<T>(point_at(u) - p));
        if (!(r > T(0))) return detail::ambient_only_sample(emission_);
        T cos_light = -glm::dot(normal_, l);
        if (sides_ == sidedness::two_sided) cos_light = std::fabs(cos_light);
        if (!(cos_light > T(0))) cos_light = T(0); // back side of a one-sided light: dark
        return detail::make_sample(emission_, l, r, cos_light * area_ / (r * r));
    }

    /// The physical sample at p toward point_at(u), chosen uniformly by area (see the
    /// class comment). Nothing for p on the light, the back of a one-sided light or an
    /// overflowing density. Precondition: u in [0,1]^2.
    [[nodiscard]] std::optional<incident_sample<T>> sample_incident(const vec3<T>& p,
                                                                    const vec2<T>& u) const noexcept {
        return detail::area_incident(p, point_at(u), normal_, area_, this->radiance(), sides_);
    }

    /// The first hit of r with the light's parallelogram, either side (see the class
    /// comment for uv and dpdu), or nothing.
    [[nodiscard]] std::optional<hit<T>> intersect(const ray<T>& r) const noexcept {
        std::optional<hit<T>> out;
        const T n_dot_d = glm::dot(normal_, r.direction);
        if (n_dot_d == T(0)) return out;
        const T t = glm::dot(normal_, corner_ - r.origin) / n_dot_d;
        if (!(t >= r.t_min && t <= r.t_max) || !std::isfinite(t)) return out;
        const vec3<T> x = r.at(t);
        const vec3<T> offset = x - corner_;
        const T s = glm::dot(offset, dual_u_);
        const T w = glm::dot(offset, dual_v_);
        if (!(s >= T(0) && s <= T(1) && w >= T(0) && w <= T(1))) return out;
        out.emplace();
        out->t = t;
        out->p = x;
        out->n = normal_;
        out->p_error = detail::plane_hit_error(r.origin, corner_, t, r.direction);
        out->front_face = n_dot_d < T(0);
        out->uv = vec2<T>(s, w);
        out->dpdu = edge_u_;
        return out;
    }

    /// Calls fn(sample) for the n x n stratified samples sample(p, stratified_u(i, j, n,
    /// jitter(i, j))), i, j in [0, n). Each is an unbiased estimate on its own; the
    /// average of the n^2 results of a linear shader is the stratified estimate. `jitter`
    /// returns a point in [0,1)^2 per stratum (cell_centre: a deterministic grid). Throws
    /// shade::invalid_parameter naming "samples_per_side" if n < 1.
    template <class F, class Jitter = cell_centre<T>>
    void for_each_sample(const vec3<T>& p, int samples_per_side, F&& fn,
                         Jitter&& jitter = {}) const {
        const int n = detail::require_samples_per_side(samples_per_side);
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i)
                fn(sample(p, stratified_u<T>(i, j, n, jitter(i, j))));
    }

private:
    vec3<T> corner_;
    vec3<T> edge_u_;
    vec3<T> edge_v_;
    vec3<T> normal_{0, 0, 1};
    vec3<T> dual_u_{1, 0, 0};
    vec3<T> dual_v_{0, 1, 0};
    T area_ = T(0);
    emission<T> emission_;
    sidedness sides_;
};

} // namespace shade
