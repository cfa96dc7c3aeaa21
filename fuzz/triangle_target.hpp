#pragma once
// The body of the three ray/triangle fuzz targets, one per algorithm of
// shade/geometry/triangle.hpp. Input layout (see input.hpp for how scalars are read):
//   byte 0: bit 0 picks double (1) or float (0); bit 1 back-face culling;
//   byte 1: scenario, mod 3:
//     0  free:   triangle v0, v1, v2, then ray origin, direction, t_min, t_max, all as
//                decoded (any value, non-finite included);
//     1  aimed:  triangle, origin, barycentrics (b1, b2) and a scale s, t_min, t_max; the
//                direction is s * (b0 v0 + b1 v1 + b2 v2 - origin), b0 = 1 - b1 - b2, so
//                edges (b = 0), vertices and the inside are reached often;
//     2  closed: a tetrahedron with small-integer vertices times 2^k and the ray from its
//                centroid in a decoded direction (watertight only, see check_closed).
// Checked on every result: the common hit rules (hit_checks.hpp), barycentrics that are
// finite and >= 0, and no hit from a triangle with a non-finite vertex.

#include <array>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <limits>

#include <shade/geometry/triangle.hpp>

#include "expect.hpp"
#include "hit_checks.hpp"
#include "input.hpp"

namespace shade::fuzz {

/// Intersects with Algorithm and checks everything a triangle hit promises.
template <class Algorithm, std::floating_point T>
void check_triangle(const ray<T>& r, const triangle<T>& tri, culling cull) {
    const auto h = intersect<Algorithm>(r, tri, cull);
    check_hit(r, h, cull);
    // The lean test must find exactly what the full one reports.
    const auto x = find_intersection<Algorithm>(r, tri, cull);
    expect(x.has_value() == h.has_value(), "find_intersection and intersect disagree on a hit");
    if (!h) return;
    expect(x->t == h->t && x->barycentric == h->barycentric && x->front_face == h->front_face,
           "find_intersection and intersect disagree on t, barycentrics or the face");
    const vec3<T>& b = h->barycentric;
    const bool b_ok = is_finite(b) && b.x >= T(0) && b.y >= T(0) && b.z >= T(0);
    if (!b_ok) show("barycentric", b);
    expect(b_ok, "a triangle hit's barycentrics are not finite and >= 0");
    expect(is_finite(tri.v0) && is_finite(tri.v1) && is_finite(tri.v2),
           "a triangle with a non-finite vertex was hit");
}

/// Determinant of (b - a, c - a, d - a) for integer points: six times the signed volume of
/// the tetrahedron, exact in 64-bit integers for coordinates in [-128, 127].
[[nodiscard]] inline std::int64_t orient(const std::array<std::int64_t, 3>& a,
                                         const std::array<std::int64_t, 3>& b,
                                         const std::array<std::int64_t, 3>& c,
                                         const std::array<std::int64_t, 3>& d) noexcept {
    const std::int64_t bx = b[0] - a[0], by = b[1] - a[1], bz = b[2] - a[2];
    const std::int64_t cx = c[0] - a[0], cy = c[1] - a[1], cz = c[2] - a[2];
    const std::int64_t dx = d[0] - a[0], dy = d[1] - a[1], dz = d[2] - a[2];
    return bx * (cy * dz - cz * dy) - by * (cx * dz - cz * dx) + bz * (cx * dy - cy * dx);
}

/// Watertightness on a closed mesh: a ray starting strictly inside a tetrahedron must hit
/// at least one of its four faces, whatever its direction (rays through shared edges and
/// vertices included). Vertices are integers in [-128, 127] times 2^k, |k| <= 20, so the
/// centroid (sum / 4) and every vertex minus it are exact in float and double; a non-zero
/// integer volume puts the centroid strictly inside. The direction is rescaled by a power
/// of two (exact, the same ray) so that t = distance / |direction| cannot overflow.
template <std::floating_point T>
void check_closed(input& in) {
    std::array<std::array<std::int64_t, 3>, 4> p{};
    for (auto& v : p)
        for (auto& c : v) c = static_cast<std::int8_t>(in.byte());
    if (orient(p[0], p[1], p[2], p[3]) == 0) return; // flat: no inside
    const int k = static_cast<int>(in.byte() % 41) - 20;
    std::array<vec3<T>, 4> v{};
    for (std::size_t i = 0; i < 4; ++i)
        v[i] = vec3<T>(std::ldexp(T(p[i][0]), k), std::ldexp(T(p[i][1]), k),
                       std::ldexp(T(p[i][2]), k));
    const vec3<T> centroid = (v[0] + v[1] + v[2] + v[3]) / T(4);

    vec3<T> d = in.vector<T>();
    ray<T> r{centroid, d};
    if (!r.valid()) return;
    const T m = std::max(std::abs(d.x), std::max(std::abs(d.y), std::abs(d.z)));
    int e = 0;
    (void)std::frexp(m, &e);
    // Per component: the factor 2^-e alone would overflow for a subnormal m.
    r.direction = vec3<T>(std::ldexp(d.x, -e), std::ldexp(d.y, -e), std::ldexp(d.z, -e));

    const std::array<triangle<T>, 4> faces{triangle<T>{v[0], v[1], v[2]},
                                           triangle<T>{v[0], v[3], v[1]},
                                           triangle<T>{v[0], v[2], v[3]},
                                           triangle<T>{v[1], v[3], v[2]}};
    int hits = 0;
    for (const auto& f : faces) {
        const auto h = intersect<watertight>(r, f);
        check_hit(r, h);
        if (h) ++hits;
    }
    if (hits == 0) {
        show(r);
        for (const auto& q : v) show("vertex", q);
    }
    expect(hits > 0, "a ray from inside a closed tetrahedron slipped through (watertight)");
}

/// Decodes one scenario (see the top of this file) in scalar type T and checks it.
template <class Algorithm, std::floating_point T>
void triangle_scenario(input& in, culling cull) {
    const unsigned scenario = in.choice(3);
    if (scenario == 2) {
        if constexpr (std::same_as<Algorithm, watertight>) check_closed<T>(in);
        return;
    }
    triangle<T> tri{in.vector<T>(), in.vector<T>(), in.vector<T>()};
    ray<T> r;
    r.origin = in.vector<T>();
    if (scenario == 0) {
        r.direction = in.vector<T>();
    } else {
        const T b1 = in.scalar<T>();
        const T b2 = in.scalar<T>();
        const T s = in.scalar<T>();
        const vec3<T> target = (T(1) - b1 - b2) * tri.v0 + b1 * tri.v1 + b2 * tri.v2;
        r.direction = s * (target - r.origin);
    }
    r.t_min = in.scalar<T>();
    r.t_max = in.scalar<T>();
    check_ray_checked(r);
    check_triangle<Algorithm>(r, tri, cull);
}

/// The whole fuzz target for Algorithm: picks the scalar type and culling, runs one
/// scenario. Always returns 0 (libFuzzer's "input processed").
template <class Algorithm>
int triangle_target(const std::uint8_t* data, std::size_t size) {
    input in(data, size);
    const std::uint8_t head = in.byte();
    const culling cull = (head & 2u) != 0 ? culling::back_faces : culling::none;
    if ((head & 1u) != 0)
        triangle_scenario<Algorithm, double>(in, cull);
    else
        triangle_scenario<Algorithm, float>(in, cull);
    return 0;
}

} // namespace shade::fuzz
