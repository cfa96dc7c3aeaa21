// Ray/sphere and ray/plane intersection: shade's routines against GLM 0.9.9.8's
// glm::intersectRaySphere and glm::intersectRayPlane on the same precomputed pairs (512
// in float, 256 in double: the same bytes, within the L1 data cache), about half of them
// hits. See bench/support.hpp for names, counters and the callgrind mode.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#define GLM_ENABLE_EXPERIMENTAL
#include <glm/gtx/intersect.hpp>

#include <benchmark/benchmark.h>

#include <shade/core/random.hpp>
#include <shade/geometry/plane.hpp>
#include <shade/geometry/sphere.hpp>

#include "support.hpp"

namespace {

using shade_bench::outcome;

// Pairs per data set: the same number of bytes for float and double.
template <class T>
constexpr std::size_t pair_count = 512 * sizeof(float) / sizeof(T);

template <class T>
using v3 = shade::vec3<T>;

template <class T>
v3<T> random_unit(shade::rng& g) {
    for (;;) {
        const v3<T> p(T(2) * g.uniform<T>() - T(1), T(2) * g.uniform<T>() - T(1),
                      T(2) * g.uniform<T>() - T(1));
        const T len = glm::length(p);
        if (len > T(0.1) && len <= T(1)) return p / len;
    }
}

// Pairs per "_memory" data set: more bytes than the last-level cache holds.
template <class T>
constexpr std::size_t memory_pair_count = shade_bench::beyond_cache_bytes / (sizeof(shade::ray<T>) + 4 * sizeof(T));

template <class T, class Shape, class Run>
double hit_rate(const std::vector<shade::ray<T>>& rays, const std::vector<Shape>& shapes, Run run) {
    std::size_t hits = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) hits += static_cast<std::size_t>(run(rays[i], shapes[i]).hit);
    return static_cast<double>(hits) / static_cast<double>(rays.size());
}

// Every pair in storage order, or in `order` when one is given (a permutation of the
// pairs: bench/support.hpp, random_order).
template <class T, class Shape, class Run>
void add_pairs(const std::string& name, const std::vector<shade::ray<T>>& rays,
               const std::vector<Shape>& shapes, Run run, const std::vector<std::uint32_t>* order = nullptr) {
    shade_bench::add(
        name, double(rays.size()),
        [&rays, &shapes, run, order] {
            if (order == nullptr) {
                for (std::size_t i = 0; i < rays.size(); ++i) {
                    outcome<T> o = run(rays[i], shapes[i]);
                    benchmark::DoNotOptimize(o);
                }
            } else {
                for (const std::uint32_t i : *order) {
                    outcome<T> o = run(rays[i], shapes[i]);
                    benchmark::DoNotOptimize(o);
                }
            }
        },
        hit_rate(rays, shapes, run));
}

// ---- sphere ---------------------------------------------------------------------------

template <class T>
struct sphere_data {
    std::vector<shade::ray<T>> rays; // unit directions (GLM requires them)
    std::vector<shade::sphere<T>> spheres;
};

// Spheres of radius 0.5 to 1.5 around points of [-2, 2]^3; rays from 3 to 8 away aimed
// at a point 0 to 0.9 radii (hit) or 1.1 to 2 radii (miss) off the centre.
template <class T>
sphere_data<T> make_spheres(std::uint64_t seed, std::size_t count = pair_count<T>) {
    shade::rng g(seed);
    sphere_data<T> data;
    for (std::size_t i = 0; i < count; ++i) {
        const v3<T> centre = random_unit<T>(g) * (T(2) * g.uniform<T>());
        const T radius = T(0.5) + g.uniform<T>();
        const bool hit = (i % 2) == 0;
        const v3<T> towards = random_unit<T>(g);
        const v3<T> origin = centre + towards * (T(3) + T(5) * g.uniform<T>());
        // An offset perpendicular to the line from the origin to the centre.
        const v3<T> side = glm::normalize(glm::cross(towards, random_unit<T>(g)));
        const T off = radius * (hit ? T(0.9) * g.uniform<T>() : T(1.1) + T(0.9) * g.uniform<T>());
        data.rays.push_back(shade::ray<T>{origin, glm::normalize(centre + side * off - origin)});
        data.spheres.emplace_back(centre, radius);
    }
    return data;
}

template <class T>
outcome<T> run_shade_sphere(const shade::ray<T>& r, const shade::sphere<T>& s) {
    const auto h = shade::find_intersection(r, s);
    if (!h) return {};
    return {1, h->t, h->n.x, h->n.y};
}

// GLM's position-and-normal overload, so that it computes what shade's hit record holds
// (t alone would skip the point and normal).
template <class T>
outcome<T> run_glm_sphere(const shade::ray<T>& r, const shade::sphere<T>& s) {
    v3<T> position, normal;
    if (glm::intersectRaySphere(r.origin, r.direction, s.center(), s.radius(), position, normal)) {
        return {1, glm::dot(position - r.origin, r.direction), normal.x, normal.y};
    }
    return {};
}

