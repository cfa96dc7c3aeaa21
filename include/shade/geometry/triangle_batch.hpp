#pragma once
// shade::triangle_batch: up to N triangles stored structure-of-arrays, intersected with
// one ray at a time by a branch-free, vectorized Möller-Trumbore.
//
// Usage:
//     std::array<shade::triangle<float>, 8> tris = ...;
//     const shade::triangle_batch<float, 8> batch(tris);       // pack once
//     const auto all = shade::intersect(r, batch);              // every lane: hit, t, b
//     if (auto c = shade::intersect_closest(r, batch))          // nearest lane, full record
//         use(c->index, c->hit.t, c->hit.p, c->hit.n);
//
// Results are bitwise identical to the scalar shade::moller_trumbore (shade/geometry/
// triangle.hpp) on each triangle: the same hit or miss, the same t, barycentrics and
// front_face (and, from intersect_closest, the same p and n). This holds because every
// lane performs exactly the scalar algorithm's floating-point operations in the same
// order (GLM's cross and dot; a = v0 - v1, e2 = v2 - v0 and m = a × e2, minus the
// normal, computed at packing with the very expressions the scalar code uses). Like the
// scalar code it needs the compiler not to contract a*b + c into a fused multiply-add
// differently in the two (x86-64 without -mfma never contracts; elsewhere compile with
// -ffp-contract=off). tests/geometry/test_triangle_batch.cpp checks it.
//
// The division is deferred: each lane first computes the numerators U, V, W of the
// barycentrics and det, and decides hit or miss from their signs exactly as the scalar
// code does. Only for a vector step with at least one candidate lane are t, b0, b1, b2
// divided out, all lanes of the step at once. A ray that misses the whole batch (the
// common case in a bounding-volume hierarchy) divides nothing. Because the normal is
// stored, each lane does 18 multiplications and 14 additions before that decision,
// against 24 and 19 for the paper's P = d × e2, Q = s × e1 arrangement.
//
// Vectorization: the kernel is written once over a "lanes" type. With g++ and clang++ it
// uses GNU vector extensions (vector_size), which both compile from the same source to
// the target's SIMD instructions: 4 floats or 2 doubles per step with the x86-64
// baseline SSE2, 8/4 with -mavx or better, NEON on ARM. The only target-specific code
// turns a comparison mask into lane bits with the x86 movmsk builtins (a loop
// elsewhere). Other compilers get the same kernel one lane at a time
// (detail::scalar_lanes, also tested).
// Plain loops over the arrays were tried first: g++ 12 vectorized only part of them
// (not under its default -ftrapping-math) and clang++ 14 none.
// Compile every translation unit that calls it with the same target flags (as for any
// inline code specialised per target).
//
// Run-time dispatch: on x86-64 built without -mavx (the default target), the kernel is
// also compiled for AVX (detail::intersect_batch_avx, 8 floats or 4 doubles per step,
// through gnu::target) and shade::intersect calls it when the CPU and OS support AVX.
// AVX does not include FMA, so both forms give the same bits. Batches of 64 bytes (16
// floats, 8 or 16 doubles) go to a third form where the CPU has AVX-512F
// (detail::intersect_batch_avx512: 16 floats or 8 doubles per step, comparisons into
// mask registers, arithmetic through intrinsics that cannot be contracted), the same
// bits again. shade::triangle_batch_kernel() says which forms run. Define
// SHADE_NO_RUNTIME_DISPATCH to always use the build's own target.

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <type_traits>

#include <glm/geometric.hpp>

#if defined(__GNUC__) && defined(__x86_64__)
#include <immintrin.h>
#endif

#include <shade/core/error.hpp>
#include <shade/core/math.hpp>
#include <shade/core/types.hpp>
#include <shade/geometry/hit.hpp>
#include <shade/geometry/ray.hpp>
#include <shade/geometry/triangle.hpp>

