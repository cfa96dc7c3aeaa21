#pragma once
// shade::triangle_batch: up to N triangles stored structure-of-arrays, intersected with
// one ray at a time by a branch-free, vectorized Möller-Trumbore.
//
// Usage:
//     std::array<shade::triangle<float>, 8> tris = ...;
//     const shade::triangle_batch<float, 8> batch(tris);       // pack once
//     const auto all = shade::intersect(r, batch);              // every lane: hit, t, b
//     if (auto c = shade::intersect_closest(r, batch, tris))    // nearest lane, full record
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
// Not included by <shade/shade.hpp>: include this header where you use the batch (it is
// platform-specific SIMD code with run-time CPU detection, which the umbrella leaves out).
//
// Forms of the kernel (shade/geometry/detail/triangle_batch_*.hpp), all giving the same
// bits: with g++ and clang++, GNU vector extensions at the build target's vector width
// (SSE2 on the x86-64 baseline, AVX with -mavx, NEON on ARM); other compilers, one lane
// at a time. Compile every translation unit that calls it with the same target flags (as
// for any inline code specialised per target).
//
// Run-time dispatch: on x86-64 built without -mavx (the default target), the kernel is
// also compiled for AVX (8 floats or 4 doubles per step, through gnu::target) and
// shade::intersect calls it when the CPU and OS support AVX. AVX does not include FMA, so
// both forms give the same bits. Batches of 64 bytes (16 floats, 8 or 16 doubles) go to a
// third form where the CPU has AVX-512F (16 floats or 8 doubles per step, comparisons
// into mask registers, arithmetic with embedded rounding, which cannot be contracted),
// the same bits again. The CPU is examined on the first call (a function-local static: no
// static initialiser). shade::triangle_batch_kernel() says which forms run. Define
// SHADE_NO_RUNTIME_DISPATCH to always use the build's own target.

#include <concepts>
#include <cstddef>
#include <optional>
#include <span>
#include <string>

#include <shade/core/error.hpp>
#include <shade/core/math.hpp>
#include <shade/core/types.hpp>
#include <shade/geometry/hit.hpp>
#include <shade/geometry/ray.hpp>
#include <shade/geometry/triangle.hpp>
#include <shade/geometry/detail/triangle_batch_avx.hpp>
#include <shade/geometry/detail/triangle_batch_avx512.hpp>
#include <shade/geometry/detail/triangle_batch_kernel.hpp>
#include <shade/geometry/detail/triangle_batch_vector.hpp>

namespace shade {

/// Up to N triangles in structure-of-arrays form (one array per coordinate), ready for
/// shade::intersect(ray, triangle_batch). Lanes past the packed triangles are empty and
/// never hit. Degenerate or non-finite triangles may be packed; like the scalar test they
/// never hit.
///
/// Storage: only what every intersection reads, contiguous: the arrays v0, a = v0 - v1,
/// e2 = v2 - v0 and m = a × e2, 12 N scalars (48 bytes per triangle in float, 96 in
/// double) and the count. The vertices v1 and v2, which only a full hit record needs, are
/// not copied: the caller keeps its triangles and passes them to intersect_closest (so an
/// array of batches streams nothing else; shade::triangle_bvh keeps them beside each of
/// its leaf batches, read only for the hit it returns).
/// The class is over-aligned (up to 64 bytes, see detail::batch_array_alignment) so that
/// the kernel's vector loads stay within cache lines; std::vector and new handle that
/// since C++17.
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
        }
    }

    /// Number of packed triangles (lanes 0 .. size()-1).
    [[nodiscard]] std::size_t size() const noexcept { return count_; }

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

    soa3 v0_, a_, e2_, m_; // empty lanes are all zero, so their det is 0: no hit
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
/// bit to shade::intersect<moller_trumbore>(ray, triangle of that lane, culling).
template <std::floating_point T>
struct batch_hit {
    std::size_t index = 0; ///< lane of the nearest triangle hit
    triangle_hit<T> hit;   ///< t, p, n, front_face and barycentrics of that hit
};

namespace detail {
/// True when shade::intersect(ray, triangle_batch) chooses its kernel at run time: on
/// x86-64 built without -mavx (the default target) and without SHADE_NO_RUNTIME_DISPATCH.
#if defined(__GNUC__) && defined(__x86_64__) && !defined(__AVX__) && \
    !defined(SHADE_NO_RUNTIME_DISPATCH)
inline constexpr bool batch_dispatch_at_run_time = true;
#else
inline constexpr bool batch_dispatch_at_run_time = false;
#endif
} // namespace detail

/// Which form of the batch kernel shade::intersect(ray, triangle_batch) runs on this CPU
/// with this build: "avx512f for batches of 64 bytes ..., avx for the others (selected
/// at run time)", "avx (selected at run time)", "vector <bytes> bytes" (the vector
/// width of the build's target) or "scalar" (one lane at a time). For reports and
/// benchmarks; every form gives the same bits.
[[nodiscard]] inline std::string triangle_batch_kernel() {
#if defined(__GNUC__) && defined(__x86_64__)
    if constexpr (detail::batch_dispatch_at_run_time) {
        if (detail::cpu_has_avx512f())
            return "avx512f for batches of 64 bytes (16 floats, 8 or 16 doubles), avx for the "
                   "others (selected at run time)";
        if (detail::cpu_has_avx()) return "avx (selected at run time)";
    }
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
#if defined(__GNUC__) && defined(__x86_64__)
    if constexpr (detail::batch_dispatch_at_run_time) {
        if constexpr (detail::whole_avx512_steps<T, N>) {
            if (detail::cpu_has_avx512f()) return detail::intersect_batch_avx512(r, batch, cull);
        }
        if (detail::cpu_has_avx()) return detail::intersect_batch_avx(r, batch, cull);
        return detail::intersect_batch_baseline(r, batch, cull);
    }
#endif
    return detail::intersect_batch<detail::default_lanes<T, N>>(r, batch, cull);
}

/// The nearest hit of r among the lanes of batch (the lowest lane on equal t), with the
/// full hit record exactly as shade::intersect<moller_trumbore> returns it for that
/// triangle, or nothing when no lane is hit. triangles are the ones the batch was packed
/// from, in lane order (the batch keeps only what the test reads; the record needs the
/// vertices). Throws shade::invalid_parameter naming "triangles" when their number is
/// not batch.size().
template <std::floating_point T, std::size_t N>
[[nodiscard]] std::optional<batch_hit<T>> intersect_closest(const ray<T>& r,
                                                            const triangle_batch<T, N>& batch,
                                                            std::span<const triangle<T>> triangles,
                                                            culling cull = culling::none) {
    if (triangles.size() != batch.size())
        throw invalid_parameter("triangles",
                                "must be the " + std::to_string(batch.size()) +
                                    " triangles the batch was packed from",
                                std::to_string(triangles.size()) + " triangles");
    const triangle_batch_hits<T, N> all = intersect(r, batch, cull);
    const std::optional<std::size_t> best = all.closest();
    if (!best) return std::nullopt;
    const std::size_t i = *best;
    const triangle_intersection<T> x{all.t[i], vec3<T>(all.b0[i], all.b1[i], all.b2[i]),
                                     all.front_face(i)};
    return batch_hit<T>{i, make_hit(triangles[i], x)};
}

} // namespace shade
