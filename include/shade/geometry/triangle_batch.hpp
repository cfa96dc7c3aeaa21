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
// order (GLM's cross and dot, e1 = v1 - v0 and e2 = v2 - v0 stored at packing), and
// because the division-free early-out below only skips work when no lane can hit.
// Like the scalar code it needs the compiler not to contract a*b + c into a fused
// multiply-add differently in the two (x86-64 without -mfma never contracts; elsewhere
// compile with -ffp-contract=off). tests/geometry/test_triangle_batch.cpp checks it.
//
// The division is deferred: each lane first computes the scalar algorithm's numerators
// U = T·P, V = d·Q, T_n = e2·Q and det = e1·P without dividing, and a conservative
// division-free test (a superset of the lanes the scalar test accepts) decides whether
// any lane of the vector step can hit. Only then are u = U/det, v = V/det and
// t = T_n/det computed, for all lanes of the step at once, and the scalar algorithm's own
// tests applied to them. A ray that misses the whole batch (the common case in a
// bounding-volume hierarchy) divides nothing.
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
} // namespace detail

/// Up to N triangles in structure-of-arrays form (one array per coordinate), ready for
/// shade::intersect(ray, triangle_batch). Lanes past the packed triangles are empty and
/// never hit. Degenerate or non-finite triangles may be packed; like the scalar test they
/// never hit.
///
/// Storage: the hot arrays v0, e1 = v1 - v0 and e2 = v2 - v0 (9 N scalars) are read by
/// every intersection; v1 and v2 (6 N scalars) only by intersect_closest to build its hit
/// point, and by intersect when the batch holds coordinates so large (above max/4 in
/// magnitude) that the hit point could overflow.
template <std::floating_point T, std::size_t N = 8>
class triangle_batch {
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
            // The same operations as in moller_trumbore::intersect, so the same bits.
            const vec3<T> e1 = tri.v1 - tri.v0;
            const vec3<T> e2 = tri.v2 - tri.v0;
            set(v0_, i, tri.v0);
            set(e1_, i, e1);
            set(e2_, i, e2);
            set(v1_, i, tri.v1);
            set(v2_, i, tri.v2);
            // A lane hits only where the scalar finish step would find a unit normal; a
            // usable lane has finite edges and therefore finite vertices.
            const bool usable = detail::is_unit_normal(tri.normal());
            usable_[i] = usable ? T(1) : T(0);
            if (usable) large_ = large_ || exceeds_quarter_max(tri);
        }
    }

    /// Number of packed triangles (lanes 0 .. size()-1).
    [[nodiscard]] std::size_t size() const noexcept { return count_; }

    /// The triangle in lane i, as packed. Precondition: i < size().
    [[nodiscard]] triangle<T> triangle_at(std::size_t i) const noexcept {
        return triangle<T>{get(v0_, i), get(v1_, i), get(v2_, i)};
    }

    /// True when some usable lane has a coordinate above max/4 in magnitude, so that the
    /// hit point b0 v0 + b1 v1 + b2 v2 could overflow and must be checked per hit.
    [[nodiscard]] bool large() const noexcept { return large_; }

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
    // With every |coordinate| <= max/4 and barycentrics in [0, 1], each component of
    // b0 v0 + b1 v1 + b2 v2 is at most 3 (max/4) (1 + eps)^2 < max: it cannot overflow.
    static bool exceeds_quarter_max(const triangle<T>& tri) noexcept {
        const T quarter_max = std::numeric_limits<T>::max() / T(4);
        for (const vec3<T>& v : {tri.v0, tri.v1, tri.v2})
            for (int k = 0; k < 3; ++k)
                if (!(std::abs(v[k]) <= quarter_max)) return true;
        return false;
    }

    soa3 v0_, e1_, e2_; // hot
    soa3 v1_, v2_;      // cold: hit points only
    std::array<T, N> usable_{}; // 1 where a lane can hit, else 0 (a value vectors load)
    std::size_t count_ = 0;
    bool large_ = false;

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
    std::array<T, N> t{};         ///< ray parameter (direction units); +inf on a miss
    std::array<T, N> b0{};        ///< barycentric weight of v0
    std::array<T, N> b1{};        ///< barycentric weight of v1 (u)
    std::array<T, N> b2{};        ///< barycentric weight of v2 (v)

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
    static const auto& e1(const batch& b) noexcept { return b.e1_; }
    static const auto& e2(const batch& b) noexcept { return b.e2_; }
    static const auto& v1(const batch& b) noexcept { return b.v1_; }
    static const auto& v2(const batch& b) noexcept { return b.v2_; }
    static const auto& usable(const batch& b) noexcept { return b.usable_; }
};

