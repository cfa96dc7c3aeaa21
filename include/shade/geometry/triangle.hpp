#pragma once
// shade::triangle and ray/triangle intersection with three interchangeable algorithms.
//
// Usage:
//     shade::triangle<float> tri{v0, v1, v2};
//     auto h = shade::intersect(r, tri);                          // Möller-Trumbore
//     auto w = shade::intersect<shade::watertight>(r, tri);       // watertight
//     auto c = shade::intersect<shade::watertight>(r, tri, shade::culling::back_faces);
//
// Every algorithm is a tag type with a static member `intersect(ray, triangle, culling)`
// returning std::optional<triangle_hit<T>> and a `name`, so tests and benchmarks can loop
// over shade::triangle_algorithms on the same data. All of them
//   * are double-sided by default (culling::back_faces keeps front faces only);
//   * treat counter-clockwise (v0, v1, v2), seen from the front, as the front face: the
//     geometric normal is normalize(cross(v1 - v0, v2 - v0));
//   * report the same hit record: t in units of the ray direction, barycentrics
//     (b0, b1, b2) of v0, v1, v2, p = b0 v0 + b1 v1 + b2 v2 (interpolated, so it lies on
//     the triangle up to rounding), the geometric unit normal and front_face;
//   * use no epsilons at all: a triangle 1e-6 wide is hit like one 1e6 wide;
//   * return no hit for an invalid ray (see ray::valid), a degenerate triangle (the cross
//     product of its edges evaluates to exactly zero, or a vertex is not finite), a ray
//     parallel to the triangle's plane, or t outside [t_min, t_max].
// They differ on rays through edges and vertices: only `watertight` guarantees that such a
// ray hits at least one of the triangles sharing the edge or vertex.
//
// Watertightness also needs the compiler not to fuse a*b - c*d into a fused multiply-add
// (which makes the shared edge's two evaluations differ by more than a sign); x86-64
// without -mfma never does, elsewhere compile with -ffp-contract=off.

#include <algorithm>
#include <cmath>
#include <concepts>
#include <limits>
#include <optional>
#include <string_view>
#include <tuple>
#include <utility>

#include <glm/geometric.hpp>

#include <shade/core/math.hpp>
#include <shade/core/types.hpp>
#include <shade/geometry/hit.hpp>
#include <shade/geometry/ray.hpp>

#if defined(__GNUC__)
/// Keeps a rarely taken tail out of line (g++ and clang++ both define __GNUC__).
#define SHADE_NOINLINE [[gnu::noinline]]
#else
#define SHADE_NOINLINE
#endif

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

} // namespace detail

template <std::floating_point T>
vec3<T> triangle<T>::normal() const noexcept {
    return detail::unit_normal_from_cross(glm::cross(v1 - v0, v2 - v0));
}

