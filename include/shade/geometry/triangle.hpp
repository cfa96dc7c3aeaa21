#pragma once
// shade::triangle and ray/triangle intersection with three interchangeable algorithms.
//
// Usage:
//     shade::triangle<float> tri{v0, v1, v2};
//     auto h = shade::intersect(r, tri);                          // Möller-Trumbore
//     auto w = shade::intersect<shade::watertight>(r, tri);       // watertight
//     auto c = shade::intersect<shade::watertight>(r, tri, shade::culling::back_faces);
//
//     // In a hot loop (a BVH leaf), find t and the barycentrics only, and build the full
//     // record once, for the closest triangle:
//     if (auto x = shade::find_intersection(r, tri)) { r.t_max = x->t; best = {x, &tri}; }
//     ... shade::triangle_hit<float> h = shade::make_hit(*best.tri, *best.x);
//
// Every algorithm is a tag type with a static member `find(ray, triangle, culling)`
// returning std::optional<triangle_intersection<T>> (t, barycentrics, front_face) and a
// `name`, so tests and benchmarks can loop over the set of them
// (shade/geometry/triangle_algorithms.hpp) on the same data. shade::intersect<A> is find
// followed by shade::make_hit, which adds the hit point and the unit normal. All algorithms
//   * are double-sided by default (culling::back_faces keeps front faces only);
//   * treat counter-clockwise (v0, v1, v2), seen from the front, as the front face: the
//     geometric normal is normalize(cross(v1 - v0, v2 - v0));
//   * report the same record: t in units of the ray direction, barycentrics (b0, b1, b2)
//     of v0, v1, v2, all >= 0, and front_face; make_hit adds p = b0 v0 + b1 v1 + b2 v2
//     (interpolated, so it lies on the triangle up to rounding) and the geometric unit
//     normal;
//   * use no epsilons at all: a triangle 1e-6 wide is hit like one 1e6 wide;
//   * return no hit for an invalid ray (see ray::valid), a degenerate triangle (the cross
//     product of its edges evaluates to exactly zero, or a vertex is not finite), a ray
//     parallel to the triangle's plane, t outside [t_min, t_max], or when an
//     intermediate product overflows (coordinates beyond about 1e18 in float, 1e150 in
//     double).
// They differ on rays through edges and vertices: only `watertight` guarantees that such a
// ray hits at least one of the triangles sharing the edge or vertex, whatever the compiler
// fuses into multiply-adds (see watertight; docs/robustness.md lists the builds tested).

#include <cmath>
#include <array>
#include <concepts>
#include <cstdint>
#include <limits>
#include <optional>
#include <string_view>
#include <type_traits>
#include <utility>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <shade/core/math.hpp>
#include <shade/core/types.hpp>
#include <shade/geometry/aabb.hpp>
#include <shade/geometry/hit.hpp>
#include <shade/geometry/ray.hpp>

namespace shade {

/// A triangle with vertices v0, v1, v2; counter-clockwise seen from the front.
/// A plain aggregate: degenerate or non-finite triangles are allowed and never hit.
template <std::floating_point T>
struct triangle {
    using scalar_type = T;

    vec3<T> v0{0, 0, 0}; ///< first vertex
    vec3<T> v1{1, 0, 0}; ///< second vertex
    vec3<T> v2{0, 1, 0}; ///< third vertex

