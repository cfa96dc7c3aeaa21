#pragma once
// The triangle_batch kernel, written once over a "lanes" type L (L::width lanes per step
// and the lane operations the kernel needs), and scalar_lanes, its portable one-lane-at-a-
// time form. shade/geometry/triangle_batch.hpp holds the public types and picks the lanes
// (the vector backends are triangle_batch_vector.hpp, triangle_batch_avx.hpp and
// triangle_batch_avx512.hpp next to this file). The kernel also runs on vertex_batch, the
// triangles as their vertices only (shade::triangle_bvh's leaves), forming the edges and
// the normal that triangle_batch stores.
//
// The division is deferred: each lane first computes the numerators U, V, W of the
// barycentrics and det, and decides hit or miss from their signs exactly as the scalar
// code does. Only for a vector step with at least one candidate lane are t, b0, b1, b2
// divided out, all lanes of the step at once, so a ray that misses the whole batch (the
// common case in a bounding-volume hierarchy) divides nothing. With the normal stored,
// each lane does 18 multiplications and 14 additions before that decision, against 24
// and 19 for the paper's P = d x e2, Q = s x e1 arrangement (a vertex_batch adds the 6
// multiplications and 9 subtractions of the edges and the normal).

#include <array>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <limits>

#include <glm/common.hpp>

#include <shade/core/math.hpp>
#include <shade/geometry/hit.hpp>
#include <shade/geometry/ray.hpp>
#include <shade/geometry/triangle.hpp>

namespace shade {

template <std::floating_point T, std::size_t N>
class triangle_batch;
template <std::floating_point T, std::size_t N>
struct triangle_batch_hits;

namespace detail {

/// Alignment of the per-lane arrays of triangle_batch and triangle_batch_hits: the largest
/// power of two up to 64 (a cache line, and an AVX-512 vector) that divides the N * sizeof(T)
/// bytes of one array. With it every array starts at a multiple of the kernel's vector
/// step, so no vector load or store straddles two cache lines.
template <std::floating_point T, std::size_t N>
[[nodiscard]] constexpr std::size_t batch_array_alignment() noexcept {
    std::size_t align = 64;
    while (align > alignof(T) && (N * sizeof(T)) % align != 0) align /= 2;
    return align;
}

/// Tag of the triangle_batch_hits constructor that leaves the lanes to the batch kernel.
struct every_lane_written {};

/// Reads a triangle_batch's arrays for the intersection routines below.
template <std::floating_point T, std::size_t N>
struct batch_access {
    using batch = triangle_batch<T, N>;
    static const auto& v0(const batch& b) noexcept { return b.v0_; }
    static const auto& a(const batch& b) noexcept { return b.a_; }
    static const auto& e2(const batch& b) noexcept { return b.e2_; }
    static const auto& m(const batch& b) noexcept { return b.m_; }
};

/// Up to N triangles as their vertices only, structure-of-arrays (v0, v1, v2: 9 N
/// scalars, 36 bytes a triangle in float), for shade::triangle_bvh's leaves: three
/// quarters of a triangle_batch, which also stores the edges and the normal. The kernel
/// forms those from the vertices at each test with the scalar code's operations (6
/// multiplications and 9 subtractions a lane), so it gives triangle_batch's bits. Lanes
/// past the count are zero: their edges and normal are zero, det = 0, never hit.
template <std::floating_point T, std::size_t N>
struct alignas(batch_array_alignment<T, N>()) vertex_batch {
    using scalar_type = T;
    static constexpr std::size_t width = N;
    struct soa3 {
        std::array<T, N> x, y, z;
    };
    soa3 v0, v1, v2;