namespace shade {

namespace detail {
template <std::floating_point T, std::size_t N>
struct batch_access; // reads a triangle_batch's arrays; defined below

/// Alignment of the per-lane arrays of triangle_batch and triangle_batch_hits: the largest
/// power of two up to 64 (a cache line, and an AVX-512 vector) that divides the N * sizeof(T)
/// bytes of one array. With it every array starts at a multiple of the kernel's vector
/// step, so no vector load or store straddles two cache lines (measured 3-8 % faster for
/// 8 floats with AVX than arrays aligned only to sizeof(T)).
template <std::floating_point T, std::size_t N>
[[nodiscard]] constexpr std::size_t batch_array_alignment() noexcept {
    std::size_t align = 64;
    while (align > alignof(T) && (N * sizeof(T)) % align != 0) align /= 2;
    return align;
}

/// Tag of the triangle_batch_hits constructor that leaves the lanes to the batch kernel.
struct every_lane_written {};
} // namespace detail

/// Up to N triangles in structure-of-arrays form (one array per coordinate), ready for
/// shade::intersect(ray, triangle_batch). Lanes past the packed triangles are empty and
/// never hit. Degenerate or non-finite triangles may be packed; like the scalar test they
/// never hit.
///
/// Storage: the hot arrays v0, a = v0 - v1, e2 = v2 - v0 and m = a × e2 (12 N scalars)
/// are read by every intersection; v1 and v2 (6 N scalars) only by triangle_at and
/// intersect_closest. The class is over-aligned (up to 64 bytes, see
/// detail::batch_array_alignment) so that the kernel's vector loads stay within cache
/// lines; std::vector and new handle that since C++17.
template <std::floating_point T, std::size_t N = 8>
class alignas(detail::batch_array_alignment<T, N>()) triangle_batch {
    static_assert(N > 0, "a triangle batch needs at least one lane");

public:
    using scalar_type = T;
    /// Number of lanes (triangles the batch can hold).
    static constexpr std::size_t width = N;

    /// An empty batch: no lane ever hits.
    triangle_batch() noexcept = default;

    /// Packs triangles[i] into lane i. Throws shade::invalid_parameter naming "triangles"
    /// if more than N triangles are given.
    explicit triangle_batch(std::span<const triangle<T>> triangles) {
        if (triangles.size() > N)
            throw invalid_parameter("triangles",
                                    "must hold at most " + std::to_string(N) +
                                        " triangles (the batch width)",
                                    std::to_string(triangles.size()) + " triangles");
        count_ = triangles.size();
        for (std::size_t i = 0; i < count_; ++i) {
            const triangle<T>& tri = triangles[i];
            // The same operations as in moller_trumbore::find, so the same bits.
            const vec3<T> a = tri.v0 - tri.v1;
            const vec3<T> e2 = tri.v2 - tri.v0;
            set(v0_, i, tri.v0);
            set(a_, i, a);
            set(e2_, i, e2);
            set(m_, i, glm::cross(a, e2));
            set(v1_, i, tri.v1);
            set(v2_, i, tri.v2);
        }
    }

    /// Number of packed triangles (lanes 0 .. size()-1).
    [[nodiscard]] std::size_t size() const noexcept { return count_; }

    /// The triangle in lane i, as packed. Precondition: i < size().
    [[nodiscard]] triangle<T> triangle_at(std::size_t i) const noexcept {
        return triangle<T>{get(v0_, i), get(v1_, i), get(v2_, i)};
    }

private:
    using lanes = std::array<T, N>;
    struct soa3 {
        lanes x{}, y{}, z{};
    };

    static void set(soa3& a, std::size_t i, const vec3<T>& v) noexcept {
        a.x[i] = v.x;
        a.y[i] = v.y;
        a.z[i] = v.z;
    }
    static vec3<T> get(const soa3& a, std::size_t i) noexcept {
        return vec3<T>(a.x[i], a.y[i], a.z[i]);
    }

    soa3 v0_, a_, e2_, m_; // hot; empty lanes are all zero, so their det is 0: no hit
    soa3 v1_, v2_;          // cold: triangle_at and hit points only
    std::size_t count_ = 0;

    template <std::floating_point U, std::size_t M>
    friend struct detail::batch_access;
};

/// Per-lane results of one ray against a triangle_batch. For lane i: hit(i) says whether
/// shade::moller_trumbore would report a hit; where it does, t[i], b0[i], b1[i], b2[i] and
/// front_face(i) are bitwise the scalar hit's t, barycentric and front_face. Where it
/// does not, t[i] = +infinity, the barycentrics are 0 and front_face(i) is false.
/// The flags are bit masks (bit i for lane i), which SIMD code produces in one instruction.
template <std::floating_point T, std::size_t N>
struct triangle_batch_hits {
    static_assert(N <= 64, "the hit flags are bits of a 64-bit mask");
    std::uint64_t hit_bits = 0;   ///< bit i set: lane i was hit
    std::uint64_t front_bits = 0; ///< bit i set: lane i was hit on its counter-clockwise side
    alignas(detail::batch_array_alignment<T, N>()) std::array<T, N> t; ///< ray parameter (direction units); +inf on a miss
    std::array<T, N> b0;          ///< barycentric weight of v0
    std::array<T, N> b1;          ///< barycentric weight of v1 (u)
    std::array<T, N> b2;          ///< barycentric weight of v2 (v)

