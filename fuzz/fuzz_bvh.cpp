// libFuzzer target: the BVH build and traversal (shade::triangle_bvh with Möller-Trumbore
// leaves batched and with watertight leaves, shade::primitive_bvh over spheres).
//
// Input: byte 0 bit 0 double/float, bits 1-2 the structure (0, 3: triangle_bvh with
// Möller-Trumbore; 1: triangle_bvh<T, watertight>; 2: primitive_bvh<sphere>), bit 3 back
// faces culled (triangles), bit 4 nodes of eight children (shade::bvh_width::eight; four
// on a CPU without AVX) instead of four; byte 1 the number of primitives (0-31); each triangle three
// vectors, each sphere a centre and a radius (any values); then up to four rays, each a
// byte (bit 0: aimed at a point of a primitive, from barycentric or unit-sphere
// coordinates decoded next, else a decoded direction), an origin and t_min, t_max.
// Checked (the guarantee shade/geometry/bvh.hpp states):
//   * construction throws exactly shade::invalid_parameter, for triangles exactly when a
//     vertex is not finite (sphere lists hold only spheres their own constructor accepted;
//     their hierarchy may reject a sphere whose box overflows);
//   * closest(r), if anything, is a hit the leaf test reports for that primitive, no
//     nearer than what a loop of the leaf test over every primitive keeps as nearest;
//   * when the real point o + t d of that loop's hit lies in its primitive's bounds
//     (certified below; always so for an exact test, not always for one that rounds, such
//     as Möller-Trumbore near an edge), closest(r) has the same t (bitwise), on the same
//     primitive with the same record, or on another primitive the leaf test hits at that
//     t; the hit obeys the common hit rules;
//   * any(r) is true only when that loop finds a hit, and is true when its nearest hit
//     lies in its primitive's bounds as above.

#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <optional>
#include <type_traits>
#include <vector>

#include <glm/geometric.hpp>

#include <shade/core/error.hpp>
#include <shade/geometry/aabb.hpp>
#include <shade/geometry/bvh.hpp>
#include <shade/geometry/sphere.hpp>
#include <shade/geometry/triangle.hpp>
#include <shade/geometry/triangle_bvh.hpp>

#include "expect.hpp"
#include "hit_checks.hpp"
#include "input.hpp"