namespace detail {

/// The shared last step of every triangle algorithm: checks what the algorithm computed
/// and builds the hit record. No hit unless t is finite and in [t_min, t_max], every
/// barycentric is a number >= 0, the triangle has a normal (not degenerate) and the face
/// passes culling. Centralising this makes the "bad input never hits" rules identical for
/// all algorithms, whatever NaN or infinity an algorithm's arithmetic produced.
/// cross_e1_e2 must be glm::cross(tri.v1 - tri.v0, tri.v2 - tri.v0) (the algorithms that
/// already have the edges pass it in; the result is then bitwise tri.normal()).
template <std::floating_point T>
[[nodiscard]] inline std::optional<triangle_hit<T>>
finish_triangle_hit(const ray<T>& r, const triangle<T>& tri, T t, const vec3<T>& b,
                    bool front_face, culling cull, const vec3<T>& cross_e1_e2) noexcept {
    if (!in_interval(t, r.t_min, r.t_max)) return std::nullopt;
    if (!(b.x >= T(0) && b.y >= T(0) && b.z >= T(0))) return std::nullopt; // NaN fails too
    if (cull == culling::back_faces && !front_face) return std::nullopt;
    // unit_normal_from_cross inlined, deciding on |c|^2 rather than on the normal: its
    // fast path always gives a finite non-zero vector, so no check of n is needed there.
    const T len2 = glm::dot(cross_e1_e2, cross_e1_e2);
    vec3<T> n;
    if (len2 >= std::numeric_limits<T>::min() && len2 <= std::numeric_limits<T>::max()) {
        n = cross_e1_e2 / std::sqrt(len2);
    } else {
        n = normalize_or_zero(cross_e1_e2);
        if (!is_unit_normal(n)) return std::nullopt; // degenerate or not finite
    }
    const vec3<T> p = b.x * tri.v0 + b.y * tri.v1 + b.z * tri.v2;
    if (!is_finite(p)) return std::nullopt;
    triangle_hit<T> h;
    h.t = t;
    h.p = p;
    h.n = n;
    h.front_face = front_face;
    h.barycentric = b;
    return h;
}

/// The next wider floating-point type, used by the watertight test's fallback: double for
/// float (where products of floats and their differences keep the exact sign), long
/// double for double (wider than double on x86-64 Linux; on platforms where long double
/// is double the fallback adds nothing and the test is watertight only for float).
template <std::floating_point T>
struct wider {
    using type = long double;
};
template <>
struct wider<float> {
    using type = double;
};

} // namespace detail

/// Möller and Trumbore's algorithm (the default): solves o + t d = (1-u-v) v0 + u v1 + v v2
/// for (t, u, v) by Cramer's rule with scalar triple products, rejecting as early as
/// possible.
///
/// Möller, Trumbore 1997, "Fast, Minimum Storage Ray-Triangle Intersection", Journal of
/// Graphics Tools 2(1):21-28, §2 (Cramer's rule, rewritten with P = d × e2, Q = T × e1):
///     e1 = v1 - v0, e2 = v2 - v0, P = d × e2, det = e1·P, T = o - v0, Q = T × e1,
///     u = T·P / det, v = d·Q / det, t = e2·Q / det.
/// det = -d·(e1 × e2), so det > 0 exactly when the ray hits the front face. The paper's
/// epsilon on det is dropped: only det == 0 (parallel ray or degenerate triangle) is
/// rejected, so tiny triangles are not lost. The test u + v <= 1 is written as
/// b0 = 1 - u - v >= 0 so that the returned b0 is never negative.
struct moller_trumbore {
    static constexpr std::string_view name = "moller_trumbore"; ///< for test and benchmark output