    /// Every lane missed: t = +infinity, barycentrics 0.
    triangle_batch_hits() noexcept {
        t.fill(infinity<T>);
        b0.fill(T(0));
        b1.fill(T(0));
        b2.fill(T(0));
    }

    /// For the batch kernel, which writes every lane itself: the arrays are left
    /// unwritten here (filling them first would cost as much as the test of a lane).
    explicit triangle_batch_hits(detail::every_lane_written) noexcept {}

    /// True when lane i was hit.
    [[nodiscard]] bool hit(std::size_t i) const noexcept { return (hit_bits >> i) & 1u; }
    /// True when lane i was hit on its front (counter-clockwise) side.
    [[nodiscard]] bool front_face(std::size_t i) const noexcept { return (front_bits >> i) & 1u; }

    /// Number of lanes hit.
    [[nodiscard]] std::size_t count() const noexcept {
        return static_cast<std::size_t>(std::popcount(hit_bits));
    }

    /// The hit lane with the smallest t (the lowest such index on ties), or nothing.
    [[nodiscard]] std::optional<std::size_t> closest() const noexcept {
        std::optional<std::size_t> best;
        for (std::uint64_t bits = hit_bits; bits != 0; bits &= bits - 1) {
            const auto i = static_cast<std::size_t>(std::countr_zero(bits));
            if (!best || t[i] < t[*best]) best = i;
        }
        return best;
    }
};

/// The nearest hit in a triangle_batch: its lane and the full hit record, equal bit for
/// bit to shade::intersect<moller_trumbore>(ray, batch.triangle_at(index), culling).
template <std::floating_point T>
struct batch_hit {
    std::size_t index = 0; ///< lane of the nearest triangle hit
    triangle_hit<T> hit;   ///< t, p, n, front_face and barycentrics of that hit
};

namespace detail {

/// Reads a triangle_batch's arrays for the intersection routines below.
template <std::floating_point T, std::size_t N>
struct batch_access {
    using batch = triangle_batch<T, N>;
    static const auto& v0(const batch& b) noexcept { return b.v0_; }
    static const auto& a(const batch& b) noexcept { return b.a_; }
    static const auto& e2(const batch& b) noexcept { return b.e2_; }
    static const auto& m(const batch& b) noexcept { return b.m_; }
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

#if defined(__GNUC__) // g++ and clang++
/// Bytes of the vectors the kernel uses: 32 with AVX (also when AVX-512 is enabled:
/// 64-byte generic vectors measured 3x slower there, their comparisons going through mask
/// registers), else 16 (SSE2, NEON and the like). Vectors wider than the target's would
/// only be split again and, on x86-64, change the calling convention (g++ -Wpsabi).
#if defined(__AVX__)
inline constexpr std::size_t native_vector_bytes = 32;
#else
inline constexpr std::size_t native_vector_bytes = 16;
#endif

/// The largest power-of-two number of bytes <= MaxBytes that divides N scalars of T: the
/// step of the vector kernel.
template <std::floating_point T, std::size_t N, std::size_t MaxBytes = native_vector_bytes>
[[nodiscard]] constexpr std::size_t step_bytes() noexcept {
    std::size_t bytes = MaxBytes;
    while (bytes > N * sizeof(T) || (N * sizeof(T)) % bytes != 0) bytes /= 2;
    return bytes;
}

#if !defined(__AVX__) && defined(__SSE2__)
using avx_float_mask [[gnu::vector_size(32)]] = std::int32_t;
using avx_double_mask [[gnu::vector_size(32)]] = std::int64_t;
/// Bit i set where lane i of m is set, for 8 float or 4 double lanes: one vmovmskps or
/// vmovmskpd. Only the kernel compiled for AVX (intersect_batch_avx, on a CPU with AVX)
/// calls these. The AVX builtins are allowed only in a function compiled for AVX, hence a
/// function of its own; once the kernel is inlined into intersect_batch_avx, g++ 12 and
/// clang++ 14 inline this call too. It replaced two 16-byte movmsk per mask, one per
/// half, and made the float batch8 benchmark 10-14 % faster at 50 and 100 % hits.
[[gnu::target("avx")]] inline std::uint64_t movemask_avx(const avx_float_mask& m) noexcept {
    using f8 [[gnu::vector_size(32)]] = float;
    return static_cast<std::uint32_t>(__builtin_ia32_movmskps256(reinterpret_cast<f8>(m)));
}
[[gnu::target("avx")]] inline std::uint64_t movemask_avx(const avx_double_mask& m) noexcept {
    using d4 [[gnu::vector_size(32)]] = double;
    return static_cast<std::uint32_t>(__builtin_ia32_movmskpd256(reinterpret_cast<d4>(m)));
}
#endif

/// Bytes / sizeof(T) lanes at a time in GNU vector extensions, which g++ and clang++
/// compile from the same source to SSE, AVX, NEON, ... instructions (no intrinsics).
/// Comparisons give integer lanes of all ones (true) or zero.
template <std::floating_point T, std::size_t Bytes>
struct vector_lanes {
    static constexpr std::size_t width = Bytes / sizeof(T); ///< lanes per step
    using mask_int = std::conditional_t<sizeof(T) == 4, std::int32_t, std::int64_t>;
    using vec [[gnu::vector_size(Bytes)]] = T;         ///< width values
    using mask [[gnu::vector_size(Bytes)]] = mask_int; ///< width flags (0 or -1)
    [[gnu::always_inline]] static void load(vec& out, const T* p) noexcept {
        std::memcpy(&out, p, sizeof out);
    }
    [[gnu::always_inline]] static void store(T* p, const vec& v) noexcept {
        std::memcpy(p, &v, sizeof v);
    }
    [[gnu::always_inline]] static void splat(vec& out, T x) noexcept {
        for (std::size_t i = 0; i < width; ++i) out[i] = x;
    }
    /// out = a where m is set, b elsewhere, bit for bit.
    [[gnu::always_inline]] static void select(vec& out, const mask& m, const vec& a,
                                              const vec& b) noexcept {
        out = reinterpret_cast<vec>((reinterpret_cast<mask>(a) & m) |
                                    (reinterpret_cast<mask>(b) & ~m));
    }
    /// out = a where m is set, +0 elsewhere.
    [[gnu::always_inline]] static void keep(vec& out, const mask& m, const vec& a) noexcept {
        out = reinterpret_cast<vec>(reinterpret_cast<mask>(a) & m);
    }
    /// out = |a| (sign bit cleared), as std::abs.
    [[gnu::always_inline]] static void abs(vec& out, const vec& a) noexcept {
        out = reinterpret_cast<vec>(reinterpret_cast<mask>(a) & ~sign_bit());
    }
    /// out = a with its sign flipped where s has its sign bit set (a times sign(s),
    /// exactly).
    [[gnu::always_inline]] static void flip_sign(vec& out, const vec& a, const vec& s) noexcept {
        out = reinterpret_cast<vec>(reinterpret_cast<mask>(a) ^
                                    (reinterpret_cast<mask>(s) & sign_bit()));
    }
    /// The sign bit of each lane as an integer: -0 reinterpreted (0x8000... per lane).
    [[gnu::always_inline]] static mask_int sign_bit() noexcept {
        return std::bit_cast<mask_int>(-T(0));
    }
    /// Bit i set where lane i of m is set: one movmsk instruction on x86 (these builtins
    /// are g++'s and clang++'s), a loop elsewhere.
    [[gnu::always_inline]] static std::uint64_t bits(const mask& m) noexcept {
#if defined(__SSE2__)
        if constexpr (Bytes == 16 && sizeof(T) == 4) {
            using f4 [[gnu::vector_size(16)]] = float;
            return static_cast<std::uint32_t>(__builtin_ia32_movmskps(reinterpret_cast<f4>(m)));
        } else if constexpr (Bytes == 16 && sizeof(T) == 8) {
            using d2 [[gnu::vector_size(16)]] = double;
            return static_cast<std::uint32_t>(__builtin_ia32_movmskpd(reinterpret_cast<d2>(m)));
        }
#endif
#if defined(__AVX__)
        if constexpr (Bytes == 32 && sizeof(T) == 4) {
            using f8 [[gnu::vector_size(32)]] = float;
            return static_cast<std::uint32_t>(__builtin_ia32_movmskps256(reinterpret_cast<f8>(m)));
        } else if constexpr (Bytes == 32 && sizeof(T) == 8) {
            using d4 [[gnu::vector_size(32)]] = double;
            return static_cast<std::uint32_t>(__builtin_ia32_movmskpd256(reinterpret_cast<d4>(m)));
        }
#elif defined(__SSE2__)
        // 32-byte steps without a global -mavx: the kernel compiled for AVX at run time
        // (intersect_batch_avx). The AVX builtins are allowed only in functions compiled
        // for AVX, so they sit in movemask_avx, which is inlined there.
        if constexpr (Bytes == 32) return movemask_avx(m);
#endif
        std::uint64_t out = 0;
        for (std::size_t i = 0; i < width; ++i) out |= std::uint64_t(m[i] < 0) << i;
        return out;
    }
    /// Bit i set where lane i of v has its sign bit set (movmsk reads exactly that).
    [[gnu::always_inline]] static std::uint64_t sign_bits(const vec& v) noexcept {
        return bits(reinterpret_cast<mask>(v));
    }
    /// True when any lane of m is set.
    [[gnu::always_inline]] static bool any(const mask& m) noexcept {
        return bits(m) != 0;
    }
};

/// The kernel's default lanes: vectors where the compiler has GNU vector extensions.
template <std::floating_point T, std::size_t N>
using default_lanes = vector_lanes<T, step_bytes<T, N>()>;
#else
/// The kernel's default lanes: one at a time where GNU vector extensions are missing.
template <std::floating_point T, std::size_t N>
using default_lanes = scalar_lanes<T>;
#endif

#if defined(__GNUC__)
// Forced inline, so that the kernel is compiled for the instruction set of its caller:
// intersect_batch_avx below is compiled for AVX while the rest of the program may not be.
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

/// The batch kernel behind shade::intersect(ray, triangle_batch) (see there), L::width
/// lanes per step with the lane operations of L (scalar_lanes or vector_lanes). Each
/// lane goes through the same IEEE operations whatever L is, so every L gives the same
/// bits.
template <class L, std::floating_point T, std::size_t N>
[[nodiscard]] SHADE_DETAIL_BATCH_INLINE triangle_batch_hits<T, N>
intersect_batch(const ray<T>& r, const triangle_batch<T, N>& batch, culling cull) noexcept {
    static_assert(N % L::width == 0, "the lane step must divide the batch width");
    using vec = typename L::vec;
    using mask = typename L::mask;
    using access = batch_access<T, N>;
    // The one test of the ray itself, which the scalar code makes per hit (t_accepted);
    // a non-finite or zero origin or direction needs none (see moller_trumbore).
    if (!(r.t_min >= T(0))) return {};
    triangle_batch_hits<T, N> out{every_lane_written{}}; // the loop below writes every lane

    const auto& v0 = access::v0(batch);
    const auto& av = access::a(batch);
    const auto& e2 = access::e2(batch);
    const auto& mv = access::m(batch);

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
    L::splat(t_hi, std::min(r.t_max, std::numeric_limits<T>::max()));
    L::splat(inf, infinity<T>);
    // Fully unrolled (at most 16 steps): measured 1.5x faster for 16 floats under SSE2,
    // where the rolled loop reloads the ray's splats; both compilers read this pragma.
#if defined(__GNUC__)
#pragma GCC unroll 16
#endif
    for (std::size_t k = 0; k < N / L::width; ++k) {
        const std::size_t i = k * L::width;
        // The scalar code's dot and cross products in GLM's order,
        // cross(a, b) = (a.y b.z - b.y a.z, a.z b.x - b.z a.x, a.x b.y - b.x a.y) and
        // dot(a, b) = (a.x b.x + a.y b.y) + a.z b.z; flip_sign(x, det) is x * sign(det).
        vec p_x, p_y, p_z, m_x, m_y, m_z, f_x, f_y, f_z, g_x, g_y, g_z;
        load_xyz<L>(p_x, p_y, p_z, v0, i);
        load_xyz<L>(m_x, m_y, m_z, mv, i);
        load_xyz<L>(f_x, f_y, f_z, av, i);
        load_xyz<L>(g_x, g_y, g_z, e2, i);
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
#undef SHADE_DETAIL_BATCH_INLINE

#if defined(__GNUC__) && defined(__x86_64__) && !defined(__AVX__) && \
    !defined(SHADE_NO_RUNTIME_DISPATCH)
#define SHADE_DETAIL_BATCH_AVX_DISPATCH 1
/// The kernel with 32-byte steps (8 floats or 4 doubles), compiled for AVX whatever the
/// flags of the including file: the x86-64 baseline (SSE2) holds only 4 floats per step.
/// Called only where the CPU and the OS support AVX (cpu_has_avx). Without FMA (AVX does
/// not imply it) every lane performs the same IEEE operations as the SSE2 and scalar
/// forms, so the results are the same bits.
template <std::floating_point T, std::size_t N>
[[gnu::target("avx")]] [[nodiscard]] triangle_batch_hits<T, N>
intersect_batch_avx(const ray<T>& r, const triangle_batch<T, N>& batch, culling cull) noexcept {
    return intersect_batch<vector_lanes<T, step_bytes<T, N, 32>()>>(r, batch, cull);
}

/// The AVX-512 register types of T: 16 floats or 8 doubles, and a mask of as many bits.
template <std::floating_point T>
struct avx512_types;
template <>
struct avx512_types<float> {
    using vector = __m512;
    using mask = __mmask16;
};
template <>
struct avx512_types<double> {
    using vector = __m512d;
    using mask = __mmask8;
};

/// True when a batch of N lanes of T is a whole number of 64-byte AVX-512 steps (16
/// floats, 8 or 16 doubles): the batches shade::intersect sends to intersect_batch_avx512.
template <std::floating_point T, std::size_t N>
inline constexpr bool whole_avx512_steps = N * sizeof(T) % 64 == 0;

/// 64-byte steps with AVX-512F intrinsics (16 floats or 8 doubles), for the run-time
/// dispatch of the default build. GNU vector extensions of 64 bytes were measured 3x
/// slower than 32 bytes (their comparisons give vector masks, converted to and from the
/// mask registers); here a comparison writes a mask register that the next & and the
/// lane bits use as it is. The arithmetic uses the embedded-rounding intrinsics (round
/// to nearest, exceptions suppressed): the same IEEE operations as the other forms, but
/// ones the compiler cannot contract into fused multiply-adds (AVX-512F has FMA, and
/// g++'s default -ffp-contract=fast would fuse a * b - c * d), so every lane keeps the
/// scalar code's bits. Each function is compiled for AVX-512F and called only from
/// intersect_batch_avx512, into which g++ 12 and clang++ 14 inline them.
template <std::floating_point T>
struct avx512_lanes {
    static constexpr std::size_t width = 64 / sizeof(T); ///< lanes per step
    static constexpr bool is_float = sizeof(T) == 4;
    static constexpr int nearest = _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC;
    using raw = typename avx512_types<T>::vector;
    using raw_mask = typename avx512_types<T>::mask;
    /// Every lane: the masked (zeroing) forms of the arithmetic are used with it, because
    /// g++ 12's unmasked embedded-rounding intrinsics (like its bitwise ones, replaced by
    /// the vector operators ^ & ~ below) read an undefined source register and trip
    /// -Wmaybe-uninitialized once inlined; with all lanes set they are the same
    /// instructions.
    static constexpr raw_mask all = static_cast<raw_mask>(~raw_mask(0));

    /// One bit per lane (a mask register).
    struct mask {
        raw_mask m;
        friend mask operator&(const mask& a, const mask& b) noexcept {
            return {static_cast<raw_mask>(a.m & b.m)};
        }
    };

    /// width values (one zmm register). Its operators are the kernel's lane arithmetic.
    struct vec {
        raw v;
        [[gnu::target("avx512f")]] friend vec operator+(const vec& a, const vec& b) noexcept {
            if constexpr (is_float) return {_mm512_maskz_add_round_ps(all, a.v, b.v, nearest)};
            else return {_mm512_maskz_add_round_pd(all, a.v, b.v, nearest)};
        }
        [[gnu::target("avx512f")]] friend vec operator-(const vec& a, const vec& b) noexcept {
            if constexpr (is_float) return {_mm512_maskz_sub_round_ps(all, a.v, b.v, nearest)};
            else return {_mm512_maskz_sub_round_pd(all, a.v, b.v, nearest)};
        }
        [[gnu::target("avx512f")]] friend vec operator*(const vec& a, const vec& b) noexcept {
            if constexpr (is_float) return {_mm512_maskz_mul_round_ps(all, a.v, b.v, nearest)};
            else return {_mm512_maskz_mul_round_pd(all, a.v, b.v, nearest)};
        }
        [[gnu::target("avx512f")]] friend vec operator/(const vec& a, const vec& b) noexcept {
            if constexpr (is_float) return {_mm512_maskz_div_round_ps(all, a.v, b.v, nearest)};
            else return {_mm512_maskz_div_round_pd(all, a.v, b.v, nearest)};
        }
        // Ordered, quiet comparisons: false where either side is NaN, as in C++.
        [[gnu::target("avx512f")]] friend mask operator>=(const vec& a, const vec& b) noexcept {
            return compare<_CMP_GE_OQ>(a, b);
        }
        [[gnu::target("avx512f")]] friend mask operator<=(const vec& a, const vec& b) noexcept {
            return compare<_CMP_LE_OQ>(a, b);
        }
        [[gnu::target("avx512f")]] friend mask operator>(const vec& a, const vec& b) noexcept {
            return compare<_CMP_GT_OQ>(a, b);
        }
    };

    [[gnu::target("avx512f")]] static __m512i to_bits(const vec& a) noexcept {
        if constexpr (is_float) return _mm512_castps_si512(a.v);
        else return _mm512_castpd_si512(a.v);
    }
    [[gnu::target("avx512f")]] static vec from_bits(__m512i x) noexcept {
        if constexpr (is_float) return {_mm512_castsi512_ps(x)};
        else return {_mm512_castsi512_pd(x)};
    }
    /// The sign bit of every lane (-0 reinterpreted).
    [[gnu::target("avx512f")]] static __m512i sign_bit() noexcept {
        if constexpr (is_float) return _mm512_set1_epi32(std::bit_cast<std::int32_t>(-0.0f));
        else return _mm512_set1_epi64(std::bit_cast<std::int64_t>(-0.0));
    }
    template <int Predicate>
    [[gnu::target("avx512f")]] static mask compare(const vec& a, const vec& b) noexcept {
        if constexpr (is_float) return {_mm512_cmp_ps_mask(a.v, b.v, Predicate)};
        else return {_mm512_cmp_pd_mask(a.v, b.v, Predicate)};
    }

    [[gnu::target("avx512f")]] static void load(vec& out, const T* p) noexcept {
        if constexpr (is_float) out.v = _mm512_loadu_ps(p);
        else out.v = _mm512_loadu_pd(p);
    }
    [[gnu::target("avx512f")]] static void store(T* p, const vec& v) noexcept {
        if constexpr (is_float) _mm512_storeu_ps(p, v.v);
        else _mm512_storeu_pd(p, v.v);
    }
    [[gnu::target("avx512f")]] static void splat(vec& out, T x) noexcept {
        if constexpr (is_float) out.v = _mm512_set1_ps(x);
        else out.v = _mm512_set1_pd(x);
    }
    /// out = a where m is set, b elsewhere, bit for bit.
    [[gnu::target("avx512f")]] static void select(vec& out, const mask& m, const vec& a,
                                                  const vec& b) noexcept {
        if constexpr (is_float) out.v = _mm512_mask_blend_ps(m.m, b.v, a.v);
        else out.v = _mm512_mask_blend_pd(m.m, b.v, a.v);
    }
    /// out = a where m is set, +0 elsewhere.
    [[gnu::target("avx512f")]] static void keep(vec& out, const mask& m, const vec& a) noexcept {
        if constexpr (is_float) out.v = _mm512_maskz_mov_ps(m.m, a.v);
        else out.v = _mm512_maskz_mov_pd(m.m, a.v);
    }
    /// out = |a| (sign bit cleared).
    [[gnu::target("avx512f")]] static void abs(vec& out, const vec& a) noexcept {
        out = from_bits(to_bits(a) & ~sign_bit());
    }
    /// out = a with its sign flipped where s has its sign bit set.
    [[gnu::target("avx512f")]] static void flip_sign(vec& out, const vec& a, const vec& s) noexcept {
        out = from_bits(to_bits(a) ^ (to_bits(s) & sign_bit()));
    }
    /// Bit i set where lane i of m is set.
    static std::uint64_t bits(const mask& m) noexcept { return m.m; }
    /// Bit i set where lane i of v has its sign bit set.
    [[gnu::target("avx512f")]] static std::uint64_t sign_bits(const vec& v) noexcept {
        if constexpr (is_float) return _mm512_test_epi32_mask(to_bits(v), sign_bit());
        else return _mm512_test_epi64_mask(to_bits(v), sign_bit());
    }
    /// True when any lane of m is set.
    static bool any(const mask& m) noexcept { return m.m != 0; }
};

/// The kernel with 64-byte steps (avx512_lanes), compiled for AVX-512F. Called only where
/// the CPU and the OS support AVX-512F (cpu_has_avx512f) and whole_avx512_steps<T, N>.
template <std::floating_point T, std::size_t N>
[[gnu::target("avx512f")]] [[nodiscard]] triangle_batch_hits<T, N>
intersect_batch_avx512(const ray<T>& r, const triangle_batch<T, N>& batch, culling cull) noexcept {
    return intersect_batch<avx512_lanes<T>>(r, batch, cull);
}

/// The baseline kernel as a function of its own, so that shade::intersect stays a small
/// dispatcher that jumps to one kernel or the other.
template <std::floating_point T, std::size_t N>
[[gnu::noinline]] [[nodiscard]] triangle_batch_hits<T, N>
intersect_batch_baseline(const ray<T>& r, const triangle_batch<T, N>& batch, culling cull) noexcept {
    return intersect_batch<default_lanes<T, N>>(r, batch, cull);
}

/// True when this CPU and its OS support AVX (libgcc's or compiler-rt's CPU model, which
/// also checks that the OS saves the 256-bit registers). Set once, when the program
/// starts. A batch intersected before that (from another file's static initialiser)
/// reads false and takes the baseline kernel, which gives the same results.
inline const bool cpu_has_avx = [] {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx") != 0;
}();

/// True when this CPU and its OS support AVX-512F (the same CPU model, which checks that
/// the OS saves the 512-bit and mask registers), set like cpu_has_avx.
inline const bool cpu_has_avx512f = [] {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx512f") != 0;
}();
#endif

} // namespace detail

/// Which form of the batch kernel shade::intersect(ray, triangle_batch) runs on this CPU
/// with this build: "avx512f for batches of 64 bytes ..., avx for the others (selected
/// at run time)", "avx (selected at run time)", "vector <bytes> bytes" (the vector
/// width of the build's target) or "scalar" (one lane at a time). For reports and
/// benchmarks; every form gives the same bits.
[[nodiscard]] inline std::string triangle_batch_kernel() {
#if defined(SHADE_DETAIL_BATCH_AVX_DISPATCH)
    if (detail::cpu_has_avx512f)
        return "avx512f for batches of 64 bytes (16 floats, 8 or 16 doubles), avx for the "
               "others (selected at run time)";
    if (detail::cpu_has_avx) return "avx (selected at run time)";
#endif
#if defined(__GNUC__)
    return "vector " + std::to_string(detail::native_vector_bytes) + " bytes";
#else
    return "scalar";
#endif
}

/// Intersects r with every lane of batch: Möller and Trumbore's algorithm exactly as in
/// shade::moller_trumbore (Möller, Trumbore 1997, "Fast, Minimum Storage Ray-Triangle
/// Intersection", Journal of Graphics Tools 2(1):21-28, §2, in the arrangement around the
/// stored m = (v0 - v1) × e2 = -n that triangle.hpp derives: det = d·m,
/// c = d × (v0 - o), U = e2·c, V = (v0 - v1)·c), lane by lane, with the same culling rule
/// and the same rejection of invalid rays, degenerate triangles and t outside
/// [t_min, t_max].
///
/// A lane is hit when, with a = |det| and U, V multiplied by sign(det),
///     U >= 0,  V >= 0,  W = a - (U + V) >= 0,  0 < a <= max
/// (and det > 0 under back-face culling) and t = sign(det) (v0 - o)·m / a is finite and
/// in [t_min, t_max]. These are the scalar code's tests (its two branches on the sign of
/// det, made branch-free) on the same values, and the quotients t, W/a, U/a, V/a are
/// its bits. Where no lane of a vector step passes the first line, the step costs no
/// division.
template <std::floating_point T, std::size_t N>
[[nodiscard]] triangle_batch_hits<T, N> intersect(const ray<T>& r, const triangle_batch<T, N>& batch,
                                                  culling cull = culling::none) noexcept {
#if defined(SHADE_DETAIL_BATCH_AVX_DISPATCH)
    if constexpr (detail::whole_avx512_steps<T, N>) {
        if (detail::cpu_has_avx512f) return detail::intersect_batch_avx512(r, batch, cull);
    }
    if (detail::cpu_has_avx) return detail::intersect_batch_avx(r, batch, cull);
    return detail::intersect_batch_baseline(r, batch, cull);
#else
    return detail::intersect_batch<detail::default_lanes<T, N>>(r, batch, cull);
#endif
}

/// The nearest hit of r among the lanes of batch (the lowest lane on equal t), with the
/// full hit record exactly as shade::intersect<moller_trumbore> returns it for that
/// triangle, or nothing when no lane is hit.
template <std::floating_point T, std::size_t N>
[[nodiscard]] std::optional<batch_hit<T>> intersect_closest(const ray<T>& r,
                                                            const triangle_batch<T, N>& batch,
                                                            culling cull = culling::none) noexcept {
    const triangle_batch_hits<T, N> all = intersect(r, batch, cull);
    const std::optional<std::size_t> best = all.closest();
    if (!best) return std::nullopt;
    const std::size_t i = *best;
    const triangle_intersection<T> x{all.t[i], vec3<T>(all.b0[i], all.b1[i], all.b2[i]),
                                     all.front_face(i)};
    return batch_hit<T>{i, make_hit(batch.triangle_at(i), x)};
}

} // namespace shade
