#pragma once
// Shared by the plane, sphere and triangle tests: a sweep of rays with a special value in
// one coordinate of the origin, one of the direction and in the interval, to check that
// no ray that is not valid() ever hits. Plane, sphere and Möller-Trumbore test only
// t_min >= 0 of the ray and rely on their arithmetic to reject the rest, so this sweep is
// the evidence for that claim (docs/robustness.md).

#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <utility>

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/core/math.hpp>
#include <shade/geometry/ray.hpp>

namespace geometry_test {

/// Number of rays for_each_special_ray makes: 3 origin coordinates x 3 direction
/// coordinates x 10 values x 10 values x 6 intervals.
inline constexpr std::size_t special_ray_count = 3u * 3u * 10u * 10u * 6u;

/// Calls f(ray) for every ray of the sweep: the ray from (0.5, 0.25, 0.125) along
/// (-0.1, -0.2, -0.3), one origin coordinate and one direction coordinate replaced by one
/// of 0, -0, 0.25, -1, +-inf, NaN, +-max and the smallest subnormal, with one of the
/// intervals [0, inf], [-1, inf], [NaN, inf], [0, NaN], [2, 1], [-0, inf].
template <class T, class F>
void for_each_special_ray(F&& f) {
    const T inf = std::numeric_limits<T>::infinity();
    const T nan = std::numeric_limits<T>::quiet_NaN();
    const T max = std::numeric_limits<T>::max();
    const std::array<T, 10> specials{T(0), T(-0.0), T(0.25), T(-1), inf, -inf, nan, max, -max,
                                     std::numeric_limits<T>::denorm_min()};
    const std::array<std::pair<T, T>, 6> intervals{
        {{0, inf}, {T(-1), inf}, {nan, inf}, {0, nan}, {2, 1}, {T(-0.0), inf}}};
    for (int ko = 0; ko < 3; ++ko)
        for (int kd = 0; kd < 3; ++kd)
            for (const T so : specials)
                for (const T sd : specials)
                    for (const auto& [t_min, t_max] : intervals) {
                        shade::vec3<T> o(T(0.5), T(0.25), T(0.125));
                        shade::vec3<T> d(T(-0.1), T(-0.2), T(-0.3));
                        o[ko] = so;
                        d[kd] = sd;
                        f(shade::ray<T>{o, d, t_min, t_max});
                    }
}

/// Calls shade::intersect(ray, shape) with the shape's default algorithm.
struct default_intersect {
    template <class Ray, class Shape>
    auto operator()(const Ray& r, const Shape& shape) const {
        return shade::intersect(r, shape);
    }
};

/// The sweep against every shape with intersect(ray, shape) returning
/// std::optional<hit> (shade::intersect by default; the triangle tests pass
/// shade::intersect<Algorithm>): no hit for a ray that is not valid(); for a valid ray,
/// every hit has a finite t inside [t_min, t_max], a finite point and a unit normal. The
/// shapes should be placed so that the unmodified ray hits them (checked: over 100 hits).
template <class T, class Shape, std::size_t M, class Intersect = default_intersect>
void check_special_rays(const std::array<Shape, M>& shapes, Intersect intersect = {}) {
    std::size_t rays = 0, valid_hits = 0;
    for_each_special_ray<T>([&](const shade::ray<T>& r) {
        ++rays;
        for (const Shape& shape : shapes) {
            const auto h = intersect(r, shape);
            if (!r.valid()) {
                CHECK_FALSE(h.has_value());
            } else if (h) {
                ++valid_hits;
                CHECK(std::isfinite(h->t));
                CHECK(h->t >= r.t_min);
                CHECK(h->t <= r.t_max);
                CHECK(shade::is_finite(h->p));
                CHECK(std::abs(glm::length(h->n) - T(1)) <= 4 * std::numeric_limits<T>::epsilon());
            }
        }
    });
    CHECK(rays == special_ray_count);
    CHECK(valid_hits > 100); // the sweep also contains rays that do hit
}

} // namespace geometry_test
