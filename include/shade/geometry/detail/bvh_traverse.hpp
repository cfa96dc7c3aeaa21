#pragma once
// The traversal behind shade::bvh and shade::triangle_bvh: the conservative slab test of
// four (or eight) float boxes at once, and the ordered depth-first walk. Internal: use
// shade/geometry/bvh.hpp.
//
// The four boxes of a node are tested in one 16-byte GNU vector (g++ and clang++ compile
// it to SSE on the x86-64 baseline, NEON on ARM); other compilers test them one at a time.
// On x86-64 with g++ or clang++, nodes of eight children are tested in one 32-byte vector
// by a walk compiled for AVX (a function attribute, whatever the flags of the including
// file), which a hierarchy uses only where the CPU has AVX (bvh_node_width).

#include <array>
#include <bit>
#include <cmath>
#include <concepts>
#include <cstdint>
#include <limits>
#include <type_traits>

#include <shade/core/math.hpp>
#include <shade/core/types.hpp>
#include <shade/geometry/aabb.hpp>
#include <shade/geometry/detail/bvh_build.hpp>
#include <shade/geometry/detail/cpu.hpp>
#include <shade/geometry/ray.hpp>

namespace shade::detail {

/// How a ray is scaled for the box tests. Most rays are not: when every direction
/// component is 0 or has a magnitude in [2^-125, 2^125], its float reciprocal is a finite
/// normal float (or +-inf for 0, which the slab test handles). Otherwise the direction is
/// multiplied by 2^exponent, which brings its largest |component| into [0.5, 1) (exact: a
/// power of two), so that the float reciprocal of every component that is then a normal
/// float neither overflows nor loses precision as a subnormal, whatever the direction's
/// length (a float direction of 1e-40, a double one of 1e-300 or 1e300); ray parameters
/// then scale by 2^-exponent, computed in double (exact for float rays) and rounded
/// outward to float.
template <std::floating_point T>
struct bvh_ray_scale {
    bool scaled = false;
    int exponent = 0;
    T direction_factor = T(1); ///< 2^exponent, or 0 where that is not a normal T
    double t_factor = 1.0;     ///< 2^-exponent, or 0 where that is not a normal double

    /// No scaling.
    bvh_ray_scale() = default;
    /// No scaling where the direction does not need it, else the scale described above.
    explicit bvh_ray_scale(const vec3<T>& direction) noexcept {
        if (needed(direction)) [[unlikely]]
            scale(direction);
    }

    /// True when some direction component is nonzero with a magnitude outside
    /// [2^-125, 2^125].
    [[nodiscard]] static bool needed(const vec3<T>& direction) noexcept {
        return !(usable(direction.x) && usable(direction.y) && usable(direction.z));
    }

    /// The direction's component d times 2^exponent.
    [[nodiscard]] T direction(T d) const noexcept {
        if (!scaled) return d;
        return direction_factor != T(0) ? d * direction_factor : times_power_of_two(d, exponent);
    }
    /// A float no smaller than the ray parameter t in scaled units.
    [[nodiscard]] float t_up(T t) const noexcept {
        if (!scaled) return float_up(t);
        return next_float_up(static_cast<float>(scaled_t(t)));
    }
    /// A float no larger than the ray parameter t in scaled units.
    [[nodiscard]] float t_down(T t) const noexcept {
        if (!scaled) return float_down(t);
        return next_float_down(static_cast<float>(scaled_t(t)));
    }

private:
    [[nodiscard]] static bool usable(T d) noexcept {
        const T a = std::abs(d);
        return a == T(0) || (a >= T(0x1p-125) && a <= T(0x1p+125));
    }
    void scale(const vec3<T>& direction) noexcept {
        scaled = true;
        exponent = power_of_two_rescale_exponent(direction);
        direction_factor = normal_or_zero(times_power_of_two(T(1), exponent));
        t_factor = normal_or_zero(times_power_of_two(1.0, -exponent));
    }
    template <std::floating_point U>
    [[nodiscard]] static U normal_or_zero(U x) noexcept {
        return std::isnormal(x) ? x : U(0);
    }
    // t 2^-exponent in double: a product by a normal power of two is exact unless it
    // underflows (then the rounding outward to float covers it); times_power_of_two where
    // 2^-exponent itself is not a normal double.
    [[nodiscard]] double scaled_t(T t) const noexcept {
        const double u = static_cast<double>(t);
        return t_factor != 0.0 ? u * t_factor : times_power_of_two(u, -exponent);
    }
};

/// The smallest normal float, 2^-126: a scaled direction component at least this large has
/// a finite float reciprocal of full precision.
inline constexpr float bvh_min_normal = 0x1p-126f;

/// The box-test values of an axis along which the scaled direction d_k is below
/// bvh_min_normal (zero included): the ray moves along it by at most delta = |d_k| t_max
/// (unscaled), so its coordinate stays in [o_k - delta, o_k + delta] for every t in range.
/// The axis is tested as that interval against the slab, for all t at once: reciprocal
/// +inf, near plane lo, far plane hi, origin_near the interval's top rounded up and
/// origin_far its bottom rounded down. Then (lo - origin_near) inf is +inf (the box is
/// rejected) when lo lies above the interval, and (hi - origin_far) inf is -inf when hi
/// lies below it; otherwise the products are -inf, +inf or NaN (a plane touching the
/// interval: 0 x inf), none of which rejects the box (the test ignores NaN).
struct bvh_parallel_axis {
    float origin_near;
    float origin_far;