    /// The hit of r with tri, or nothing (see the header comment for the common rules).
    template <std::floating_point T>
    [[nodiscard]] static std::optional<triangle_hit<T>>
    intersect(const ray<T>& r, const triangle<T>& tri, culling cull = culling::none) noexcept {
        const vec3<T> e1 = tri.v1 - tri.v0;
        const vec3<T> e2 = tri.v2 - tri.v0;
        const vec3<T> p_vec = glm::cross(r.direction, e2);
        const T det = glm::dot(e1, p_vec);
        if (det == T(0)) return std::nullopt;
        if (cull == culling::back_faces && !(det > T(0))) return std::nullopt;
        // Division-free early outs on the numerators U = T·P and V = d·Q: the candidate
        // test of shade::intersect(ray, triangle_batch) (triangle_batch.hpp, where the
        // slacks are derived): with a = |det| and s = sign(det),
        //     s U >= -a 2^-20,  s V >= -a 2^-20,  a - s (U + V) >= -a 2^-10.
        // It accepts every (U, V) the divided tests below accept (a superset: the slacks
        // cover a quotient underflowing to -0 and the roundings of 1 - u - v), so the
        // results are exactly those of dividing first; NaN fails every comparison.
        const T a = std::abs(det);
        const T m = a * T(0x1p-20);
        const vec3<T> t_vec = r.origin - tri.v0;
        const T u_num = glm::dot(t_vec, p_vec);
        const T s_u = det < T(0) ? -u_num : u_num;
        if (!(s_u >= -m)) return std::nullopt;
        const vec3<T> q_vec = glm::cross(t_vec, e1);
        const T v_num = glm::dot(r.direction, q_vec);
        const T s_v = det < T(0) ? -v_num : v_num;
        if (!(s_v >= -m && a - (s_u + s_v) >= -(a * T(0x1p-10)))) return std::nullopt;
        return candidate(r, tri, e1, e2, q_vec, det, u_num, v_num, cull);
    }

private:
    /// The rest of intersect for a candidate: the divisions, the exact tests and the hit
    /// record. Kept out of line so that the far more frequent misses above run with few
    /// live values (no register spills) and no division.
    template <std::floating_point T>
    [[nodiscard]] SHADE_NOINLINE static std::optional<triangle_hit<T>>
    candidate(const ray<T>& r, const triangle<T>& tri, const vec3<T>& e1, const vec3<T>& e2,
              const vec3<T>& q_vec, T det, T u_num, T v_num, culling cull) noexcept {
        // The ray's validity is checked only here, for candidates: misses never need it,
        // and every bad ray still gets no hit, as before.
        if (!r.valid()) return std::nullopt;
        const T u = u_num / det;
        const T v = v_num / det;
        const T b0 = T(1) - u - v;
        // u <= 1 follows from v >= 0 and b0 = (1 - u) - v >= 0 (a rounded difference is
        // >= 0 exactly when the exact one is); NaN fails too.
        if (!(u >= T(0) && v >= T(0) && b0 >= T(0))) return std::nullopt;
        const T t = glm::dot(e2, q_vec) / det;
        return detail::finish_triangle_hit(r, tri, t, vec3<T>(b0, u, v), det > T(0), cull,
                                           glm::cross(e1, e2));
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

    /// The hit of r with tri, or nothing (see the header comment for the common rules).
    template <std::floating_point T>
    [[nodiscard]] static std::optional<triangle_hit<T>>
    intersect(const ray<T>& r, const triangle<T>& tri, culling cull = culling::none) noexcept {
        if (!r.valid()) return std::nullopt;
        const vec3<T> n = glm::cross(tri.v1 - tri.v0, tri.v2 - tri.v0);
        const vec3<T> n_hat = detail::normalize_or_zero(n);
        if (!detail::is_unit_normal(n_hat)) return std::nullopt; // degenerate
        const T n_dot_d = glm::dot(n_hat, r.direction);
        if (n_dot_d == T(0)) return std::nullopt; // parallel to the plane
        const bool front_face = n_dot_d < T(0);
        if (cull == culling::back_faces && !front_face) return std::nullopt;
        const T t = glm::dot(n_hat, tri.v0 - r.origin) / n_dot_d;
        if (!detail::in_interval(t, r.t_min, r.t_max)) return std::nullopt;
        const vec3<T> p = r.at(t);
        const T area2 = glm::dot(n_hat, n); // |n|, twice the triangle's area
        const T b0 = glm::dot(n_hat, glm::cross(tri.v2 - tri.v1, p - tri.v1)) / area2;
        if (!(b0 >= T(0))) return std::nullopt;
        const T b1 = glm::dot(n_hat, glm::cross(tri.v0 - tri.v2, p - tri.v2)) / area2;
        if (!(b1 >= T(0))) return std::nullopt;
        const T b2 = glm::dot(n_hat, glm::cross(tri.v1 - tri.v0, p - tri.v0)) / area2;
        return detail::finish_triangle_hit(r, tri, t, vec3<T>(b0, b1, b2), front_face, cull, n);
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
///     W = B_x' A_y' - B_y' A_x' (weights of v0, v1, v2); an edge function that is exactly
///     0 is recomputed in the next wider type so its sign is right;
///   * hit when U, V, W all have the same sign (zero counts as either), det = U + V + W
///     != 0; t = (U A_z' + V B_z' + W C_z') / det with A_z' = S_z A_z.
/// An edge shared by two triangles gives edge-function values of exactly opposite sign in
/// the two (same vertices, same operations), so a ray crossing it is inside at least one.
/// det > 0 is the front face.
struct watertight {
    static constexpr std::string_view name = "watertight"; ///< for test and benchmark output

    /// The hit of r with tri, or nothing (see the header comment for the common rules).
    template <std::floating_point T>
    [[nodiscard]] static std::optional<triangle_hit<T>>
    intersect(const ray<T>& r, const triangle<T>& tri, culling cull = culling::none) noexcept {
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
        const T a_x = a[k_x] - s_x * a[k_z];
        const T a_y = a[k_y] - s_y * a[k_z];
        const T b_x = b[k_x] - s_x * b[k_z];
        const T b_y = b[k_y] - s_y * b[k_z];
        const T c_x = c[k_x] - s_x * c[k_z];
        const T c_y = c[k_y] - s_y * c[k_z];

        T u = c_x * b_y - c_y * b_x;
        T v = a_x * c_y - a_y * c_x;
        T w = b_x * a_y - b_y * a_x;
        if (u == T(0) || v == T(0) || w == T(0)) {
            using W = typename detail::wider<T>::type;
            u = static_cast<T>(W(c_x) * W(b_y) - W(c_y) * W(b_x));
            v = static_cast<T>(W(a_x) * W(c_y) - W(a_y) * W(c_x));
            w = static_cast<T>(W(b_x) * W(a_y) - W(b_y) * W(a_x));
        }

        const bool any_negative = u < T(0) || v < T(0) || w < T(0);
        const bool any_positive = u > T(0) || v > T(0) || w > T(0);
        if (cull == culling::back_faces ? any_negative : (any_negative && any_positive))
            return std::nullopt;
        const T det = u + v + w;
        if (det == T(0)) return std::nullopt; // parallel ray or degenerate triangle

        const T a_z = s_z * a[k_z];
        const T b_z = s_z * b[k_z];
        const T c_z = s_z * c[k_z];
        const T t = (u * a_z + v * b_z + w * c_z) / det;
        return detail::finish_triangle_hit(r, tri, t, vec3<T>(u / det, v / det, w / det),
                                           det > T(0), cull,
                                           glm::cross(tri.v1 - tri.v0, tri.v2 - tri.v0));
    }
};

/// An algorithm tag A usable with intersect<A>: a static intersect(ray, triangle, culling)
/// returning std::optional<triangle_hit<T>> and a name.
template <class A, class T>
concept triangle_algorithm =
    std::floating_point<T> &&
    requires(const ray<T>& r, const triangle<T>& tri, culling cull) {
        { A::intersect(r, tri, cull) } -> std::same_as<std::optional<triangle_hit<T>>>;
        { A::name } -> std::convertible_to<std::string_view>;
    };

/// Every triangle algorithm shade provides, for tests and benchmarks to iterate over
/// (std::apply on a value, or doctest's TEST_CASE_TEMPLATE_APPLY).
using triangle_algorithms = std::tuple<moller_trumbore, plane_then_areas, watertight>;

/// The hit of ray r with triangle tri using Algorithm (Möller-Trumbore by default), or
/// nothing. Double-sided unless cull is culling::back_faces.
template <class Algorithm = moller_trumbore, std::floating_point T>
    requires triangle_algorithm<Algorithm, T>
[[nodiscard]] std::optional<triangle_hit<T>> intersect(const ray<T>& r, const triangle<T>& tri,
                                                       culling cull = culling::none) noexcept {
    return Algorithm::intersect(r, tri, cull);
}

} // namespace shade