    /// The geometric unit normal normalize(cross(v1 - v0, v2 - v0)), or the zero vector
    /// when the triangle is degenerate (that cross product is exactly zero) or not finite.
    [[nodiscard]] vec3<T> normal() const noexcept;
};

namespace detail {

/// c / |c| for the unnormalised triangle normal c = cross(v1 - v0, v2 - v0), or the zero
/// vector when c is zero or not finite. Fast path: when |c|^2 = c·c is a normal finite
/// number (neither underflowed nor overflowed), c / sqrt(c·c) directly; squares of
/// components that underflowed are below 2^-24 (float) of c·c, so they move the result by
/// under an ulp. Otherwise (tiny, huge or non-finite c) the scaled normalize_or_zero.
/// Dividing (rather than multiplying by 1 / sqrt(c·c)) keeps axis-aligned normals exact.
template <std::floating_point T>
[[nodiscard]] inline vec3<T> unit_normal_from_cross(const vec3<T>& c) noexcept {
    const T len2 = glm::dot(c, c);
    // NaN fails both comparisons, +infinity the second.
    if (len2 >= std::numeric_limits<T>::min() && len2 <= std::numeric_limits<T>::max())
        return c / std::sqrt(len2);
    return normalize_or_zero(c);
}

#if defined(__GNUC__)
/// Four floats in a GNU vector (SSE on x86-64, NEON on ARM): a point or vector in lanes
/// 0-2 and a spare lane 3, for the float forms of triangle::normal and make_hit.
using triangle_f4 [[gnu::vector_size(16)]] = float;

/// The vertices of a float triangle in lanes 0-2, each by one 16-byte load within the
/// triangle (v0 and v1 with the next vertex's x in lane 3, v2 loaded from v1.z on and
/// rotated): lane 3 holds some coordinate, which no result reads.
[[gnu::always_inline]] inline std::array<triangle_f4, 3> vertex_lanes(const triangle<float>& tri) noexcept {
    static_assert(sizeof(triangle<float>) == 36 && sizeof(vec3<float>) == 12);
    std::array<triangle_f4, 3> v;
    __builtin_memcpy(&v[0], &tri.v0.x, sizeof v[0]);
    __builtin_memcpy(&v[1], &tri.v1.x, sizeof v[1]);
    __builtin_memcpy(&v[2], &tri.v1.z, sizeof v[2]);
    v[2] = __builtin_shufflevector(v[2], v[2], 1, 2, 3, 0);
    return v;
}

/// glm::cross(a, b) in lanes 0-2: lane k is a[k+1] b[k+2] - b[k+1] a[k+2] (indices mod 3),
/// the same products and difference.
[[gnu::always_inline]] inline triangle_f4 cross_lanes(const triangle_f4& a, const triangle_f4& b) noexcept {
    return __builtin_shufflevector(a, a, 1, 2, 0, 3) * __builtin_shufflevector(b, b, 2, 0, 1, 3) -
           __builtin_shufflevector(b, b, 1, 2, 0, 3) * __builtin_shufflevector(a, a, 2, 0, 1, 3);
}

/// unit_normal_from_cross(c) for c in lanes 0-2: the same c·c ((x x + y y) + z z, as
/// glm::dot) and the same three divisions, in lanes.
[[gnu::always_inline]] inline vec3<float> unit_normal_from_cross(const triangle_f4& c) noexcept {
    const triangle_f4 c2 = c * c;
    const float len2 = c2[0] + c2[1] + c2[2];
    if (len2 >= std::numeric_limits<float>::min() && len2 <= std::numeric_limits<float>::max()) [[likely]] {
        const triangle_f4 n = c / std::sqrt(len2);
        return vec3<float>(n[0], n[1], n[2]);
    }
    return normalize_or_zero(vec3<float>(c[0], c[1], c[2]));
}
#endif

} // namespace detail

template <std::floating_point T>
vec3<T> triangle<T>::normal() const noexcept {
#if defined(__GNUC__)
    if constexpr (std::is_same_v<T, float>) {
        const auto v = detail::vertex_lanes(*this);
        return detail::unit_normal_from_cross(detail::cross_lanes(v[1] - v[0], v[2] - v[0]));
    } else
#endif
    return detail::unit_normal_from_cross(glm::cross(v1 - v0, v2 - v0));
}

/// What a ray/triangle test finds: where along the ray, where on the triangle, and which
/// side. shade::make_hit turns it into the full triangle_hit (hit point and normal).
///
/// barycentric = (b0, b1, b2) are the weights of v0, v1, v2, all >= 0, summing to 1 up
/// to rounding; (u, v) = (b1, b2).
template <std::floating_point T>
struct triangle_intersection {
    using scalar_type = T;

    T t = T(0);                   ///< ray parameter, in units of the ray's direction
    vec3<T> barycentric{1, 0, 0}; ///< (b0, b1, b2): weights of v0, v1, v2
    bool front_face = true;       ///< true when the ray struck the counter-clockwise side