/// One lane at a time: the portable form of the batch kernel (any compiler), and the
/// reference the vector form is tested against.
template <std::floating_point T>
struct scalar_lanes {
    static constexpr std::size_t width = 1; ///< lanes per step
    using vec = T;                          ///< one value per lane
    using mask = bool;                      ///< one flag per lane
    static vec load(const T* p) noexcept { return *p; }
    static void store(T* p, vec v) noexcept { *p = v; }
    static vec splat(T x) noexcept { return x; }
    static vec select(mask m, vec a, vec b) noexcept { return m ? a : b; }
    static vec keep(mask m, vec a) noexcept { return m ? a : T(0); }
    static vec abs(vec a) noexcept { return std::abs(a); }
    static vec flip_sign(vec a, vec s) noexcept { return std::signbit(s) ? -a : a; }
    static mask none() noexcept { return false; }
    static bool any(mask m) noexcept { return m; }
    static std::uint64_t bits(mask m) noexcept { return m ? 1u : 0u; }
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

/// The largest power-of-two number of bytes <= native_vector_bytes that divides N
/// scalars of T: the step of the vector kernel.
template <std::floating_point T, std::size_t N>
[[nodiscard]] constexpr std::size_t step_bytes() noexcept {
    std::size_t bytes = native_vector_bytes;
    while (bytes > N * sizeof(T) || (N * sizeof(T)) % bytes != 0) bytes /= 2;
    return bytes;
}

/// Bytes / sizeof(T) lanes at a time in GNU vector extensions, which g++ and clang++
/// compile from the same source to SSE, AVX, NEON, ... instructions (no intrinsics).
/// Comparisons give integer lanes of all ones (true) or zero.
template <std::floating_point T, std::size_t Bytes>
struct vector_lanes {
    static constexpr std::size_t width = Bytes / sizeof(T); ///< lanes per step
    using mask_int = std::conditional_t<sizeof(T) == 4, std::int32_t, std::int64_t>;
    using vec [[gnu::vector_size(Bytes)]] = T;         ///< width values
    using mask [[gnu::vector_size(Bytes)]] = mask_int; ///< width flags (0 or -1)
    static vec load(const T* p) noexcept {
        vec v;
        std::memcpy(&v, p, sizeof v);
        return v;
    }
    static void store(T* p, const vec& v) noexcept { std::memcpy(p, &v, sizeof v); }
    static vec splat(T x) noexcept {
        vec v;
        for (std::size_t i = 0; i < width; ++i) v[i] = x;
        return v;
    }
    /// a where m is set, b elsewhere, bit for bit.
    static vec select(const mask& m, const vec& a, const vec& b) noexcept {
        return reinterpret_cast<vec>((reinterpret_cast<mask>(a) & m) |
                                     (reinterpret_cast<mask>(b) & ~m));
    }
    /// a where m is set, +0 elsewhere.
    static vec keep(const mask& m, const vec& a) noexcept {
        return reinterpret_cast<vec>(reinterpret_cast<mask>(a) & m);
    }
    /// |a| (sign bit cleared), as std::abs.
    static vec abs(const vec& a) noexcept {
        return reinterpret_cast<vec>(reinterpret_cast<mask>(a) & ~sign_bits());
    }
    /// a with its sign flipped where s has its sign bit set (a times sign(s), exactly).
    static vec flip_sign(const vec& a, const vec& s) noexcept {
        return reinterpret_cast<vec>(reinterpret_cast<mask>(a) ^
                                     (reinterpret_cast<mask>(s) & sign_bits()));
    }
    static mask sign_bits() noexcept {
        return reinterpret_cast<mask>(splat(-T(0)));
    }
    static mask none() noexcept { return mask{}; }
    static bool any(const mask& m) noexcept {
        mask_int bits = 0;
        for (std::size_t i = 0; i < width; ++i) bits |= m[i];
        return bits != 0;
    }
    /// Bit i set where lane i of m is set: one movmsk instruction on x86 (these builtins
    /// are g++'s and clang++'s), a loop elsewhere.
    static std::uint64_t bits(const mask& m) noexcept {
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
#endif
        std::uint64_t out = 0;
        for (std::size_t i = 0; i < width; ++i) out |= std::uint64_t(m[i] != 0) << i;
        return out;
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

/// The batch kernel behind shade::intersect(ray, triangle_batch) (see there), L::width
/// lanes per step with the lane operations of L (scalar_lanes or vector_lanes). Each
/// lane goes through the same IEEE operations whatever L is, so every L gives the same
/// bits.
template <class L, std::floating_point T, std::size_t N>
[[nodiscard]] triangle_batch_hits<T, N> intersect_batch(const ray<T>& r,
                                                        const triangle_batch<T, N>& batch,
                                                        culling cull) noexcept {
    static_assert(N % L::width == 0, "the lane step must divide the batch width");
    using vec = typename L::vec;
    using mask = typename L::mask;
    using access = batch_access<T, N>;
    triangle_batch_hits<T, N> out;
    out.t.fill(infinity<T>);
    if (!r.valid()) return out;

    const auto& v0 = access::v0(batch);
    const auto& e1 = access::e1(batch);
    const auto& e2 = access::e2(batch);
    const auto& usable = access::usable(batch);

    const vec o_x = L::splat(r.origin.x), o_y = L::splat(r.origin.y), o_z = L::splat(r.origin.z);
    const vec d_x = L::splat(r.direction.x), d_y = L::splat(r.direction.y),
              d_z = L::splat(r.direction.z);
    const vec zero = L::splat(T(0)), one = L::splat(T(1));
    const vec loose = L::splat(T(0x1p-10)); // relative slack of the rounded tests
    const vec tiny = L::splat(T(0x1p-20));  // covers quotients that underflow to -0
    const bool front_only = cull == culling::back_faces;

    const vec t_lo = L::splat(r.t_min);
    const vec t_hi = L::splat(std::min(r.t_max, std::numeric_limits<T>::max()));
    const vec inf = L::splat(infinity<T>);
    for (std::size_t k = 0; k < N / L::width; ++k) {
        const std::size_t i = k * L::width;
        // Division-free part: the scalar code's dot and cross products in GLM's order,
        // cross(a, b) = (a.y b.z - b.y a.z, a.z b.x - b.z a.x, a.x b.y - b.x a.y) and
        // dot(a, b) = (a.x b.x + a.y b.y) + a.z b.z.
        const vec e1_x = L::load(&e1.x[i]), e1_y = L::load(&e1.y[i]), e1_z = L::load(&e1.z[i]);
        const vec e2_x = L::load(&e2.x[i]), e2_y = L::load(&e2.y[i]), e2_z = L::load(&e2.z[i]);
        const vec p_x = d_y * e2_z - e2_y * d_z;
        const vec p_y = d_z * e2_x - e2_z * d_x;
        const vec p_z = d_x * e2_y - e2_x * d_y;
        const vec dt = e1_x * p_x + e1_y * p_y + e1_z * p_z;
        const vec s_x = o_x - L::load(&v0.x[i]);
        const vec s_y = o_y - L::load(&v0.y[i]);
        const vec s_z = o_z - L::load(&v0.z[i]);
        const vec un = s_x * p_x + s_y * p_y + s_z * p_z;
        const vec q_x = s_y * e1_z - e1_y * s_z;
        const vec q_y = s_z * e1_x - e1_z * s_x;
        const vec q_z = s_x * e1_y - e1_x * s_y;
        const vec vn = d_x * q_x + d_y * q_y + d_z * q_z;

        // The candidate test (see shade::intersect below); s U is U with its sign flipped
        // by the sign of det.
        const vec a = L::abs(dt);
        const vec m = a * tiny;
        const vec su = L::flip_sign(un, dt);
        const vec sv = L::flip_sign(vn, dt);
        mask candidate = (L::load(&usable[i]) != zero) & (dt != zero) & (su >= -m) &
                         (sv >= -m) & (a - (su + sv) >= -(a * loose));
        if (front_only) candidate = candidate & (dt > zero);
        if (L::bits(candidate) == 0) {
            // No lane of this step can hit: no division (out is already all misses).
            continue;
        }

        // The scalar algorithm's divisions and tests. Its u <= 1 is implied by v >= 0 and
        // b0 = (1 - u) - v >= 0 (a rounded difference is >= 0 exactly when the exact one
        // is); t finite in [t_min, t_max] is t >= t_min and t <= min(t_max, max), as
        // t_min >= 0 is finite and NaN fails both.
        const vec tn = e2_x * q_x + e2_y * q_y + e2_z * q_z;
        const vec u = un / dt;
        const vec v = vn / dt;
        const vec b0 = one - u - v;
        const vec t = tn / dt;
        const mask ok = candidate & (u >= zero) & (v >= zero) & (b0 >= zero) & (t >= t_lo) &
                        (t <= t_hi);
        L::store(&out.t[i], L::select(ok, t, inf));
        L::store(&out.b0[i], L::keep(ok, b0));
        L::store(&out.b1[i], L::keep(ok, u));
        L::store(&out.b2[i], L::keep(ok, v));
        out.hit_bits |= L::bits(ok) << i;
        out.front_bits |= L::bits(ok & (dt > zero)) << i;
    }

    if (batch.large()) {
        // Only for batches with coordinates above max/4: the hit point must be finite,
        // as the scalar finish step requires (computed in the same order as there).
        const auto& v1 = access::v1(batch);
        const auto& v2 = access::v2(batch);
        for (std::size_t i = 0; i < N; ++i) {
            const T p_x = out.b0[i] * v0.x[i] + out.b1[i] * v1.x[i] + out.b2[i] * v2.x[i];
            const T p_y = out.b0[i] * v0.y[i] + out.b1[i] * v1.y[i] + out.b2[i] * v2.y[i];
            const T p_z = out.b0[i] * v0.z[i] + out.b1[i] * v1.z[i] + out.b2[i] * v2.z[i];
            const bool finite = std::isfinite(p_x) && std::isfinite(p_y) && std::isfinite(p_z);
            if (out.hit(i) && !finite) {
                out.hit_bits &= ~(std::uint64_t(1) << i);
                out.front_bits &= ~(std::uint64_t(1) << i);
                out.t[i] = infinity<T>;
                out.b0[i] = out.b1[i] = out.b2[i] = T(0);
            }
        }
    }
    return out;
}

} // namespace detail

/// Intersects r with every lane of batch: Möller and Trumbore's algorithm exactly as in
/// shade::moller_trumbore (Möller, Trumbore 1997, "Fast, Minimum Storage Ray-Triangle
/// Intersection", Journal of Graphics Tools 2(1):21-28, §2; see triangle.hpp for the
/// equations: P = d × e2, det = e1·P, T = o - v0, Q = T × e1, u = T·P / det,
/// v = d·Q / det, t = e2·Q / det), lane by lane, with the same culling rule and the same
/// rejection of invalid rays, degenerate triangles and t outside [t_min, t_max].
///
/// Before dividing, a lane is kept as a candidate when, with s = sign(det), a = |det|:
///     det != 0,  s U >= -m,  s V >= -m,  a - s (U + V) >= -a 2^-10,   m = a 2^-20
/// (and det > 0 under back-face culling). These are u >= 0, v >= 0 and 1 - u - v >= 0
/// multiplied by |det|, loosened so that no lane the rounded scalar test accepts can fail
/// them: m covers a quotient U/det that underflows to -0 (which the scalar test accepts
/// as u >= 0; it needs |U| < a 2^-148 or so), and 2^-10 covers the few roundings in
/// 1 - u - v (about 2^-22 relative in float). Where no lane is a candidate the result is
/// all misses without any division; otherwise the scalar tests decide, on the divided
/// values, for every lane. (Testing t before dividing too cost more than it saved.)
template <std::floating_point T, std::size_t N>
[[nodiscard]] triangle_batch_hits<T, N> intersect(const ray<T>& r, const triangle_batch<T, N>& batch,
                                                  culling cull = culling::none) noexcept {
    return detail::intersect_batch<detail::default_lanes<T, N>>(r, batch, cull);
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
    const triangle<T> tri = batch.triangle_at(i);
    batch_hit<T> out;
    out.index = i;
    out.hit.t = all.t[i];
    out.hit.barycentric = vec3<T>(all.b0[i], all.b1[i], all.b2[i]);
    out.hit.p = all.b0[i] * tri.v0 + all.b1[i] * tri.v1 + all.b2[i] * tri.v2;
    out.hit.n = tri.normal();
    out.hit.front_face = all.front_face(i);
    return out;
}

} // namespace shade