    template <std::floating_point T>
    bvh_parallel_axis(T o, T d, T t_max) noexcept {
        // In double: exact for float rays; for double rays within a few double ulps,
        // far below the float step the rounding outward adds.
        const double delta = d == T(0) ? 0.0 : std::abs(static_cast<double>(d)) * static_cast<double>(t_max);
        origin_near = next_float_up(static_cast<float>(static_cast<double>(o) + delta));
        origin_far = next_float_down(static_cast<float>(static_cast<double>(o) - delta));
    }
};

/// What the box tests need of a ray of scalar T, in float, with its direction scaled by
/// bvh_ray_scale (so are all ray parameters): per axis the reciprocal of the scaled
/// direction, which plane is near (lo when the direction's sign bit is clear, else hi),
/// and the origin rounded so that each slab distance errs outward. For a float ray the
/// origin is exact; for a double ray, it is rounded up where it is subtracted from the
/// near plane and down for the far plane (or the reverse for a negative direction), so
/// the computed near distance can only be smaller and the far one larger. The far
/// distances are then enlarged by E = 1 + 2 gamma(n) (Ize 2013, see shade::intersect(ray,
/// aabb)): n = 3 roundings for float rays (subtraction, reciprocal, product), n = 4 for
/// double rays, whose reciprocal is rounded twice (to double, then to float). E is
/// applied to the reciprocal (inv_far = inv E, rounded) rather than to each far distance
/// ((plane - o) inv, rounded, times E, rounded): either way a far distance is the exact
/// one times E and n + 1 rounding factors (1 + e_i), |e_i| <= 2^-24, so it has the same
/// bound, and the test has one multiplication fewer per node. An axis
/// whose scaled direction component is below bvh_min_normal is tested as in
/// bvh_parallel_axis. This is the scalar form of bvh_ray4 (used where GNU vectors are
/// missing).
#if !defined(__GNUC__)
struct bvh_float_ray {
    using lanes = std::array<float, 4>;
    std::array<float, 3> inv;           ///< 1 / scaled direction, per axis
    std::array<float, 3> inv_far;       ///< inv E, the factor of the far distances
    std::array<float, 3> origin_near;   ///< origin, rounded against the near plane
    std::array<float, 3> origin_far;    ///< origin, rounded against the far plane
    std::array<std::size_t, 3> near_plane; ///< index of the near plane in bvh_node<4>::planes
    float t_min = 0.0f;                 ///< the ray's t_min, scaled and rounded down