namespace {

using namespace shade;
using fuzz::expect;

// True when the real point o + t d certainly lies in the closed box. Each coordinate is
// o_k + t d_k: the product exactly as prod + e1 (e1 from an FMA; 0 for float rays, whose
// product is exact in double), the sum as s + e2 (Knuth's two-sum, exact), so the point is
// s + e2 + e1. With no error terms s is the point and is compared exactly; otherwise s must
// lie inside by more than twice their size. A product near the subnormal range, whose FMA
// error term may itself be rounded, counts as uncertain by the smallest subnormal.
template <std::floating_point T>
bool certainly_inside(const aabb<T>& box, const ray<T>& r, T t) {
    using W = std::conditional_t<sizeof(T) == sizeof(float), double, T>;
    for (int k = 0; k < 3; ++k) {
        const W tt = t, d = r.direction[k], o = r.origin[k];
        const W prod = tt * d;
        W e1 = std::fma(tt, d, -prod);
        if (!std::isfinite(prod) || !std::isfinite(e1)) return false;
        const W s = o + prod;
        const W bb = s - o;
        const W e2 = (o - (s - bb)) + (prod - bb);
        W error = std::abs(e1) + std::abs(e2);
        if (std::abs(prod) < std::numeric_limits<W>::min() * W(0x1p+54))
            error += std::numeric_limits<W>::denorm_min();
        const W lo = box.lo[k], hi = box.hi[k];
        if (!std::isfinite(s)) return false;
        if (error == W(0)) {
            if (!(lo <= s && s <= hi)) return false;
        } else if (!(s - lo > W(2) * error && hi - s > W(2) * error)) {
            return false;
        }
    }
    return true;
}

// The nearest hit of r over every primitive, as a BVH's leaves would keep it: the index
// and the record, t_max lowered after each hit.
template <class Hit>
struct brute_hit {
    std::uint32_t primitive;
    Hit hit;
};

template <class Algorithm, std::floating_point T>
std::optional<brute_hit<triangle_hit<T>>> brute_closest(const std::vector<triangle<T>>& tris, ray<T> r,
                                                        culling cull) {
    std::optional<brute_hit<triangle_hit<T>>> best;
    if (!r.valid()) return best;
    for (std::size_t i = 0; i < tris.size(); ++i) {
        if (const auto x = find_intersection<Algorithm>(r, tris[i], cull)) {
            r.t_max = x->t;
            best = brute_hit<triangle_hit<T>>{static_cast<std::uint32_t>(i), make_hit(tris[i], *x)};
        }
    }
    return best;
}

template <std::floating_point T>
std::optional<brute_hit<hit<T>>> brute_closest(const std::vector<sphere<T>>& spheres, ray<T> r) {
    std::optional<brute_hit<hit<T>>> best;
    if (!r.valid()) return best;
    for (std::size_t i = 0; i < spheres.size(); ++i) {
        if (const auto h = intersect(r, spheres[i])) {
            r.t_max = h->t;
            best = brute_hit<hit<T>>{static_cast<std::uint32_t>(i), *h};
        }
    }
    return best;
}

// Bitwise equality of the parts of two hit records both kinds have.
template <std::floating_point T, class H>
bool same_record(const H& a, const H& b) {
    bool same = a.t == b.t && a.p == b.p && a.n == b.n && a.front_face == b.front_face;
    if constexpr (requires { a.barycentric; }) same = same && a.barycentric == b.barycentric;
    return same;
}

// Compares a BVH's closest/any with the brute-force loop for ray r; `hit_at(i, t)` says
// whether the leaf test hits primitive i at exactly t, `box_of(i)` gives its bounds.
template <std::floating_point T, class Found, class Brute, class Any, class HitAt, class BoxOf>
void compare(const ray<T>& r, const Found& found, const Brute& brute, Any any, HitAt hit_at, BoxOf box_of,
             culling cull) {
    fuzz::check_hit(r, found ? std::optional(found->hit) : std::nullopt, cull);
    const bool in_box = brute && certainly_inside(box_of(brute->primitive), r, brute->hit.t);
    const auto context = [&](const char* what) {
        fuzz::show(r);
        std::fprintf(stderr, "  %s; bvh %s, loop %s\n", what, found ? "hit" : "no hit", brute ? "hit" : "no hit");
        if (found) fuzz::show("bvh t", found->hit.t);
        if (brute) {
            fuzz::show("loop t", brute->hit.t);
            fuzz::show("loop box lo", box_of(brute->primitive).lo);
            fuzz::show("loop box hi", box_of(brute->primitive).hi);
        }
        if (found && brute)
            std::fprintf(stderr, "  bvh primitive %u, loop primitive %u\n", unsigned(found->primitive),
                         unsigned(brute->primitive));
    };
    // What closest() returns is always a leaf-test hit, never nearer than the loop's.
    if (found) {
        const bool real = brute.has_value() && !(found->hit.t < brute->hit.t) &&
                          hit_at(found->primitive, found->hit.t);
        if (!real) context("closest() is not a leaf-test hit at or beyond the loop's nearest");
        expect(real, "BVH closest() returned a hit the loop does not report, or a nearer one");
    }
    if (in_box) {
        const bool same_t = found && found->hit.t == brute->hit.t;
        const bool record_ok = same_t && (found->primitive == brute->primitive
                                              ? same_record<T>(found->hit, brute->hit)
                                              : hit_at(found->primitive, brute->hit.t));
        if (!same_t || !record_ok) context("the loop's nearest hit lies in its primitive's box");
        expect(same_t, "BVH closest() missed the loop's nearest hit, whose point lies in its box");
        expect(record_ok, "BVH closest() record differs from the loop's (or its primitive is not hit at that t)");
    }
    if (any && !brute) context("any() without a loop hit");
    expect(!any || brute.has_value(), "BVH any() is true but the loop finds no hit");
    if (in_box && !any) context("any() false");
    expect(!in_box || any, "BVH any() is false although the loop's nearest hit lies in its box");
}

// A ray decoded from the input: a free direction, or aimed at a point of primitive `target`.
template <std::floating_point T, class PointOf>
ray<T> decode_ray(fuzz::input& in, std::size_t count, PointOf point_of) {
    const bool aimed = in.flag() && count > 0;
    vec3<T> o = in.vector<T>();
    vec3<T> d;
    if (aimed) {
        const std::size_t target = in.byte() % count;
        d = point_of(target, in.vector<T>()) - o;
    } else {
        d = in.vector<T>();
    }
    const T t_min = in.scalar<T>();
    const T t_max = in.scalar<T>();
    return ray<T>{o, d, t_min, t_max};
}

template <class Algorithm, std::floating_point T>
void run_triangles(fuzz::input& in, culling cull, bvh_width width) {
    const std::size_t count = in.byte() % 32u;
    std::vector<triangle<T>> tris;
    bool all_finite = true;
    for (std::size_t i = 0; i < count; ++i) {
        triangle<T> t{in.vector<T>(), in.vector<T>(), in.vector<T>()};
        all_finite = all_finite && is_finite(t.v0) && is_finite(t.v1) && is_finite(t.v2);
        tris.push_back(t);
    }
    std::optional<triangle_bvh<T, Algorithm>> accel;
    try {
        accel.emplace(std::span<const triangle<T>>(tris), width);
    } catch (const invalid_parameter&) {
        expect(!all_finite, "triangle_bvh rejected finite triangles");
        return;
    }
    expect(all_finite, "triangle_bvh accepted a non-finite vertex");
    expect(accel->size() == count, "triangle_bvh holds a different number of triangles");
    for (int k = 0; k < 4; ++k) {
        // Aimed at b0 v0 + b1 v1 + b2 v2 with barycentric-like weights (normalised by their
        // sum when it is usable), so edges and vertices are common.
        const ray<T> r = decode_ray<T>(in, count, [&](std::size_t i, vec3<T> b) {
            const T sum = b.x + b.y + b.z;
            if (std::isfinite(sum) && sum != T(0)) b /= sum;
            return b.x * tris[i].v0 + b.y * tris[i].v1 + b.z * tris[i].v2;
        });
        const auto found = accel->closest(r, cull);
        const auto brute = brute_closest<Algorithm>(tris, r, cull);
        compare<T>(r, found, brute, accel->any(r, cull),
                   [&](std::uint32_t i, T t) {
                       const auto x = find_intersection<Algorithm>(r, tris[i], cull);
                       return x && x->t == t;
                   },
                   [&](std::uint32_t i) { return bounds(tris[i]); }, cull);
    }
}

template <std::floating_point T>
void run_spheres(fuzz::input& in, bvh_width width) {
    const std::size_t count = in.byte() % 32u;
    std::vector<sphere<T>> spheres;
    for (std::size_t i = 0; i < count; ++i) {
        const vec3<T> c = in.vector<T>();
        const T radius = in.scalar<T>();
        try {
            spheres.emplace_back(c, radius);
        } catch (const invalid_parameter&) {
            continue;
        }
    }
    std::optional<primitive_bvh<sphere<T>>> built;
    try {
        built.emplace(std::span<const sphere<T>>(spheres), width);
    } catch (const invalid_parameter&) {
        return; // a valid sphere whose box overflows (centre and radius near the largest T)
    }
    const primitive_bvh<sphere<T>>& accel = *built;
    for (int k = 0; k < 4; ++k) {
        // Aimed at centre + radius u / |u| (u decoded; the centre itself when u is unusable).
        const ray<T> r = decode_ray<T>(in, spheres.size(), [&](std::size_t i, const vec3<T>& u) {
            const T length = glm::length(u);
            const vec3<T> offset = std::isfinite(length) && length > T(0) ? u / length : vec3<T>(0);
            return spheres[i].center() + spheres[i].radius() * offset;
        });
        const auto found = accel.closest(r);
        const auto brute = brute_closest(spheres, r);
        compare<T>(r, found, brute, accel.any(r),
                   [&](std::uint32_t i, T t) {
                       const auto h = intersect(r, spheres[i]);
                       return h && h->t == t;
                   },
                   [&](std::uint32_t i) { return bounds(spheres[i]); }, culling::none);
    }
}

template <std::floating_point T>
void run(fuzz::input& in, unsigned head) {
    const unsigned structure = (head >> 1u) & 3u;
    const culling cull = (head & 8u) != 0 ? culling::back_faces : culling::none;
    const bvh_width width = (head & 16u) != 0 ? bvh_width::eight : bvh_width::four;
    if (structure == 1)
        run_triangles<watertight, T>(in, cull, width);
    else if (structure == 2)
        run_spheres<T>(in, width);
    else
        run_triangles<moller_trumbore, T>(in, cull, width);
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    shade::fuzz::input in(data, size);
    const unsigned head = in.byte();
    if ((head & 1u) != 0)
        run<double>(in, head);
    else
        run<float>(in, head);
    return 0;
}