    /// Lanes unset (trivial, so that storage for many batches is not written before they
    /// are assigned); to be assigned a batch made from triangles before it is read.
    vertex_batch() noexcept = default;
    /// Packs tris[i] into lane i, for i < count <= N (a precondition), and zero into the
    /// lanes past count.
    vertex_batch(const triangle<T>* tris, std::size_t count) noexcept : v0{}, v1{}, v2{} {
        for (std::size_t i = 0; i < count && i < N; ++i) {
            set(v0, i, tris[i].v0);
            set(v1, i, tris[i].v1);
            set(v2, i, tris[i].v2);
        }
    }
    /// The triangle of lane i, exactly as packed.
    [[nodiscard]] triangle<T> get(std::size_t i) const noexcept {
        return {vec3<T>(v0.x[i], v0.y[i], v0.z[i]), vec3<T>(v1.x[i], v1.y[i], v1.z[i]),
                vec3<T>(v2.x[i], v2.y[i], v2.z[i])};
    }

private:
    static void set(soa3& a, std::size_t i, const vec3<T>& v) noexcept {
        a.x[i] = v.x;
        a.y[i] = v.y;
        a.z[i] = v.z;
    }
};

/// One lane at a time: the portable form of the batch kernel (any compiler), and the
/// reference the vector form is tested against.
///
/// The lane operations of both forms write their result to their first argument instead
/// of returning it: a 32-byte vector returned by value from code compiled without AVX
/// would make g++ warn about the calling convention (-Wpsabi), see intersect_batch_avx.
template <std::floating_point T>
struct scalar_lanes {
    static constexpr std::size_t width = 1; ///< lanes per step
    using vec = T;                          ///< one value per lane
    using mask = bool;                      ///< one flag per lane
    static void load(vec& out, const T* p) noexcept { out = *p; }
    static void store(T* p, vec v) noexcept { *p = v; }
    static void splat(vec& out, T x) noexcept { out = x; }
    static void select(vec& out, mask m, vec a, vec b) noexcept { out = m ? a : b; }
    static void keep(vec& out, mask m, vec a) noexcept { out = m ? a : T(0); }
    static void abs(vec& out, vec a) noexcept { out = std::abs(a); }
    static void flip_sign(vec& out, vec a, vec s) noexcept { out = std::signbit(s) ? -a : a; }
    static std::uint64_t bits(mask m) noexcept { return m ? 1u : 0u; }
    static std::uint64_t sign_bits(vec v) noexcept { return std::signbit(v) ? 1u : 0u; }
    static bool any(mask m) noexcept { return m; }
};

#if defined(__GNUC__)
// Forced inline, so that the kernel is compiled for the instruction set of its caller:
// intersect_batch_avx (triangle_batch_avx.hpp) is compiled for AVX while the rest of the program may not be.
#define SHADE_DETAIL_BATCH_INLINE [[gnu::always_inline]] inline
#else
#define SHADE_DETAIL_BATCH_INLINE inline
#endif

/// x, y, z = lanes i .. i + L::width - 1 of the x, y and z arrays of a (one of the
/// batch's structure-of-arrays vectors).
template <class L, class Arrays>
SHADE_DETAIL_BATCH_INLINE void load_xyz(typename L::vec& x, typename L::vec& y, typename L::vec& z,
                                        const Arrays& a, std::size_t i) noexcept {
    L::load(x, &a.x[i]);
    L::load(y, &a.y[i]);
    L::load(z, &a.z[i]);
}

/// Lanes i .. i + L::width - 1 of a triangle_batch: v0 (p), a = v0 - v1 (f), e2 = v2 - v0
/// (g) and m = a x e2, as stored (x, y, z of each).
template <class L, std::floating_point T, std::size_t N, class V = typename L::vec>
SHADE_DETAIL_BATCH_INLINE void load_step(const triangle_batch<T, N>& batch, std::size_t i, V& p_x, V& p_y, V& p_z,
                                         V& f_x, V& f_y, V& f_z, V& g_x, V& g_y, V& g_z, V& m_x, V& m_y,
                                         V& m_z) noexcept {
    using access = batch_access<T, N>;
    load_xyz<L>(p_x, p_y, p_z, access::v0(batch), i);
    load_xyz<L>(m_x, m_y, m_z, access::m(batch), i);
    load_xyz<L>(f_x, f_y, f_z, access::a(batch), i);
    load_xyz<L>(g_x, g_y, g_z, access::e2(batch), i);
}

/// The same lanes of a vertex_batch, the edges and the normal formed as the scalar code
/// and triangle_batch's packing form them: a = v0 - v1, e2 = v2 - v0 and GLM's
/// cross(a, e2) = (a.y e2.z - e2.y a.z, a.z e2.x - e2.z a.x, a.x e2.y - e2.x a.y).
template <class L, std::floating_point T, std::size_t N, class V = typename L::vec>
SHADE_DETAIL_BATCH_INLINE void load_step(const vertex_batch<T, N>& batch, std::size_t i, V& p_x, V& p_y, V& p_z,
                                         V& f_x, V& f_y, V& f_z, V& g_x, V& g_y, V& g_z, V& m_x, V& m_y,
                                         V& m_z) noexcept {
    V s_x, s_y, s_z, w_x, w_y, w_z;
    load_xyz<L>(p_x, p_y, p_z, batch.v0, i);
    load_xyz<L>(s_x, s_y, s_z, batch.v1, i);
    load_xyz<L>(w_x, w_y, w_z, batch.v2, i);
    f_x = p_x - s_x;
    f_y = p_y - s_y;
    f_z = p_z - s_z;
    g_x = w_x - p_x;
    g_y = w_y - p_y;
    g_z = w_z - p_z;
    m_x = f_y * g_z - g_y * f_z;
    m_y = f_z * g_x - g_z * f_x;
    m_z = f_x * g_y - g_x * f_y;
}

/// The batch kernel behind shade::intersect(ray, triangle_batch) (see there), L::width
/// lanes per step with the lane operations of L (scalar_lanes or vector_lanes). Each
/// lane goes through the same IEEE operations whatever L is, so every L gives the same
/// bits. Batch is triangle_batch<T, N> or vertex_batch<T, N> (see load_step).
template <class L, template <class, std::size_t> class Batch, std::floating_point T, std::size_t N>
[[nodiscard]] SHADE_DETAIL_BATCH_INLINE triangle_batch_hits<T, N>
intersect_batch(const ray<T>& r, const Batch<T, N>& batch, culling cull) noexcept {
    static_assert(N % L::width == 0, "the lane step must divide the batch width");
    using vec = typename L::vec;
    using mask = typename L::mask;
    // The one test of the ray itself, which the scalar code makes per hit (t_accepted);
    // a non-finite or zero origin or direction needs none (see moller_trumbore).
    if (!(r.t_min >= T(0))) return {};
    triangle_batch_hits<T, N> out{every_lane_written{}}; // the loop below writes every lane

    vec o_x, o_y, o_z, d_x, d_y, d_z, zero, largest, t_lo, t_hi, inf;
    L::splat(o_x, r.origin.x);
    L::splat(o_y, r.origin.y);
    L::splat(o_z, r.origin.z);
    L::splat(d_x, r.direction.x);
    L::splat(d_y, r.direction.y);
    L::splat(d_z, r.direction.z);
    L::splat(zero, T(0));
    L::splat(largest, std::numeric_limits<T>::max());
    const bool front_only = cull == culling::back_faces;

    // t finite in [t_min, t_max] is t >= t_min and t <= min(t_max, max); NaN fails both.
    L::splat(t_lo, r.t_min);
    L::splat(t_hi, glm::min(r.t_max, std::numeric_limits<T>::max()));
    L::splat(inf, infinity<T>);
    // Fully unrolled (at most 16 steps), so the ray's splats stay in registers instead of
    // being reloaded at every step; both compilers read this pragma.
#if defined(__GNUC__)
#pragma GCC unroll 16
#endif
    for (std::size_t k = 0; k < N / L::width; ++k) {
        const std::size_t i = k * L::width;
        // The scalar code's dot and cross products in GLM's order,
        // cross(a, b) = (a.y b.z - b.y a.z, a.z b.x - b.z a.x, a.x b.y - b.x a.y) and
        // dot(a, b) = (a.x b.x + a.y b.y) + a.z b.z; flip_sign(x, det) is x * sign(det).
        vec p_x, p_y, p_z, f_x, f_y, f_z, g_x, g_y, g_z, m_x, m_y, m_z;
        load_step<L>(batch, i, p_x, p_y, p_z, f_x, f_y, f_z, g_x, g_y, g_z, m_x, m_y, m_z);
        const vec q_x = p_x - o_x;
        const vec q_y = p_y - o_y;
        const vec q_z = p_z - o_z;
        const vec c_x = d_y * q_z - q_y * d_z;
        const vec c_y = d_z * q_x - q_z * d_x;
        const vec c_z = d_x * q_y - q_x * d_y;
        // The scalar code's two branches on the sign of det in one, on the numerators
        // multiplied by sign(det) (see moller_trumbore for why the bits agree).
        const vec det = d_x * m_x + d_y * m_y + d_z * m_z;
        vec a, un, vn;
        L::abs(a, det);
        L::flip_sign(un, g_x * c_x + g_y * c_y + g_z * c_z, det);
        L::flip_sign(vn, f_x * c_x + f_y * c_y + f_z * c_z, det);
        const vec wn = a - (un + vn);
        mask candidate = (un >= zero) & (vn >= zero) & (wn >= zero) & (a > zero) & (a <= largest);
        if (front_only) candidate = candidate & (det > zero);
        if (!L::any(candidate)) {
            // No lane of this step is hit: no division.
            L::store(&out.t[i], inf);
            L::store(&out.b0[i], zero);
            L::store(&out.b1[i], zero);
            L::store(&out.b2[i], zero);
            continue;
        }

        vec t_num, t_out, b0, b1, b2;
        L::flip_sign(t_num, q_x * m_x + q_y * m_y + q_z * m_z, det);
        const vec t = t_num / a;
        const mask ok = candidate & (t >= t_lo) & (t <= t_hi);
        L::select(t_out, ok, t, inf);
        L::keep(b0, ok, wn / a);
        L::keep(b1, ok, un / a);
        L::keep(b2, ok, vn / a);
        L::store(&out.t[i], t_out);
        L::store(&out.b0[i], b0);
        L::store(&out.b1[i], b1);
        L::store(&out.b2[i], b2);
        // A hit lane has 0 < |det| <= max, so det > 0 exactly where its sign bit is clear.
        const std::uint64_t hit = L::bits(ok);
        out.hit_bits |= hit << i;
        out.front_bits |= (hit & ~L::sign_bits(det)) << i;
    }
    return out;
}
/// The any-hit form of intersect_batch: true exactly when intersect_batch(r, batch,
/// cull).hit_bits != 0 (the same operations up to the test of t), without the
/// barycentric divisions and the stores of the hit record, returning at the first step
/// with a hit. Each step makes one decision: t is divided out on every lane and tested
/// together with the candidate mask, where intersect_batch first branches on whether any
/// lane is a candidate: in a hierarchy's any-hit walk, one data-dependent branch a leaf
/// instead of two. TMinChecked: the caller has made sure that r.t_min >= 0 (a hierarchy's
/// walk that turns away rays that are not valid()), so the kernel does not test it again
/// (for each leaf).
template <class L, bool TMinChecked = false, template <class, std::size_t> class Batch, std::floating_point T,
          std::size_t N>
[[nodiscard]] SHADE_DETAIL_BATCH_INLINE bool intersect_batch_any(const ray<T>& r, const Batch<T, N>& batch,
                                                                 culling cull) noexcept {
    static_assert(N % L::width == 0, "the lane step must divide the batch width");
    using vec = typename L::vec;
    using mask = typename L::mask;
    if constexpr (!TMinChecked)
        if (!(r.t_min >= T(0))) return false;
    vec o_x, o_y, o_z, d_x, d_y, d_z, zero, largest, t_lo, t_hi;
    L::splat(o_x, r.origin.x);
    L::splat(o_y, r.origin.y);
    L::splat(o_z, r.origin.z);
    L::splat(d_x, r.direction.x);
    L::splat(d_y, r.direction.y);
    L::splat(d_z, r.direction.z);
    L::splat(zero, T(0));
    L::splat(largest, std::numeric_limits<T>::max());
    const bool front_only = cull == culling::back_faces;
    L::splat(t_lo, r.t_min);
    L::splat(t_hi, glm::min(r.t_max, std::numeric_limits<T>::max()));
#if defined(__GNUC__)
#pragma GCC unroll 16
#endif
    for (std::size_t k = 0; k < N / L::width; ++k) {
        // intersect_batch's operations, in its order (see there).
        vec p_x, p_y, p_z, f_x, f_y, f_z, g_x, g_y, g_z, m_x, m_y, m_z;
        load_step<L>(batch, k * L::width, p_x, p_y, p_z, f_x, f_y, f_z, g_x, g_y, g_z, m_x, m_y, m_z);
        const vec q_x = p_x - o_x;
        const vec q_y = p_y - o_y;
        const vec q_z = p_z - o_z;
        const vec c_x = d_y * q_z - q_y * d_z;
        const vec c_y = d_z * q_x - q_z * d_x;
        const vec c_z = d_x * q_y - q_x * d_y;
        const vec det = d_x * m_x + d_y * m_y + d_z * m_z;
        vec a, un, vn, t_num;
        L::abs(a, det);
        L::flip_sign(un, g_x * c_x + g_y * c_y + g_z * c_z, det);
        L::flip_sign(vn, f_x * c_x + f_y * c_y + f_z * c_z, det);
        const vec wn = a - (un + vn);
        mask candidate = (un >= zero) & (vn >= zero) & (wn >= zero) & (a > zero) & (a <= largest);
        if (front_only) candidate = candidate & (det > zero);
        // Every lane divided, candidate or not: a lane that is not (a zero det, say) may
        // give inf or NaN here, which the candidate mask discards.
        L::flip_sign(t_num, q_x * m_x + q_y * m_y + q_z * m_z, det);
        const vec t = t_num / a;
        if (L::any(candidate & (t >= t_lo) & (t <= t_hi))) return true;
    }
    return false;
}
#undef SHADE_DETAIL_BATCH_INLINE

} // namespace detail
} // namespace shade