    template <std::floating_point T>
    bvh_float_ray(const ray<T>& r, const bvh_ray_scale<T>& scale) noexcept {
        constexpr bool exact = sizeof(T) == sizeof(float);
        const float enlarge = 1.0f + 2.0f * rounding_gamma<float>(exact ? 3 : 4);
        t_min = scale.t_down(r.t_min);
        for (std::size_t k = 0; k < 3; ++k) {
            const T d = scale.direction(r.direction[int(k)]);
            const T o = r.origin[int(k)];
            if (scale.scaled && !(std::abs(d) >= T(bvh_min_normal))) {
                const bvh_parallel_axis axis(o, r.direction[int(k)], r.t_max);
                inv[k] = infinity<float>;
                inv_far[k] = infinity<float>;
                near_plane[k] = 2 * k;
                origin_near[k] = axis.origin_near;
                origin_far[k] = axis.origin_far;
                continue;
            }
            const bool negative = std::signbit(d);
            inv[k] = static_cast<float>(T(1) / d);
            inv_far[k] = inv[k] * enlarge;
            near_plane[k] = 2 * k + (negative ? 1 : 0);
            // Near plane minus origin: rounding the origin up makes it smaller for a
            // positive direction (and the distance, a positive multiple, smaller too).
            origin_near[k] = negative ? float_down(o) : float_up(o);
            origin_far[k] = negative ? float_up(o) : float_down(o);
        }
    }
};
#endif

#if defined(__GNUC__)
using bvh_f4 [[gnu::vector_size(16)]] = float;
using bvh_i4 [[gnu::vector_size(16)]] = std::int32_t;

[[gnu::always_inline]] inline unsigned bvh_bits(const bvh_i4& m) noexcept {
#if defined(__SSE__)
    return static_cast<unsigned>(__builtin_ia32_movmskps(reinterpret_cast<bvh_f4>(m)));
#else
    unsigned out = 0;
    for (int i = 0; i < 4; ++i) out |= unsigned(m[i] != 0) << i;
    return out;
#endif
}

using bvh_u4 [[gnu::vector_size(16)]] = std::uint32_t;

/// next_float_up on each lane, in the same integer arithmetic.
[[gnu::always_inline]] inline bvh_f4 bvh_next_up(const bvh_f4& f) noexcept {
    const auto b = reinterpret_cast<bvh_u4>(f + 0.0f); // -0 becomes +0
    const bvh_u4 negative = b >> 31;
    const auto finite = reinterpret_cast<bvh_u4>(b != 0x7f80'0000u); // all ones unless +infinity
    return reinterpret_cast<bvh_f4>(b + ((1u - 2u * negative) & finite));
}

using bvh_f8 [[gnu::vector_size(32)]] = float;
#if defined(__x86_64__)
using bvh_i8 [[gnu::vector_size(32)]] = std::int32_t;
/// bvh_bits for eight lanes, in the AVX walk.
[[gnu::target("avx")]] inline unsigned bvh_bits8(const bvh_i8& m) noexcept {
    return static_cast<unsigned>(__builtin_ia32_movmskps256(reinterpret_cast<bvh_f8>(m)));
}

/// out = lane k (0, 1 or 2) of v in all eight lanes (a shuffle of the register: a
/// constant k once the loop that calls it is unrolled).
[[gnu::always_inline]] inline void bvh_lane8(bvh_f8& out, const bvh_f4& v, std::size_t k) noexcept {
    if (k == 0) out = __builtin_shufflevector(v, v, 0, 0, 0, 0, 0, 0, 0, 0);
    else if (k == 1) out = __builtin_shufflevector(v, v, 1, 1, 1, 1, 1, 1, 1, 1);
    else out = __builtin_shufflevector(v, v, 2, 2, 2, 2, 2, 2, 2, 2);
}
#endif

/// a = the lane-wise maximum (Max) or minimum of t and a, keeping a where t is NaN: maxps or
/// minps for four lanes (not always formed from a selection), a selection for eight.
template <bool Max, class Lanes>
[[gnu::always_inline]] inline void bvh_keep(Lanes& a, const Lanes& t) noexcept {
#if defined(__SSE__)
    if constexpr (sizeof a == 16) a = Max ? __builtin_ia32_maxps(t, a) : __builtin_ia32_minps(t, a); else
#endif
    a = (Max ? t > a : t < a) ? t : a;
}

/// bvh_float_ray's values (scaled by `scale`) in every lane of Lanes (bvh_f4, bvh_f8) and
/// the byte offsets of the near and far planes in a node, as the box test reads them;
/// computed once per ray, without branches (the direction's signs vary from ray to ray).
template <class Lanes>
struct bvh_ray_lanes {
    using lanes = Lanes;
    std::array<Lanes, 3> inv;
    std::array<Lanes, 3> inv_far; ///< inv E (see bvh_float_ray)
    std::array<Lanes, 3> origin_near;
    std::array<Lanes, 3> origin_far;
    std::array<std::uint32_t, 4> near_offset; ///< [k < 3]: byte offset of planes[near_plane[k]]
    std::array<std::uint32_t, 4> far_offset;  ///< [k < 3]: byte offset of planes[near_plane[k] ^ 1]
    Lanes t_min;
    std::uint32_t octant; ///< bit k set where direction component k has its sign bit set (bvh_node::visit)

    template <std::floating_point T>
    [[gnu::always_inline]] explicit bvh_ray_lanes(const ray<T>& r, const bvh_ray_scale<T>& scale) noexcept
        : t_min(Lanes{} + scale.t_down(r.t_min)) {
        constexpr float enlarge = 1.0f + 2.0f * rounding_gamma<float>(sizeof(T) == sizeof(float) ? 3 : 4);
        const vec3<T> d = !scale.scaled ? r.direction
                                        : vec3<T>(scale.direction(r.direction.x), scale.direction(r.direction.y),
                                                  scale.direction(r.direction.z));
        const vec3<T>& o = r.origin;
        const bvh_f4 d3{static_cast<float>(d.x), static_cast<float>(d.y), static_cast<float>(d.z), 1.0f};
        // 1 / d per axis, rounded to float: for a float ray one division of the four lanes
        // (lane 3 divides by 1), for a double ray in double, then rounded.
        bvh_f4 inv3;
        if constexpr (sizeof(T) == sizeof(float))
            inv3 = 1.0f / d3;
        else
            inv3 = bvh_f4{static_cast<float>(T(1) / d.x), static_cast<float>(T(1) / d.y),
                          static_cast<float>(T(1) / d.z), 1.0f};
        // All ones where the direction's sign bit is set (rounding to float keeps the
        // sign, also of a zero or of a component that underflows).
        bvh_i4 negative = reinterpret_cast<bvh_i4>(d3) >> 31;
        const bvh_f4 o3{static_cast<float>(o.x), static_cast<float>(o.y), static_cast<float>(o.z), 0.0f};
        bvh_f4 up = o3;
        bvh_f4 down = o3;
        if constexpr (sizeof(T) != sizeof(float)) {
            up = bvh_next_up(o3);
            down = -bvh_next_up(-o3);
        }
        const auto select = [&](const bvh_f4& if_negative, const bvh_f4& otherwise) {
            return reinterpret_cast<bvh_f4>((reinterpret_cast<bvh_i4>(if_negative) & negative) |
                                            (reinterpret_cast<bvh_i4>(otherwise) & ~negative));
        };
        bvh_f4 near3 = select(down, up);
        bvh_f4 far3 = select(up, down);
        // Axes along which the scaled direction is below the smallest normal float: only
        // a scaled ray has them (an unscaled one may have a zero component, which the
        // reciprocal +-inf handles as bvh_parallel_axis would).
        for (int k = 0; scale.scaled && k < 3; ++k) {
            if (std::abs(d[k]) >= T(bvh_min_normal)) continue;
            const bvh_parallel_axis axis(o[k], r.direction[k], r.t_max);
            inv3[k] = infinity<float>;
            negative[k] = 0;
            near3[k] = axis.origin_near;
            far3[k] = axis.origin_far;
        }
        const bvh_f4 inv_far3 = inv3 * enlarge; // +-inf stays +-inf
        for (std::size_t k = 0; k < 3; ++k) {
#if defined(__x86_64__)
            if constexpr (sizeof(Lanes) == 32) {
                // Lane k of each four-lane vector into eight lanes, register to register:
                // these values are on the chain from the ray's division to the first node
                // test, where a store and a broadcast load would add their latency.
                bvh_lane8(inv[k], inv3, k);
                bvh_lane8(inv_far[k], inv_far3, k);
                bvh_lane8(origin_near[k], near3, k);
                bvh_lane8(origin_far[k], far3, k);
            } else
#endif
            {
                inv[k] = Lanes{} + inv3[k];
                inv_far[k] = Lanes{} + inv_far3[k];
                origin_near[k] = Lanes{} + near3[k];
                origin_far[k] = Lanes{} + far3[k];
            }
        }
        octant = bvh_bits(negative) & 7u;
        // Plane 2 k + 1 (hi) is near where the direction is negative, else plane 2 k.
        const bvh_i4 near_plane = bvh_i4{0, 2, 4, 0} + (negative & 1);
        const bvh_i4 near_bytes = near_plane * static_cast<std::int32_t>(sizeof(Lanes));
        const bvh_i4 far_bytes = (near_plane ^ 1) * static_cast<std::int32_t>(sizeof(Lanes));
        __builtin_memcpy(near_offset.data(), &near_bytes, sizeof near_offset);
        __builtin_memcpy(far_offset.data(), &far_bytes, sizeof far_offset);
    }
};
using bvh_ray4 = bvh_ray_lanes<bvh_f4>;

/// bvh_ray_scale<T>::needed(d), for a float direction in one comparison of three lanes.
template <std::floating_point T>
[[gnu::always_inline]] inline bool bvh_scale_needed(const vec3<T>& d) noexcept {
    if constexpr (sizeof(T) != sizeof(float)) {
        return bvh_ray_scale<T>::needed(d);
    } else {
        const auto a = reinterpret_cast<bvh_f4>(reinterpret_cast<bvh_i4>(bvh_f4{d.x, d.y, d.z, 0.0f}) & 0x7fff'ffff);
        return bvh_bits((a == 0.0f) | ((a >= 0x1p-125f) & (a <= 0x1p+125f))) != 0xfu;
    }
}

/// r.valid() (see shade::ray), the same answer: for a float ray in two comparisons of
/// four lanes each (origin and direction finite, 0 <= t_min <= t_max, NaN failing every
/// comparison) and one for a nonzero direction, instead of a branch per test; other
/// rays call r.valid().
template <std::floating_point T>
[[gnu::always_inline]] inline bool bvh_ray_valid(const ray<T>& r) noexcept {
    if constexpr (sizeof(T) != sizeof(float) || sizeof(ray<T>) != 8 * sizeof(float)) {
        return r.valid();
    } else {
        // The ray's 32 bytes (no padding: 3 + 3 + 1 + 1 floats): origin x, y, z and
        // direction x; direction y, z, t_min, t_max.
        bvh_f4 a, b;
        __builtin_memcpy(&a, &r, sizeof a);
        __builtin_memcpy(&b, reinterpret_cast<const unsigned char*>(&r) + sizeof a, sizeof b);
        constexpr float big = std::numeric_limits<float>::max();
        const bvh_f4 b_low{-big, -big, 0.0f, b[2]};
        const bvh_f4 b_high{big, big, infinity<float>, infinity<float>};
        // Finite: -big <= x <= big; t_min in [0, +inf], t_max in [t_min, +inf].
        const bvh_i4 in_range = (a >= -big) & (a <= big) & (b >= b_low) & (b <= b_high);
        const bool non_zero = ((bvh_bits(a != 0.0f) & 8u) | (bvh_bits(b != 0.0f) & 3u)) != 0;
        return bvh_bits(in_range) == 0xfu && non_zero;
    }
}

#if defined(__x86_64__)
/// For a float ray in the walk compiled for AVX: true when r.valid() and its direction
/// needs no scaling (!bvh_ray_scale<float>::needed), from the ray's 32 bytes as eight lanes
/// (origin, direction, t_min, t_max) in one pair of comparisons: |origin| <= the largest
/// float (finite), each |direction component| zero or in [2^-125, 2^125], t_min and t_max
/// in [0, +inf] (NaN failing every comparison), some component nonzero, t_min <= t_max.
[[gnu::target("avx")]] inline bool bvh_ray_plain8(const ray<float>& r) noexcept {
    static_assert(sizeof(ray<float>) == sizeof(bvh_f8));
    bvh_f8 a;
    __builtin_memcpy(&a, &r, sizeof a);
    constexpr float big = std::numeric_limits<float>::max();
    constexpr float inf = infinity<float>;
    // The magnitudes of the origin and direction; t_min and t_max as they are (a negative
    // one then fails >= 0).
    const bvh_i8 magnitude{0x7fff'ffff, 0x7fff'ffff, 0x7fff'ffff, 0x7fff'ffff, 0x7fff'ffff, 0x7fff'ffff, -1, -1};
    const auto m = reinterpret_cast<bvh_f8>(reinterpret_cast<bvh_i8>(a) & magnitude);
    const bvh_f8 low{0.0f, 0.0f, 0.0f, 0x1p-125f, 0x1p-125f, 0x1p-125f, 0.0f, 0.0f};
    const bvh_f8 high{big, big, big, 0x1p+125f, 0x1p+125f, 0x1p+125f, inf, inf};
    const bvh_i8 zero = m == 0.0f;
    const unsigned in_range = bvh_bits8((m >= low) & (m <= high)) | (bvh_bits8(zero) & 0x38u);
    return in_range == 0xffu && (bvh_bits8(zero) & 0x38u) != 0x38u && r.t_min <= r.t_max;
}
#endif

/// The conservative slab test of r against node's boxes (as many as Lanes holds) within
/// [t_min, t_max]: bit j set where child j's box is entered, t_enter[j] where (bvh_keep
/// ignores a NaN slab distance).
template <std::size_t W, class Lanes>
[[gnu::always_inline]] inline unsigned bvh_test_boxes(const bvh_node<W>& node, const bvh_ray_lanes<Lanes>& r,
                                                      const Lanes& t_max, Lanes& t_enter) noexcept {
    static_assert(sizeof(Lanes) == sizeof(node.planes[0]));
    const auto* planes = reinterpret_cast<const unsigned char*>(node.planes.data());
    Lanes near = r.t_min;
    Lanes far = t_max; // each far distance is enlarged already (inv_far)
    // Called with constants, forced inline (in a large translation unit g++ may otherwise
    // call it, its vectors then passing through memory): the ray stays in registers.
    const auto slab = [&](std::size_t k) __attribute__((always_inline)) {
        Lanes lo, hi;
        __builtin_memcpy(&lo, planes + r.near_offset[k], sizeof lo);
        __builtin_memcpy(&hi, planes + r.far_offset[k], sizeof hi);
        bvh_keep<true>(near, (lo - r.origin_near[k]) * r.inv[k]);
        bvh_keep<false>(far, (hi - r.origin_far[k]) * r.inv_far[k]);
    };
    slab(0), slab(1), slab(2);
    t_enter = near;
    const auto entered = near <= far;
#if defined(__x86_64__)
    if constexpr (sizeof entered == 32) return bvh_bits8(entered); else
#endif
    return bvh_bits(entered);
}
#endif

#if !defined(__GNUC__)
using bvh_ray4 = bvh_float_ray;

template <std::floating_point T>
inline bool bvh_scale_needed(const vec3<T>& d) noexcept {
    return bvh_ray_scale<T>::needed(d);
}

template <std::floating_point T>
inline bool bvh_ray_valid(const ray<T>& r) noexcept {
    return r.valid();
}

/// The four-box test one box at a time, where GNU vectors are missing.
inline unsigned bvh_test_boxes(const bvh_node<4>& node, const bvh_float_ray& r, float t_max,
                               std::array<float, 4>& t_enter) noexcept {
    unsigned bits = 0;
    for (std::size_t j = 0; j < 4; ++j) {
        float near = r.t_min;
        float far = t_max;
        for (std::size_t k = 0; k < 3; ++k) {
            const std::size_t n = r.near_plane[k];
            near = max_ignoring_nan((node.planes[n][j] - r.origin_near[k]) * r.inv[k], near);
            far = min_ignoring_nan((node.planes[n ^ 1u][j] - r.origin_far[k]) * r.inv_far[k], far);
        }
        t_enter[j] = near;
        bits |= unsigned(near <= far) << j;
    }
    return bits;
}
#endif

/// Asks for the cache line holding p ahead of its use (nothing where there is no builtin).
/// Forced inline: g++ finds a function around the builtin free of side effects and would
/// remove its calls.
#if defined(__GNUC__)
[[gnu::always_inline]] inline void bvh_prefetch(const void* p) noexcept { __builtin_prefetch(p); }
#else
inline void bvh_prefetch(const void*) noexcept {}
#endif

/// Asks for the first sizeof(bvh_node<W>) bytes (a whole node) of a child stacked for
/// later, so that they are near when it is popped: an inner node at nodes + child, a
/// leaf's first item at leaf_base + leaf_first(child) LeafBytes.
template <std::size_t LeafBytes, std::size_t W>
[[gnu::always_inline]] inline void bvh_prefetch_child(const bvh_node<W>* nodes, const void* leaf_base,
                                                      std::uint32_t child) noexcept {
    const auto* p = is_leaf_ref(child)
                        ? static_cast<const unsigned char*>(leaf_base) + std::size_t(leaf_first(child)) * LeafBytes
                        : reinterpret_cast<const unsigned char*>(nodes + child);
    for (std::size_t line = 0; line < sizeof(bvh_node<W>); line += 64) bvh_prefetch(p + line);
}

/// Entries of the traversal stack: a node reference and where the ray enters its box. A
/// path holds at most 76 nodes (the binary depth bound, bvh_builder::median_depth + 28),
/// each pushing at most W - 1 entries: 228 for four children, 532 for eight.
struct bvh_stack_entry {
    std::uint32_t ref;
    float t;
};
template <std::size_t W>
inline constexpr std::size_t bvh_stack_size = W == 4 ? 256 : 544;

/// The order in which bvh_traverse visits the children of a node that the ray enters.
enum class bvh_order {
    child,   ///< the stored order (no comparisons)
    nearest, ///< the nearest first, the others in no particular order
    sorted,  ///< nearest first, then by entry distance
    octant,  ///< two: the nearer first; three or more: the node's order for the ray's octant
             ///< (bvh_node::visit), no comparisons. Nodes of eight in a walk with AVX2's
             ///< variable shifts only; the other walks take `nearest` instead (bvh_order_in)
};

/// The order a walk takes when asked for `order`: `nearest` for `octant` where the walk
/// lacks AVX2's variable shifts of eight lanes (`variable_shifts` false), which put a
/// node's entered children in visit order in a few instructions
/// (bvh_entered_in_visit_order); without them that costs about what the order saves.
[[nodiscard]] constexpr bvh_order bvh_order_in(bvh_order order, bool variable_shifts) noexcept {
    return order == bvh_order::octant && !variable_shifts ? bvh_order::nearest : order;
}

/// True where the whole build targets AVX2 (then the walk compiled for AVX has its shifts).
#if defined(__AVX2__)
inline constexpr bool bvh_build_has_avx2 = true;
#else
inline constexpr bool bvh_build_has_avx2 = false;
#endif

#if defined(__GNUC__) && defined(__x86_64__)
/// The entered children of a node of eight, `bits` (child j at bit j), in the order
/// `visit` (one of bvh_node<8>::visit): bit p set where the child at position p was
/// entered. Each lane p shifts the entered bits right by its child's index: AVX2's
/// variable shifts (vpsrlvd) in the AVX-512 walk or an AVX2 build.
[[gnu::always_inline]] inline unsigned bvh_entered_in_visit_order(unsigned bits, std::uint32_t visit) noexcept {
    using lanes_u32 [[gnu::vector_size(32)]] = std::uint32_t;
    const lanes_u32 child = ((lanes_u32{} + visit) >> lanes_u32{0, 3, 6, 9, 12, 15, 18, 21}) & 7u;
    const lanes_u32 entered = ((lanes_u32{} + bits) >> child) << 31; // the sign bit: entered
    return bvh_bits8(reinterpret_cast<bvh_i8>(entered));
}
#endif

/// True when r is valid and needs no scaling (the common case), in the walk of Ray: for
/// a float ray in the AVX walk bvh_ray_plain8, else bvh_ray_valid and bvh_scale_needed.
template <class Ray, std::floating_point T>
[[gnu::always_inline]] inline bool bvh_ray_plain(const ray<T>& r) noexcept {
#if defined(__GNUC__) && defined(__x86_64__)
    if constexpr (sizeof(typename Ray::lanes) == 32 && std::is_same_v<T, float>) return bvh_ray_plain8(r); else
#endif
    return bvh_ray_valid(r) && !bvh_scale_needed(r.direction);
}

/// bvh_traverse's walk over nodes of W children (inlined there and in bvh_walk_wide); with
/// Validate, a ray that is not valid() visits nothing. With LeafBytes > 0, every child
/// put on the stack is prefetched (see bvh_traverse).
template <bvh_order Order, bool Validate, std::size_t LeafBytes, class Ray, std::size_t W, std::floating_point T,
          class Leaf>
[[gnu::always_inline]] inline void bvh_walk(const bvh_node<W>* nodes, const ray<T>& r, const T& t_max, Leaf& leaf,
                                            const void* leaf_base) {
    // Built only for the rare rays that need scaling, so that the common case stays a few
    // inlined comparisons (with Validate, one test for both questions; the rare rays that
    // fail it are asked each question apart).
    bvh_ray_scale<T> scale;
    if constexpr (Validate) {
        if (!bvh_ray_plain<Ray>(r)) [[unlikely]] {
            if (!bvh_ray_valid(r)) return;
            if (bvh_scale_needed(r.direction)) scale = bvh_ray_scale<T>(r.direction);
        }
    } else if (bvh_scale_needed(r.direction)) [[unlikely]] {
        scale = bvh_ray_scale<T>(r.direction);
    }
    const Ray fr(r, scale);
    typename Ray::lanes t_enter;
    float t_max_f = scale.t_up(t_max);
    typename Ray::lanes t_max_lanes = typename Ray::lanes{} + t_max_f;
    std::array<bvh_stack_entry, bvh_stack_size<W>> stack;
    std::size_t top = 0;
    std::uint32_t ref = 0;
    for (;;) {
        while (!is_leaf_ref(ref)) {
            const bvh_node<W>& node = nodes[ref];
            // The child references are in the node's last cache line, read only after the
            // box test: request it with the planes.
            bvh_prefetch(node.child.data());
            unsigned bits = bvh_test_boxes(node, fr, t_max_lanes, t_enter);
            if (bits == 0) goto pop;
            {
                const unsigned entered = bits;
                const auto i0 = static_cast<std::size_t>(std::countr_zero(bits));
                bits &= bits - 1;
                if (bits == 0) {
                    ref = node.child[i0];
                    continue;
                }
                const auto i1 = static_cast<std::size_t>(std::countr_zero(bits));
                bits &= bits - 1;
                if (bits == 0) {
                    // Two: go to the nearer, stack the other.
                    const bool first_nearer = Order == bvh_order::child || t_enter[i0] <= t_enter[i1];
                    const std::size_t go = first_nearer ? i0 : i1, later = first_nearer ? i1 : i0;
                    stack[top++] = {node.child[later], t_enter[later]};
                    if constexpr (LeafBytes != 0) bvh_prefetch_child<LeafBytes>(nodes, leaf_base, node.child[later]);
                    ref = node.child[go];
                    continue;
                }
#if defined(__GNUC__) && defined(__x86_64__)
                if constexpr (Order == bvh_order::octant) {
                    // Three or more: stack all but the first of the octant's order, far
                    // first (so that they are popped near first), and go to the first.
                    static_assert(W == 8);
                    const std::uint32_t visit = node.visit[fr.octant];
                    const auto child_at = [visit](unsigned p) { return std::size_t(visit >> (3 * p) & 7u); };
                    unsigned in_order = bvh_entered_in_visit_order(entered, visit);
                    const auto first = static_cast<unsigned>(std::countr_zero(in_order));
                    in_order &= in_order - 1;
                    do {
                        const auto p = static_cast<unsigned>(std::bit_width(in_order) - 1);
                        const std::size_t j = child_at(p);
                        stack[top++] = {node.child[j], t_enter[j]};
                        if constexpr (LeafBytes != 0) bvh_prefetch_child<LeafBytes>(nodes, leaf_base, node.child[j]);
                        in_order ^= 1u << p;
                    } while (in_order != 0);
                    ref = node.child[child_at(first)];
                    continue;
                }
#endif
                // Three or more: stack them all, then (sorted) sort them so that the
                // nearest is on top and pop it, or (nearest) take the nearest off the stack
                // and fill its place with the top entry: a linear scan, cheaper than the
                // sort. The sort also orders the later pops, which prunes more only where
                // a hit is found before them (a pop beyond the nearest hit is skipped).
                const std::size_t base = top;
                stack[top++] = {node.child[i0], t_enter[i0]};
                stack[top++] = {node.child[i1], t_enter[i1]};
                for (; bits != 0; bits &= bits - 1) {
                    const auto i = static_cast<std::size_t>(std::countr_zero(bits));
                    stack[top++] = {node.child[i], t_enter[i]};
                }
                if constexpr (LeafBytes != 0)
                    for (std::size_t a = base; a < top; ++a)
                        bvh_prefetch_child<LeafBytes>(nodes, leaf_base, stack[a].ref);
                if constexpr (Order == bvh_order::nearest) {
                    std::size_t best = base;
                    for (std::size_t a = base + 1; a < top; ++a)
                        if (stack[a].t < stack[best].t) best = a;
                    ref = stack[best].ref;
                    stack[best] = stack[--top];
                } else {
                    for (std::size_t a = base + 1; Order == bvh_order::sorted && a < top; ++a) {
                        const bvh_stack_entry e = stack[a];
                        std::size_t b = a;
                        for (; b > base && stack[b - 1].t < e.t; --b) stack[b] = stack[b - 1];
                        stack[b] = e;
                    }
                    ref = stack[--top].ref;
                }
                continue;
            }
        pop:
            do {
                if (top == 0) return;
                --top;
            } while (stack[top].t > t_max_f);
            ref = stack[top].ref;
        }
        if (leaf(leaf_first(ref), leaf_count(ref), std::bool_constant<sizeof(typename Ray::lanes) == 32>{})) return;
        t_max_f = scale.t_up(t_max);
        t_max_lanes = typename Ray::lanes{} + t_max_f;
        do {
            if (top == 0) return;
            --top;
        } while (stack[top].t > t_max_f);
        ref = stack[top].ref;
    }
}

#if defined(__GNUC__) && defined(__x86_64__) && (defined(__AVX__) || !defined(SHADE_NO_RUNTIME_DISPATCH))
#define SHADE_DETAIL_BVH_WIDE 1 // this build has the eight-wide walk (undefined at the end)
/// bvh_walk over nodes of eight, compiled for AVX (without FMA: leaf tests inlined here
/// give the baseline build's bits); used only where the CPU has AVX (bvh_node_width).
template <bvh_order Order, bool Validate, std::size_t LeafBytes, std::floating_point T, class Leaf>
[[gnu::target("avx")]] void bvh_walk_wide(const bvh_node<8>* nodes, const ray<T>& r, const T& t_max, Leaf& leaf,
                                          const void* leaf_base) {
    bvh_walk<Order, Validate, LeafBytes, bvh_ray_lanes<bvh_f8>>(nodes, r, t_max, leaf, leaf_base);
}
#endif

#if defined(SHADE_DETAIL_BVH_WIDE) && !defined(__clang__) && !defined(__AVX512F__) && !defined(SHADE_NO_RUNTIME_DISPATCH)
#define SHADE_DETAIL_BVH_WIDE512 1 // this build has the eight-wide walk for AVX-512 too (undefined at the end)
/// bvh_walk_wide compiled for AVX-512 (F, VL, BW, DQ, with BMI): the same eight-lane
/// vectors and code, in the instructions such CPUs add (AVX2, the EVEX forms, BMI). AVX-512F
/// brings fused multiply-add, which g++ would contract a * b + c into by default
/// (-ffp-contract=fast), changing the inlined leaf tests' bits: contraction is off in this
/// function and in all that is inlined into it, so its hits are bvh_walk_wide's bit for
/// bit. Only for g++: clang++ decides contraction where an expression is written (in the
/// leaf tests' headers), not in the function they are inlined into, so clang++ builds use
/// bvh_walk_wide. Used only where the CPU has that set (cpu_has_avx512_walk) and
/// bvh_avx512_walk allows it; not compiled where the build targets AVX-512 itself.
template <bvh_order Order, bool Validate, std::size_t LeafBytes, std::floating_point T, class Leaf>
[[gnu::target("avx512f,avx512vl,avx512bw,avx512dq,bmi,bmi2,lzcnt,popcnt"), gnu::optimize("fp-contract=off")]] void
bvh_walk_wide512(const bvh_node<8>* nodes, const ray<T>& r, const T& t_max, Leaf& leaf, const void* leaf_base) {
    bvh_walk<Order, Validate, LeafBytes, bvh_ray_lanes<bvh_f8>>(nodes, r, t_max, leaf, leaf_base);
}

/// True when this CPU and its OS support what bvh_walk_wide512 is compiled for (libgcc's
/// CPU model, which checks that the OS saves the 512-bit and mask registers; every CPU
/// with AVX-512 has LZCNT and POPCNT). Detected on the first call, in a function-local
/// static, so that including this header adds no static initialiser.
[[nodiscard]] inline bool cpu_has_avx512_walk() noexcept {
    static const bool has = [] {
        __builtin_cpu_init();
        return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
               __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq") &&
               __builtin_cpu_supports("bmi") && __builtin_cpu_supports("bmi2");
    }();
    return has;
}
#endif

/// Whether traversal may take the eight-wide walk compiled for AVX-512 where the build has
/// it and the CPU supports it (true); false: the walk compiled for AVX. For tests, which
/// run both walks on a CPU that has AVX-512; set it only while no thread traverses.
inline bool bvh_avx512_walk = true;

/// Whether this build has the walk compiled for AVX-512 and this CPU can run it (what
/// traversal takes while bvh_avx512_walk allows it).
[[nodiscard]] inline bool bvh_avx512_walk_available() noexcept {
#if defined(SHADE_DETAIL_BVH_WIDE512)
    return cpu_has_avx512_walk();
#else
    return false;
#endif
}

/// bvh_walk over nodes of four, as a function of its own (bvh_traverse is only the choice).
template <bvh_order Order, bool Validate, std::size_t LeafBytes, std::floating_point T, class Leaf>
void bvh_walk_four(const bvh_node<4>* nodes, const ray<T>& r, const T& t_max, Leaf& leaf, const void* leaf_base) {
    bvh_walk<Order, Validate, LeafBytes, bvh_ray4>(nodes, r, t_max, leaf, leaf_base);
}

/// The children per node (4 or 8) a build uses when `requested` are asked for.
[[nodiscard]] inline std::size_t bvh_node_width([[maybe_unused]] std::size_t requested) noexcept {
#if defined(SHADE_DETAIL_BVH_WIDE)
    if (requested == 8 && cpu_has_avx()) return 8;
#endif
    return 4;
}

/// Walks the nodes of tree (of either width) whose boxes r enters, and calls leaf(first,
/// count, avx) for every leaf reached, avx being std::true_type in the walk compiled for
/// AVX (a leaf test may then use AVX inline) and std::false_type otherwise; stops when
/// leaf returns true (any-hit). Order: the order of the children (see bvh_order). t_max is
/// read again after each leaf (a closest-hit
/// leaf shrinks it), which prunes the boxes and the stacked entries beyond it. Validate:
/// a ray that is not valid() (see shade::ray) visits nothing, tested in the walk with the
/// test for scaling; without it the caller has tested that. LeafBytes > 0: the leaves'
/// items are LeafBytes apart from leaf_base, and every child stacked for later is
/// prefetched when it is stacked (its node, or its leaf's first item), so that it waits
/// less for memory when popped (pays where the stacked children are nearly all visited,
/// any-hit walks, and the hierarchy is beyond the first-level cache).
/// Precondition: the tree has nodes, and r is valid unless Validate.
template <bvh_order Order, bool Validate = false, std::size_t LeafBytes = 0, std::floating_point T, class Leaf>
[[gnu::always_inline]] inline void bvh_traverse(const bvh_tree& tree, const ray<T>& r, const T& t_max, Leaf&& leaf,
                                                const void* leaf_base = nullptr) {
#if defined(SHADE_DETAIL_BVH_WIDE)
    if (!tree.wide_nodes.empty()) {
#if defined(SHADE_DETAIL_BVH_WIDE512)
        if (bvh_avx512_walk && cpu_has_avx512_walk())
            return bvh_walk_wide512<Order, Validate, LeafBytes>(tree.wide_nodes.data(), r, t_max, leaf, leaf_base);
#endif
        return bvh_walk_wide<bvh_order_in(Order, bvh_build_has_avx2), Validate, LeafBytes>(tree.wide_nodes.data(), r,
                                                                                           t_max, leaf, leaf_base);
    }
#endif
    bvh_walk_four<bvh_order_in(Order, false), Validate, LeafBytes>(tree.nodes.data(), r, t_max, leaf, leaf_base);
}
#undef SHADE_DETAIL_BVH_WIDE
#undef SHADE_DETAIL_BVH_WIDE512

} // namespace shade::detail