    /// Weight of v1 (b1).
    [[nodiscard]] constexpr T u() const noexcept { return barycentric.y; }
    /// Weight of v2 (b2).
    [[nodiscard]] constexpr T v() const noexcept { return barycentric.z; }
};

namespace detail {

/// make_hit's fallback where p or p_error is not finite (the sums overflow: vertices
/// within a few ulps of the largest finite value): each coordinate of p clamped to the
/// triangle's bounding box, and p_error the box's width (the largest finite value where
/// the width itself overflows).
template <std::floating_point T>
inline void clamp_hit_point_to_box(const triangle<T>& tri, vec3<T>& p, vec3<T>& p_error) noexcept {
    for (int k = 0; k < 3; ++k) {
        const T lo = glm::min(tri.v0[k], glm::min(tri.v1[k], tri.v2[k]));
        const T hi = glm::max(tri.v0[k], glm::max(tri.v1[k], tri.v2[k]));
        p[k] = glm::min(glm::max(p[k], lo), hi); // an infinite p[k] becomes lo or hi
        p_error[k] = std::isfinite(hi - lo) ? hi - lo : std::numeric_limits<T>::max();
    }
}

/// make_hit's record from its p, p_error, unit normal n and dpdu = v1 - v0 (the part both
/// forms of make_hit share).
template <std::floating_point T>
[[nodiscard]] inline triangle_hit<T> assemble_hit(const triangle_intersection<T>& x, const vec3<T>& p,
                                                  const vec3<T>& p_error, const vec3<T>& n,
                                                  const vec3<T>& dpdu) noexcept {
    triangle_hit<T> h;
    h.t = x.t;
    h.p = p;
    h.p_error = p_error;
    h.n = n;
    h.front_face = x.front_face;
    h.barycentric = x.barycentric;
    h.uv = vec2<T>(x.barycentric.y, x.barycentric.z);
    h.dpdu = dpdu;
    return h;
}

/// make_hit computed one component at a time (any T, any compiler), with the normal
/// tri.normal(): the definition the lane form below must match bit for bit.
template <std::floating_point T>
[[nodiscard]] triangle_hit<T> make_hit_scalar(const triangle<T>& tri, const triangle_intersection<T>& x) noexcept {
    const vec3<T>& b = x.barycentric;
    vec3<T> p = b.x * tri.v0 + b.y * tri.v1 + b.z * tri.v2;
    // Two parts, both distances from the plane that the intersection tests see:
    // * p's rounding: each coordinate is three products and two sums (five roundings) of
    //   weights that sum to 1 within a few roundings (each test divides its numerators by
    //   one determinant): gamma_7 of the sum of the terms' magnitudes (Pharr, Jakob,
    //   Humphreys 2023, eq. 6.24). The weights' own errors move p within the plane.
    // * the tests' plane: Moller-Trumbore decides on which side of the plane a ray starts
    //   from T = (v0 - o)·((v0 - v1) x (v2 - v0)), whose rounding (edges and cross product
    //   gamma_4, origin difference and dot product gamma_3 more) is, as a distance, below
    //   gamma_6 |v0 - o| (|e1| |e2| / |e1 x e2| + 1); for an origin on the triangle |v0 - o|
    //   is at most its longest edge L. |e1| |e2| / |e1 x e2| = 1 / sin of the angle at v0,
    //   so the term matters only for slivers and needles, where it dominates. Bounded
    //   without square roots: |x|_2 <= |x|_1 above and |x|_2 >= |x|_inf below the line.
    const auto l1 = [](const vec3<T>& w) { return std::abs(w.x) + std::abs(w.y) + std::abs(w.z); };
    // |w| per component by std::abs, one mask each. (glm::abs is w >= 0 ? w : -w, which keeps
    // the sign of -0 and so compiles to a branch per component.) Here the sign of a zero
    // never shows: each magnitude is added to others and then to plane_error > 0, or is
    // one of the three whose positive maximum divides.
    const auto abs3 = [](const vec3<T>& w) { return vec3<T>(std::abs(w.x), std::abs(w.y), std::abs(w.z)); };
    const vec3<T> e1 = tri.v1 - tri.v0;
    const vec3<T> e2 = tri.v2 - tri.v0;
    const vec3<T> c = abs3(glm::cross(e1, e2));
    const T e1_l1 = l1(e1), e2_l1 = l1(e2);
    const T longest = glm::max(glm::max(e1_l1, e2_l1), l1(tri.v2 - tri.v1));
    const T plane_error =
        detail::gamma<T>(6) * longest * (e1_l1 * e2_l1 / glm::max(c.x, glm::max(c.y, c.z)) + T(1));
    vec3<T> p_error = detail::gamma<T>(7) * (abs3(b.x * tri.v0) + abs3(b.y * tri.v1) + abs3(b.z * tri.v2)) +
                      vec3<T>(plane_error);
    if (!is_finite(p) || !is_finite(p_error)) [[unlikely]]
        clamp_hit_point_to_box(tri, p, p_error);
    return assemble_hit(x, p, p_error, tri.normal(), e1);
}

#if defined(__GNUC__)
/// make_hit for float in four-lane GNU vectors (x, y, z and a spare lane; SSE on x86-64,
/// NEON on ARM): the same operations on each coordinate, in the same order, as
/// make_hit_scalar (so the same bits wherever the compiler fuses neither into
/// multiply-adds), in a fraction of the instructions: p and p_error three coordinates at a
/// time, the cross product once (for p_error and the normal) by lane rotations, the
/// three edges' 1-norms as one transposed sum.
/// The triangle is given as its vertices in lanes (vertex_lanes, or gathered from a
/// structure-of-arrays batch by shade::triangle_bvh); inlined where it is called, so that
/// the record is written in place.
[[nodiscard, gnu::always_inline]] inline triangle_hit<float>
make_hit_lanes(const std::array<triangle_f4, 3>& v, const triangle_intersection<float>& x) noexcept {
    using f4 = triangle_f4;
    using i4 [[gnu::vector_size(16)]] = std::int32_t;
    const auto abs4 = [](const f4& w) { return reinterpret_cast<f4>(reinterpret_cast<i4>(w) & 0x7fff'ffff); };
    // glm::max(a, b) = a < b ? b : a, lane by lane (which of two equal or unordered values
    // it keeps matters to the bits).
    const auto max4 = [](const f4& a, const f4& b) { return a < b ? b : a; };
    const auto& [v0, v1, v2] = v;
    const vec3<float>& b = x.barycentric;
    const f4 w0 = b.x * v0, w1 = b.y * v1, w2 = b.z * v2;
    const f4 p = w0 + w1 + w2;
    const f4 e1 = v1 - v0, e2 = v2 - v0, e3 = v2 - v1;
    const f4 cross = cross_lanes(e1, e2);
    const f4 c = abs4(cross);
    // The 1-norms of e1, e2 and e3 = v2 - v1 in lanes 0, 1, 2: (|x| + |y|) + |z| of each.
    const f4 a1 = abs4(e1), a2 = abs4(e2), a3 = abs4(e3);
    const f4 xy12 = __builtin_shufflevector(a1, a2, 0, 4, 1, 5); // |e1.x| |e2.x| |e1.y| |e2.y|
    const f4 z12 = __builtin_shufflevector(a1, a2, 2, 6, 2, 6);  // |e1.z| |e2.z|
    const f4 ex = __builtin_shufflevector(xy12, a3, 0, 1, 4, 7);
    const f4 ey = __builtin_shufflevector(xy12, a3, 2, 3, 5, 7);
    const f4 ez = __builtin_shufflevector(z12, a3, 0, 1, 6, 7);
    const f4 l1 = ex + ey + ez;
    const float longest = max4(max4(l1, __builtin_shufflevector(l1, l1, 1, 1, 1, 1)),
                               __builtin_shufflevector(l1, l1, 2, 2, 2, 2))[0];
    const float c_max = max4(c, max4(__builtin_shufflevector(c, c, 1, 1, 1, 1), __builtin_shufflevector(c, c, 2, 2, 2, 2)))[0];
    const float plane_error = detail::gamma<float>(6) * longest * (l1[0] * l1[1] / c_max + 1.0f);
    const f4 p_error = detail::gamma<float>(7) * (abs4(w0) + abs4(w1) + abs4(w2)) + plane_error;
    constexpr float largest = std::numeric_limits<float>::max();
    const i4 finite = (abs4(p) <= largest) & (abs4(p_error) <= largest);
    vec3<float> p3(p[0], p[1], p[2]), p_error3(p_error[0], p_error[1], p_error[2]);
#if defined(__SSE__)
    const bool all_finite = (__builtin_ia32_movmskps(reinterpret_cast<f4>(finite)) & 7) == 7;
#else
    const bool all_finite = (finite[0] & finite[1] & finite[2]) != 0;
#endif
    if (!all_finite) [[unlikely]] {
        const triangle<float> tri{vec3<float>(v0[0], v0[1], v0[2]), vec3<float>(v1[0], v1[1], v1[2]),
                                  vec3<float>(v2[0], v2[1], v2[2])};
        clamp_hit_point_to_box(tri, p3, p_error3);
    }
    // The normal from the same cross product, as triangle::normal() computes it.
    return assemble_hit(x, p3, p_error3, unit_normal_from_cross(cross), vec3<float>(e1[0], e1[1], e1[2]));
}

/// make_hit_lanes of a triangle.
[[nodiscard]] inline triangle_hit<float> make_hit_lanes(const triangle<float>& tri,
                                                        const triangle_intersection<float>& x) noexcept {
    return make_hit_lanes(vertex_lanes(tri), x);
}
#endif

} // namespace detail

/// The full hit record of an intersection x that a triangle algorithm's find returned for
/// tri: x's t, barycentrics and front_face, the geometric unit normal tri.normal(), the
/// barycentric parameterisation uv = (b1, b2) with dpdu = v1 - v0 (the triangle is
/// p = v0 + u (v1 - v0) + v (v2 - v0), right-handed about its normal), and
/// the point p = b0 v0 + b1 v1 + b2 v2 with its bound p_error = gamma_7 (|b0 v0| + |b1 v1|
/// + |b2 v2|) (p's rounding) + gamma_6 L (1 / sin(angle at v0) + 1) in every coordinate
/// (the rounding of the plane the intersection tests evaluate, L the longest edge), so
/// that a ray spawned from p (shade::spawn_ray) is on the side it leaves by for every
/// algorithm. Where the sum overflows (vertices within a few ulps of the largest finite
/// value), each coordinate of p is clamped to the triangle's bounding box, so p is always
/// finite, and p_error is the box's width.
/// Precondition: x came from a find (or intersect) on this same triangle, which
/// guarantees a non-degenerate, finite triangle and finite barycentrics >= 0.
template <std::floating_point T>
[[nodiscard]] triangle_hit<T> make_hit(const triangle<T>& tri, const triangle_intersection<T>& x) noexcept {
#if defined(__GNUC__)
    if constexpr (std::is_same_v<T, float>) return detail::make_hit_lanes(tri, x); else
#endif
    return detail::make_hit_scalar(tri, x);
}

/// Texture coordinates given at a triangle's three vertices (e.g. by a mesh file). The
/// defaults, (0, 0), (1, 0), (0, 1), are the barycentric parameterisation of make_hit.
template <std::floating_point T>
struct triangle_uv {
    using scalar_type = T;

    vec2<T> uv0{0, 0}; ///< uv at v0
    vec2<T> uv1{1, 0}; ///< uv at v1
    vec2<T> uv2{0, 1}; ///< uv at v2
};

/// As make_hit(tri, x), with the uv interpolated from per-vertex coordinates,
/// uv = b0 uv0 + b1 uv1 + b2 uv2, and dpdu the derivative of the affine map from uv to
/// the triangle's points. With duv1 = uv1 - uv0, duv2 = uv2 - uv0, e1 = v1 - v0,
/// e2 = v2 - v0, solving e1 = duv1.x dp/du + duv1.y dp/dv and the same for e2 gives
///     dp/du = (duv2.y e1 - duv1.y e2) / det,   det = duv1.x duv2.y - duv1.y duv2.x
/// (Pharr, Jakob, Humphreys 2016, "Physically Based Rendering", 3rd ed., §3.6.2). Where
/// det is zero or dp/du not finite (the three uv collinear), dpdu is that of the
/// barycentric parameterisation, v1 - v0. Mirrored uv (det < 0) make (u, v) left-handed
/// about the normal. Precondition as for make_hit(tri, x).
template <std::floating_point T>
[[nodiscard]] triangle_hit<T> make_hit(const triangle<T>& tri, const triangle_intersection<T>& x,
                                       const triangle_uv<T>& uvs) noexcept {
    triangle_hit<T> h = make_hit(tri, x);
    const vec3<T>& b = x.barycentric;
    h.uv = b.x * uvs.uv0 + b.y * uvs.uv1 + b.z * uvs.uv2;
    const vec2<T> duv1 = uvs.uv1 - uvs.uv0;
    const vec2<T> duv2 = uvs.uv2 - uvs.uv0;
    const T det = duv1.x * duv2.y - duv1.y * duv2.x;
    if (det == T(0)) return h;
    const vec3<T> dpdu = (duv2.y * (tri.v1 - tri.v0) - duv1.y * (tri.v2 - tri.v0)) / det;
    if (is_finite(dpdu)) h.dpdu = dpdu;
    return h;
}

namespace detail {

/// True when t is an accepted ray parameter of r: finite and in [t_min, t_max]
/// (the rule of detail::in_interval), with t_min >= 0 (a ray with a negative or NaN t_min
/// is invalid and hits nothing; Möller-Trumbore relies on this instead of calling
/// ray::valid()). Once t >= t_min >= 0 holds, t is neither NaN nor -infinity, so
/// "finite" needs only t < +infinity: one comparison instead of std::isfinite's mask
/// and compare.
template <std::floating_point T>
[[nodiscard]] inline bool t_accepted(const ray<T>& r, T t) noexcept {
    return r.t_min >= T(0) && t >= r.t_min && t <= r.t_max && t < infinity<T>;
}

/// The shared last step of the algorithms whose arithmetic can produce anything (a NaN or
/// infinite t or barycentric from a sliver triangle or extreme input): the intersection
/// (t, b, front_face), or nothing unless t_accepted and every barycentric is finite and
/// >= 0. Keeping these rules in one place makes "bad input never hits" the same for all.
/// (Möller-Trumbore's barycentrics are finite and >= 0 by construction; it needs only
/// t_accepted.)
template <std::floating_point T>
[[nodiscard]] inline std::optional<triangle_intersection<T>>
accept_intersection(const ray<T>& r, T t, const vec3<T>& b, bool front_face) noexcept {
    if (!t_accepted(r, t)) return std::nullopt;
    if (!(is_finite(b) && b.x >= T(0) && b.y >= T(0) && b.z >= T(0))) return std::nullopt;
    return triangle_intersection<T>{t, b, front_face};
}

/// The type in which the watertight test evaluates its 2D edge functions: double for
/// float, where a product of two floats is exact (24 + 24 significant bits fit in 53), and
/// T itself otherwise (double and long double use difference_of_products).
template <std::floating_point T>
struct edge_scalar {
    using type = T;
};
template <>
struct edge_scalar<float> {
    using type = double;
};

/// a b - c d by Kahan's algorithm: w = c d rounded, e = w - c d (exact, one fused
/// multiply-add), f = a b - w (rounded once, one fused multiply-add), result f + e.
/// Its relative error is at most 2 units in the last place, so its sign is the sign of the
/// exact a b - c d and it is 0 exactly when a b = c d, as long as no product underflows
/// or overflows (magnitudes of a b and c d between about 1e-290 and 1e308 in double).
/// std::fma rounds once whether or not the processor has a fused multiply-add (without
/// one the library computes it exactly in software), and the compiler cannot fuse or
/// split any step, so the result does not depend on -ffp-contract or -march.
///
/// Kahan, W. (unpublished notes, see Higham 2002, "Accuracy and Stability of Numerical
/// Algorithms", 2nd ed., SIAM, §2.6 and problem 27.17); error bound: Jeannerod, Louvet,
/// Muller 2013, "Further analysis of Kahan's algorithm for the accurate computation of
/// 2x2 determinants", Mathematics of Computation 82(284):2245-2264, Theorem 1.
template <std::floating_point T>
[[nodiscard]] inline T difference_of_products(T a, T b, T c, T d) noexcept {
    const T w = c * d;
    const T e = std::fma(-c, d, w);
    const T f = std::fma(a, b, -w);
    return f + e;
}

/// The 2D edge function p_x q_y - p_y q_x of the watertight test, in edge_scalar<T>, with
/// the sign of the exact value (0 exactly when the exact value is 0), so the two
/// triangles sharing an edge, which pass its end points in opposite orders, always get
/// opposite signs (or both 0), whatever the compiler fuses. For float it is the product
/// difference of exact double products, rounded once: the correctly rounded exact value,
/// fused or not, and so exactly the negative of the value with p and q swapped. For
/// double it is difference_of_products (exact sign; the two magnitudes may differ in the
/// last place, which changes barycentrics by an ulp and no decision).
template <std::floating_point T>
[[nodiscard]] inline typename edge_scalar<T>::type edge_function(T p_x, T p_y, T q_x, T q_y) noexcept {
    using E = typename edge_scalar<T>::type;
    if constexpr (std::same_as<E, T>)
        return difference_of_products(p_x, q_y, p_y, q_x);
    else
        return E(p_x) * E(q_y) - E(p_y) * E(q_x);
}

/// The sheared coordinate a - s b of the watertight test, as the same bits in every
/// triangle that shares the vertex, whatever the compiler fuses: for float computed in
/// double, where s b is exact, so the fused and the unfused difference are the same
/// rounded value (then rounded to float); otherwise one fused multiply-add, rounded once.
template <std::floating_point T>
[[nodiscard]] inline T shear(T a, T s, T b) noexcept {
    if constexpr (std::same_as<typename edge_scalar<T>::type, T>)
        return std::fma(-s, b, a);
    else
        return static_cast<T>(double(a) - double(s) * double(b));
}

} // namespace detail

/// Möller and Trumbore's algorithm (the default): solves o + t d = (1-u-v) v0 + u v1 + v v2
/// for (t, u, v) by Cramer's rule, with every determinant a scalar triple product.
///
/// Möller, Trumbore 1997, "Fast, Minimum Storage Ray-Triangle Intersection", Journal of
/// Graphics Tools 2(1):21-28, §2. With e1 = v1 - v0, e2 = v2 - v0 and s = o - v0 the
/// system is [-d | e1 | e2] (t, u, v) = s, and Cramer's rule gives
///     det = -d·(e1 × e2),  u = -d·(s × e2) / det,  v = -d·(e1 × s) / det,
///     t = s·(e1 × e2) / det.
/// The paper evaluates these as P = d × e2, Q = s × e1. We rotate the triple products
/// (a·(b × c) = b·(c × a)) around the geometric normal n = e1 × e2 and c = d × s:
///     det = -d·n,  U = -e2·c,  V = e1·c,  T = s·n,   u = U/det, v = V/det, t = T/det,
/// the arrangement Embree's Möller-Trumbore kernels use with a stored normal (Wald,
/// Woop, Benthin, Johnson, Ernst 2014, "Embree: A Kernel Framework for Efficient CPU Ray
/// Tracing", ACM Transactions on Graphics 33(4):143). The code computes the same four
/// numbers without the three negations: with a = v0 - v1 = -e1, q = v0 - o = -s,
/// m = a × e2 = -n and c' = d × q = -c,
///     det = d·m,  U = e2·c',  V = a·c',  T = q·m.
/// IEEE rounding is symmetric (fl(-x) = -fl(x)), so each is bitwise the value of the
/// first form (an exact zero may have the other sign, which no test below can see),
/// without its sign flips. The operation count of either form is that of the paper (two
/// cross products, four dot products), but:
///   * n (here m) depends on the triangle alone, so shade::triangle_batch stores it and
///     each of its lanes does a quarter fewer operations than with P and Q (and bitwise
///     the same);
///   * a degenerate triangle (n exactly zero) gives det exactly zero, and a non-finite
///     vertex, direction or origin gives a NaN or infinite det, U or V (an infinity
///     times anything is infinite or NaN), so no separate check is needed: the tests
///     below reject all of them, as they reject an overflowing product.
/// det > 0 exactly when the ray hits the front face (d·n < 0).
///
/// The decision is made on the numerators, before any division, and without an epsilon
/// (the paper's epsilon on det is dropped, so tiny triangles are not lost). With
/// W = det - (U + V), the ray hits the front (det > 0) when
///     U >= 0,  V >= 0,  W >= 0,  det <= max,
/// and the back (det < 0) when
///     U <= 0,  V <= 0,  W <= 0,  det >= -max,
/// i.e. all three barycentric numerators have the sign of det (NaN fails every
/// comparison). Only then is anything divided: t = T/det, b0 = W/det, b1 = U/det,
/// b2 = V/det, each correctly rounded and >= 0; t must also be finite and in
/// [t_min, t_max]. det = 0 (a degenerate triangle, or a ray in its plane) passes the
/// second line only with U = V = 0 and then makes t infinite or NaN, so it never hits.
/// Two branches on the sign of det, rather than multiplying U, V and T by it: a
/// renderer's rays mostly strike front faces, so the branch is well predicted there
/// (docs/benchmarks.md has the timings).
/// shade::triangle_batch makes the same decision branch-free, on a = |det| and the
/// numerators multiplied by sign(det) (exact), with W' = a - (U' + V'). IEEE rounding
/// is symmetric (fl(-x) = -fl(x)), so W' = W sign(det) and the quotients agree:
/// U'/a = U/det and so on. The one exception is a zero sign: when det < 0 and W is
/// exactly zero, W = det - (U + V) is +0 and so is W' (x - x = +0 in either order), so
/// W/det would be -0 where W'/a is +0. Adding +0 to W/det (which changes nothing else)
/// makes b0 = +0 in both, so the batch gives the scalar code's bits exactly.
struct moller_trumbore {
    static constexpr std::string_view name = "moller_trumbore"; ///< for test and benchmark output

    /// Where r meets tri, or nothing (see the header comment for the common rules).
    template <std::floating_point T>
    [[nodiscard]] static std::optional<triangle_intersection<T>>
    find(const ray<T>& r, const triangle<T>& tri, culling cull = culling::none) noexcept {
        // a = -e1, q = -s, c = d × q and m = -n of the header comment: no negation.
        const vec3<T> a = tri.v0 - tri.v1;
        const vec3<T> e2 = tri.v2 - tri.v0;
        const vec3<T> q = tri.v0 - r.origin;
        const vec3<T> c = glm::cross(r.direction, q);
        const T u_raw = glm::dot(e2, c);
        const T v_raw = glm::dot(a, c);
        // Before n and det: U and V of strictly opposite signs can never both have the sign
        // of det, so the ray misses (it passes outside the edge v0 v1 or v0 v2); this cheap
        // exit is taken before the normal is computed. An underflowing product (-0) or a
        // NaN goes on to the full test below, which decides.
        std::optional<triangle_intersection<T>> out; // one object returned everywhere (NRVO)
        if (u_raw * v_raw < T(0)) return out;
        const vec3<T> m = glm::cross(a, e2);
        const T det = glm::dot(r.direction, m);
        const T w_raw = det - (u_raw + v_raw);
        constexpr T largest = std::numeric_limits<T>::max();
        if (det > T(0)) {
            if (!(u_raw >= T(0) && v_raw >= T(0) && w_raw >= T(0) && det <= largest)) return out;
        } else {
            if (cull == culling::back_faces) return out;
            if (!(u_raw <= T(0) && v_raw <= T(0) && w_raw <= T(0) && det >= -largest)) return out;
        }
        const T t = glm::dot(q, m) / det;
        // An invalid ray needs no test of its own: a non-finite origin or direction made
        // U, V or det non-finite above, a zero direction made det zero (so t is not
        // finite), and t_accepted rejects a bad [t_min, t_max].
        if (!detail::t_accepted(r, t)) return out;
        // + 0: b0 = +0, not -0, on an exact edge hit from behind (see above).
        out = triangle_intersection<T>{t, vec3<T>(w_raw / det + T(0), u_raw / det, v_raw / det),
                                       det > T(0)};
        return out;
    }
};

/// The classic two-step baseline: intersect the triangle's plane, then decide inside or
/// outside from the signed areas of the three sub-triangles the hit point p forms with the
/// edges.
///
/// Plane step as for shade::plane (Haines 1989, "Essential Ray Tracing Algorithms", in
/// Glassner (ed.), An Introduction to Ray Tracing, ray/plane section), with n = e1 × e2:
///     t = n·(v0 - o) / n·d,  p = o + t d.
/// Inside step (Marschner, Shirley 2016, Fundamentals of Computer Graphics, 4th ed., §2.7,
/// barycentric coordinates as ratios of signed areas, b_a = n·n_a / |n|^2):
///     b0 = n̂·((v2 - v1) × (p - v1)) / |n|,  b1 = n̂·((v0 - v2) × (p - v2)) / |n|,
///     b2 = n̂·((v1 - v0) × (p - v0)) / |n|,
/// with n̂ = n / |n| (dividing by |n| instead of |n|^2 keeps tiny triangles clear of
/// underflow). p is inside when all three are >= 0. Each b is computed on its own, so
/// they sum to 1 only up to rounding, and points on shared edges may be missed by both
/// neighbours: not watertight.
struct plane_then_areas {
    static constexpr std::string_view name = "plane_then_areas"; ///< for test and benchmark output

    /// Where r meets tri, or nothing (see the header comment for the common rules).
    template <std::floating_point T>
    [[nodiscard]] static std::optional<triangle_intersection<T>>
    find(const ray<T>& r, const triangle<T>& tri, culling cull = culling::none) noexcept {
        if (!r.valid()) return std::nullopt;
        const vec3<T> n = glm::cross(tri.v1 - tri.v0, tri.v2 - tri.v0);
        const vec3<T> n_hat = detail::normalize_or_zero(n);
        if (!detail::is_unit_normal(n_hat)) return std::nullopt; // degenerate
        const T n_dot_d = glm::dot(n_hat, r.direction);
        if (n_dot_d == T(0)) return std::nullopt; // parallel to the plane
        const bool front_face = n_dot_d < T(0);
        if (cull == culling::back_faces && !front_face) return std::nullopt;
        const T t = glm::dot(n_hat, tri.v0 - r.origin) / n_dot_d;
        if (!detail::t_accepted(r, t)) return std::nullopt; // before p = r.at(t) is used
        const vec3<T> p = r.at(t);
        const T area2 = glm::dot(n_hat, n); // |n|, twice the triangle's area
        const T b0 = glm::dot(n_hat, glm::cross(tri.v2 - tri.v1, p - tri.v1)) / area2;
        if (!(b0 >= T(0))) return std::nullopt;
        const T b1 = glm::dot(n_hat, glm::cross(tri.v0 - tri.v2, p - tri.v2)) / area2;
        if (!(b1 >= T(0))) return std::nullopt;
        const T b2 = glm::dot(n_hat, glm::cross(tri.v1 - tri.v0, p - tri.v0)) / area2;
        // A subnormal |n| (a sliver of a triangle) can overflow a quotient to infinity,
        // which the shared step rejects.
        return detail::accept_intersection(r, t, vec3<T>(b0, b1, b2), front_face);
    }
};

/// Woop, Benthin and Wald's watertight test: no ray slips between triangles that share an
/// edge or a vertex (with exactly equal vertex coordinates), and no epsilon anywhere.
///
/// Woop, Benthin, Wald 2013, "Watertight Ray/Triangle Intersection", Journal of Computer
/// Graphics Techniques 2(1):65-82, the algorithm of §3 and its listing:
///   * permute axes so z (index k_z) is the direction's largest component (swapping x and
///     y when d_z < 0, which keeps the winding), and shear so the ray becomes the +z axis:
///     S_x = d_x/d_z, S_y = d_y/d_z, S_z = 1/d_z;
///   * vertices relative to the origin, A = v0 - o (B, C likewise), sheared:
///     A_x' = A_x - S_x A_z, A_y' = A_y - S_y A_z;
///   * 2D edge functions U = C_x' B_y' - C_y' B_x', V = A_x' C_y' - A_y' C_x',
///     W = B_x' A_y' - B_y' A_x' (weights of v0, v1, v2), whose signs must be exact: the
///     paper recomputes an edge function that is exactly 0 in higher precision;
///   * hit when U, V, W all have the same sign (zero counts as either), det = U + V + W
///     != 0; t = (U A_z' + V B_z' + W C_z') / det with A_z' = S_z A_z.
/// Watertightness rests on two things, both made independent of what the compiler fuses
/// into multiply-adds (-ffp-contract, -march): a vertex gets the same sheared coordinates
/// in every triangle that shares it (detail::shear), and each edge function has the sign
/// of its exact value (detail::edge_function: exact double products for float, Kahan's
/// difference of products for double). Then the two triangles sharing an edge see a ray
/// on opposite sides of it, or both on it, so a ray crossing it is inside at least one
/// (Woop et al. §3.2). This holds while the sheared coordinates are finite and, for
/// double, their products neither underflow nor overflow (each 0 or between about 1e-292
/// and 1e308 in magnitude): always for finite float input. det > 0 is the front face.
struct watertight {
    static constexpr std::string_view name = "watertight"; ///< for test and benchmark output

    /// Where r meets tri, or nothing (see the header comment for the common rules).
    template <std::floating_point T>
    [[nodiscard]] static std::optional<triangle_intersection<T>>
    find(const ray<T>& r, const triangle<T>& tri, culling cull = culling::none) noexcept {
        if (!r.valid()) return std::nullopt;
        const vec3<T>& d = r.direction;
        const vec3<T> abs_d(std::abs(d.x), std::abs(d.y), std::abs(d.z));
        int k_z = 0;
        if (abs_d.y > abs_d[k_z]) k_z = 1;
        if (abs_d.z > abs_d[k_z]) k_z = 2;
        int k_x = (k_z + 1) % 3;
        int k_y = (k_x + 1) % 3;
        if (d[k_z] < T(0)) std::swap(k_x, k_y);

        const T s_x = d[k_x] / d[k_z];
        const T s_y = d[k_y] / d[k_z];
        const T s_z = T(1) / d[k_z];

        const vec3<T> a = tri.v0 - r.origin;
        const vec3<T> b = tri.v1 - r.origin;
        const vec3<T> c = tri.v2 - r.origin;
        const T a_x = detail::shear(a[k_x], s_x, a[k_z]);
        const T a_y = detail::shear(a[k_y], s_y, a[k_z]);
        const T b_x = detail::shear(b[k_x], s_x, b[k_z]);
        const T b_y = detail::shear(b[k_y], s_y, b[k_z]);
        const T c_x = detail::shear(c[k_x], s_x, c[k_z]);
        const T c_y = detail::shear(c[k_y], s_y, c[k_z]);

        // The edge functions, det and t in E (double for float): only their signs decide
        // a hit, and those are exact (detail::edge_function).
        using E = typename detail::edge_scalar<T>::type;
        const E u = detail::edge_function(c_x, c_y, b_x, b_y); // c_x b_y - c_y b_x
        const E v = detail::edge_function(a_x, a_y, c_x, c_y); // a_x c_y - a_y c_x
        const E w = detail::edge_function(b_x, b_y, a_x, a_y); // b_x a_y - b_y a_x

        const bool any_negative = u < E(0) || v < E(0) || w < E(0);
        const bool any_positive = u > E(0) || v > E(0) || w > E(0);
        if (cull == culling::back_faces ? any_negative : (any_negative && any_positive))
            return std::nullopt;
        const E det = u + v + w;
        if (det == E(0)) return std::nullopt; // parallel ray or degenerate triangle
        // The common rule for degenerate and non-finite triangles (triangle::normal is zero
        // for them), checked only for rays that passed the edge tests: rounded edge
        // functions of a zero-area triangle need not sum to exactly zero.
        if (!detail::is_unit_normal(tri.normal())) return std::nullopt;

        const E a_z = E(s_z * a[k_z]);
        const E b_z = E(s_z * b[k_z]);
        const E c_z = E(s_z * c[k_z]);
        const T t = static_cast<T>((u * a_z + v * b_z + w * c_z) / det);
        return detail::accept_intersection(
            r, t, vec3<T>(static_cast<T>(u / det), static_cast<T>(v / det), static_cast<T>(w / det)),
            det > E(0));
    }
};

/// An algorithm tag A usable with find_intersection<A> and intersect<A>: a static
/// find(ray, triangle, culling) returning std::optional<triangle_intersection<T>> and a
/// name.
template <class A, class T>
concept triangle_algorithm =
    std::floating_point<T> &&
    requires(const ray<T>& r, const triangle<T>& tri, culling cull) {
        { A::find(r, tri, cull) } -> std::same_as<std::optional<triangle_intersection<T>>>;
        { A::name } -> std::convertible_to<std::string_view>;
    };

/// Where ray r meets triangle tri (t, barycentrics, front_face) using Algorithm
/// (Möller-Trumbore by default), or nothing. The lean test for hot loops: build the full
/// record with make_hit only for the intersection you keep. Double-sided unless cull is
/// culling::back_faces.
template <class Algorithm = moller_trumbore, std::floating_point T>
    requires triangle_algorithm<Algorithm, T>
[[nodiscard]] std::optional<triangle_intersection<T>>
find_intersection(const ray<T>& r, const triangle<T>& tri, culling cull = culling::none) noexcept {
    return Algorithm::find(r, tri, cull);
}

/// The hit of ray r with triangle tri using Algorithm (Möller-Trumbore by default), or
/// nothing: find_intersection followed by make_hit. Double-sided unless cull is
/// culling::back_faces.
template <class Algorithm = moller_trumbore, std::floating_point T>
    requires triangle_algorithm<Algorithm, T>
[[nodiscard]] std::optional<triangle_hit<T>> intersect(const ray<T>& r, const triangle<T>& tri,
                                                       culling cull = culling::none) noexcept {
    const std::optional<triangle_intersection<T>> x = Algorithm::find(r, tri, cull);
    if (!x) return std::nullopt;
    return make_hit(tri, *x);
}

/// The bounds of a triangle: the smallest box holding its three vertices.
template <std::floating_point T>
[[nodiscard]] aabb<T> bounds(const triangle<T>& tri) noexcept {
    return aabb<T>{glm::min(tri.v0, glm::min(tri.v1, tri.v2)),
                   glm::max(tri.v0, glm::max(tri.v1, tri.v2))};
}

} // namespace shade