// ---- plane ----------------------------------------------------------------------------

template <class T>
struct plane_data {
    std::vector<shade::ray<T>> rays;
    std::vector<shade::plane<T>> planes;
};

// Planes through points of [-2, 2]^3 with random normals; rays from 1 to 5 away from the
// plane, pointing towards it (hit) or away from it (miss, t < 0).
template <class T>
plane_data<T> make_planes(std::uint64_t seed, std::size_t count = pair_count<T>) {
    shade::rng g(seed);
    plane_data<T> data;
    for (std::size_t i = 0; i < count; ++i) {
        const v3<T> point = random_unit<T>(g) * (T(2) * g.uniform<T>());
        const v3<T> normal = random_unit<T>(g);
        const v3<T> origin = point + normal * (T(1) + T(4) * g.uniform<T>()) + random_unit<T>(g);
        v3<T> direction = random_unit<T>(g);
        const bool hit = (i % 2) == 0;
        // Toward the plane from the front side means dot(direction, normal) < 0; keep it
        // at least 0.1 away from parallel so GLM's epsilon plays no part.
        const T cos_angle = glm::dot(direction, normal);
        if ((cos_angle < T(0)) != hit) direction = -direction;
        if (std::abs(glm::dot(direction, normal)) < T(0.1))
            direction = glm::normalize(direction + (hit ? -normal : normal) * T(0.2));
        data.rays.push_back(shade::ray<T>{origin, direction});
        data.planes.emplace_back(point, normal);
    }
    return data;
}

template <class T>
outcome<T> run_shade_plane(const shade::ray<T>& r, const shade::plane<T>& pl) {
    const auto h = shade::intersect(r, pl);
    if (!h) return {};
    return {1, h->t, h->p.x, h->p.y};
}

// GLM gives only the distance; the point is computed as shade's record holds it.
template <class T>
outcome<T> run_glm_plane(const shade::ray<T>& r, const shade::plane<T>& pl) {
    T distance;
    if (glm::intersectRayPlane(r.origin, r.direction, pl.point(), pl.normal(), distance)) {
        const v3<T> p = r.origin + distance * r.direction;
        return {1, distance, p.x, p.y};
    }
    return {};
}

template <class T>
void register_all(const char* type) {
    static const sphere_data<T> spheres = make_spheres<T>(31);
    static const plane_data<T> planes = make_planes<T>(32);
    const std::string sphere_group = std::string("sphere/") + type + "/hit50/";
    add_pairs<T>(sphere_group + "glm", spheres.rays, spheres.spheres, run_glm_sphere<T>);
    add_pairs<T>(sphere_group + "shade", spheres.rays, spheres.spheres, run_shade_sphere<T>);
    const std::string plane_group = std::string("plane/") + type + "/hit50/";
    add_pairs<T>(plane_group + "glm", planes.rays, planes.planes, run_glm_plane<T>);
    add_pairs<T>(plane_group + "shade", planes.rays, planes.planes, run_shade_plane<T>);
    if (!shade_bench::with_order_variants()) return;
    // The same pairs in a random order, and a set larger than the last-level cache.
    static const auto shuffled = shade_bench::random_order(pair_count<T>, 33);
    static const sphere_data<T> many_spheres = make_spheres<T>(34, memory_pair_count<T>);
    static const plane_data<T> many_planes = make_planes<T>(35, memory_pair_count<T>);
    static const auto memory_order = shade_bench::random_order(memory_pair_count<T>, 36);
    const std::string s = std::string("sphere/") + type, p = std::string("plane/") + type;
    add_pairs<T>(s + "/hit50_shuffled/glm", spheres.rays, spheres.spheres, run_glm_sphere<T>, &shuffled);
    add_pairs<T>(s + "/hit50_shuffled/shade", spheres.rays, spheres.spheres, run_shade_sphere<T>, &shuffled);
    add_pairs<T>(s + "/hit50_memory/glm", many_spheres.rays, many_spheres.spheres, run_glm_sphere<T>, &memory_order);
    add_pairs<T>(s + "/hit50_memory/shade", many_spheres.rays, many_spheres.spheres, run_shade_sphere<T>, &memory_order);
    add_pairs<T>(p + "/hit50_shuffled/glm", planes.rays, planes.planes, run_glm_plane<T>, &shuffled);
    add_pairs<T>(p + "/hit50_shuffled/shade", planes.rays, planes.planes, run_shade_plane<T>, &shuffled);
    add_pairs<T>(p + "/hit50_memory/glm", many_planes.rays, many_planes.planes, run_glm_plane<T>, &memory_order);
    add_pairs<T>(p + "/hit50_memory/shade", many_planes.rays, many_planes.planes, run_shade_plane<T>, &memory_order);
}

const bool registered = [] {
    register_all<float>("float");
    register_all<double>("double");
    return true;
}();

} // namespace
