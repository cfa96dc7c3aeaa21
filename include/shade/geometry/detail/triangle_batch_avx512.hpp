#pragma once
// The triangle_batch kernel on AVX-512F (16 floats or 8 doubles per step) for the run-time
// dispatch of x86-64 builds without -mavx, and the CPU test that enables it. Nothing here
// exists on other targets.
//
// Written with the compiler builtins that <immintrin.h>'s AVX-512F intrinsics are made of,
// on GNU vector types, rather than with the intrinsics: <immintrin.h> is some 45000 lines,
// which every file including shade/geometry/triangle_batch.hpp would otherwise parse.
// Where g++ and clang++ name a builtin differently (the arithmetic with embedded rounding
// and the per-lane select), both forms are here; the comparisons are the same builtins in
// both.

#include <bit>
#include <concepts>
#include <cstddef>
#include <cstdint>

#include <shade/geometry/detail/triangle_batch_kernel.hpp>

#if defined(__GNUC__) && defined(__x86_64__)
namespace shade::detail {

/// True when this CPU and its OS support AVX-512F (libgcc's or compiler-rt's CPU model,
/// which checks that the OS saves the 512-bit and mask registers). Detected on the first
/// call, in a function-local static, so that including this header adds no static
/// initialiser.
[[nodiscard]] inline bool cpu_has_avx512f() noexcept {
    static const bool has = [] {
        __builtin_cpu_init();
        return __builtin_cpu_supports("avx512f") != 0;
    }();
    return has;
}

/// True when a batch of N lanes of T is a whole number of 64-byte AVX-512 steps (16
/// floats, 8 or 16 doubles): the batches shade::intersect sends to intersect_batch_avx512.
template <std::floating_point T, std::size_t N>
inline constexpr bool whole_avx512_steps = N * sizeof(T) % 64 == 0;

/// The AVX-512F operations of the kernel on one zmm register of T (16 floats or 8
/// doubles) and one mask register (a bit per lane). The arithmetic rounds to nearest with
/// exceptions suppressed (embedded rounding, {rn-sae}): the same IEEE operations as the
/// other forms of the kernel, but ones the compiler cannot contract into fused
/// multiply-adds (AVX-512F has FMA, and g++'s default -ffp-contract=fast would fuse
/// a * b - c * d), so every lane keeps the scalar code's bits.
template <std::floating_point T>
struct avx512_ops;

/// Embedded rounding: to nearest (_MM_FROUND_TO_NEAREST_INT, 0) with exceptions
/// suppressed (_MM_FROUND_NO_EXC, 8).
inline constexpr int avx512_nearest = 8;
/// Rounding argument of the comparisons: the current direction (_MM_FROUND_CUR_DIRECTION).
inline constexpr int avx512_current = 4;
/// Comparison predicates (the _CMP_*_OQ of <immintrin.h>): ordered and quiet, so false
/// where either side is NaN, as in C++.
inline constexpr int avx512_ge = 0x1d; // _CMP_GE_OQ
inline constexpr int avx512_le = 0x12; // _CMP_LE_OQ
inline constexpr int avx512_gt = 0x1e; // _CMP_GT_OQ
/// Integer comparison "less than" (_MM_CMPINT_LT).
inline constexpr int avx512_int_lt = 1;

template <>
struct avx512_ops<float> {
    using lane_int = int;
    using vec [[gnu::vector_size(64)]] = float;
    using ints [[gnu::vector_size(64)]] = lane_int;
    using mask = std::uint16_t;
    static constexpr mask all = 0xffff;

#if defined(__clang__)
    [[gnu::target("avx512f")]] static vec add(vec a, vec b) noexcept {
        return __builtin_ia32_addps512(a, b, avx512_nearest);
    }
    [[gnu::target("avx512f")]] static vec sub(vec a, vec b) noexcept {
        return __builtin_ia32_subps512(a, b, avx512_nearest);
    }
    [[gnu::target("avx512f")]] static vec mul(vec a, vec b) noexcept {
        return __builtin_ia32_mulps512(a, b, avx512_nearest);
    }
    [[gnu::target("avx512f")]] static vec div(vec a, vec b) noexcept {
        return __builtin_ia32_divps512(a, b, avx512_nearest);
    }
    /// m ? a : b per lane.
    [[gnu::target("avx512f")]] static vec select(mask m, vec a, vec b) noexcept {
        return __builtin_ia32_selectps_512(m, a, b);
    }
#else
    // g++'s builtins are the masked forms: every lane written (mask all), the source
    // operand a (never read).
    [[gnu::target("avx512f")]] static vec add(vec a, vec b) noexcept {
        return __builtin_ia32_addps512_mask(a, b, a, all, avx512_nearest);
    }
    [[gnu::target("avx512f")]] static vec sub(vec a, vec b) noexcept {
        return __builtin_ia32_subps512_mask(a, b, a, all, avx512_nearest);
    }
    [[gnu::target("avx512f")]] static vec mul(vec a, vec b) noexcept {
        return __builtin_ia32_mulps512_mask(a, b, a, all, avx512_nearest);
    }
    [[gnu::target("avx512f")]] static vec div(vec a, vec b) noexcept {
        return __builtin_ia32_divps512_mask(a, b, a, all, avx512_nearest);
    }
    /// m ? a : b per lane.
    [[gnu::target("avx512f")]] static vec select(mask m, vec a, vec b) noexcept {
        return __builtin_ia32_blendmps_512_mask(b, a, m);
    }
#endif
    template <int Predicate>
    [[gnu::target("avx512f")]] static mask compare(vec a, vec b) noexcept {
        return __builtin_ia32_cmpps512_mask(a, b, Predicate, all, avx512_current);
    }
    /// Bit i set where lane i of x is negative (as a signed integer: its top bit set).
    [[gnu::target("avx512f")]] static mask negative(ints x) noexcept {
        return __builtin_ia32_cmpd512_mask(x, ints{}, avx512_int_lt, all);
    }
};

template <>
struct avx512_ops<double> {
    using lane_int = long long;
    using vec [[gnu::vector_size(64)]] = double;
    using ints [[gnu::vector_size(64)]] = lane_int;
    using mask = std::uint8_t;
    static constexpr mask all = 0xff;

#if defined(__clang__)
    [[gnu::target("avx512f")]] static vec add(vec a, vec b) noexcept {
        return __builtin_ia32_addpd512(a, b, avx512_nearest);
    }
    [[gnu::target("avx512f")]] static vec sub(vec a, vec b) noexcept {
        return __builtin_ia32_subpd512(a, b, avx512_nearest);
    }
    [[gnu::target("avx512f")]] static vec mul(vec a, vec b) noexcept {
        return __builtin_ia32_mulpd512(a, b, avx512_nearest);
    }
    [[gnu::target("avx512f")]] static vec div(vec a, vec b) noexcept {
        return __builtin_ia32_divpd512(a, b, avx512_nearest);
    }
    /// m ? a : b per lane.
    [[gnu::target("avx512f")]] static vec select(mask m, vec a, vec b) noexcept {
        return __builtin_ia32_selectpd_512(m, a, b);
    }
#else
    // g++'s builtins are the masked forms: every lane written (mask all), the source
    // operand a (never read).
    [[gnu::target("avx512f")]] static vec add(vec a, vec b) noexcept {
        return __builtin_ia32_addpd512_mask(a, b, a, all, avx512_nearest);
    }
    [[gnu::target("avx512f")]] static vec sub(vec a, vec b) noexcept {
        return __builtin_ia32_subpd512_mask(a, b, a, all, avx512_nearest);
    }
    [[gnu::target("avx512f")]] static vec mul(vec a, vec b) noexcept {
        return __builtin_ia32_mulpd512_mask(a, b, a, all, avx512_nearest);
    }
    [[gnu::target("avx512f")]] static vec div(vec a, vec b) noexcept {
        return __builtin_ia32_divpd512_mask(a, b, a, all, avx512_nearest);
    }
    /// m ? a : b per lane.
    [[gnu::target("avx512f")]] static vec select(mask m, vec a, vec b) noexcept {
        return __builtin_ia32_blendmpd_512_mask(b, a, m);
    }
#endif
    template <int Predicate>
    [[gnu::target("avx512f")]] static mask compare(vec a, vec b) noexcept {
        return __builtin_ia32_cmppd512_mask(a, b, Predicate, all, avx512_current);
    }
    /// Bit i set where lane i of x is negative (as a signed integer: its top bit set).
    [[gnu::target("avx512f")]] static mask negative(ints x) noexcept {
        return __builtin_ia32_cmpq512_mask(x, ints{}, avx512_int_lt, all);
    }
};

/// The kernel's lanes for 64-byte steps (16 floats or 8 doubles) on avx512_ops: a
/// comparison writes a mask register, which the next & and the lane bits use as it is
/// (the comparisons of 64-byte GNU vectors would give vector masks, converted to and from
/// the mask registers at every step). Each function is compiled for AVX-512F and called
/// only from intersect_batch_avx512, into which g++ 12 and clang++ 14 inline them.
template <std::floating_point T>
struct avx512_lanes {
    using ops = avx512_ops<T>;
    static constexpr std::size_t width = 64 / sizeof(T); ///< lanes per step
    using raw = typename ops::vec;
    using raw_ints = typename ops::ints;

    /// One bit per lane (a mask register).
    struct mask {
        typename ops::mask m;
        friend mask operator&(const mask& a, const mask& b) noexcept {
            return {static_cast<typename ops::mask>(a.m & b.m)};
        }
    };

    /// width values (one zmm register). Its operators are the kernel's lane arithmetic.
    struct vec {
        raw v;
        [[gnu::target("avx512f")]] friend vec operator+(const vec& a, const vec& b) noexcept {
            return {ops::add(a.v, b.v)};
        }
        [[gnu::target("avx512f")]] friend vec operator-(const vec& a, const vec& b) noexcept {
            return {ops::sub(a.v, b.v)};
        }
        [[gnu::target("avx512f")]] friend vec operator*(const vec& a, const vec& b) noexcept {
            return {ops::mul(a.v, b.v)};
        }
        [[gnu::target("avx512f")]] friend vec operator/(const vec& a, const vec& b) noexcept {
            return {ops::div(a.v, b.v)};
        }
        [[gnu::target("avx512f")]] friend mask operator>=(const vec& a, const vec& b) noexcept {
            return {ops::template compare<avx512_ge>(a.v, b.v)};
        }
        [[gnu::target("avx512f")]] friend mask operator<=(const vec& a, const vec& b) noexcept {
            return {ops::template compare<avx512_le>(a.v, b.v)};
        }
        [[gnu::target("avx512f")]] friend mask operator>(const vec& a, const vec& b) noexcept {
            return {ops::template compare<avx512_gt>(a.v, b.v)};
        }
    };

    /// The sign bit of every lane as an integer (-0 reinterpreted).
    [[gnu::target("avx512f")]] static raw_ints sign_bit() noexcept {
        // A scalar operand of a vector operation is broadcast to every lane.
        return raw_ints{} | std::bit_cast<typename ops::lane_int>(-T(0));
    }

    [[gnu::target("avx512f")]] static void load(vec& out, const T* p) noexcept {
        // __builtin_memcpy (g++ and clang++ only, as is this block): no <cstring> needed.
        __builtin_memcpy(&out.v, p, sizeof out.v);
    }
    [[gnu::target("avx512f")]] static void store(T* p, const vec& v) noexcept {
        __builtin_memcpy(p, &v.v, sizeof v.v);
    }
    [[gnu::target("avx512f")]] static void splat(vec& out, T x) noexcept {
        for (std::size_t i = 0; i < width; ++i) out.v[i] = x;
    }
    /// out = a where m is set, b elsewhere, bit for bit.
    [[gnu::target("avx512f")]] static void select(vec& out, const mask& m, const vec& a,
                                                  const vec& b) noexcept {
        out.v = ops::select(m.m, a.v, b.v);
    }
    /// out = a where m is set, +0 elsewhere.
    [[gnu::target("avx512f")]] static void keep(vec& out, const mask& m, const vec& a) noexcept {
        out.v = ops::select(m.m, a.v, raw{});
    }
    /// out = |a| (sign bit cleared).
    [[gnu::target("avx512f")]] static void abs(vec& out, const vec& a) noexcept {
        out.v = reinterpret_cast<raw>(reinterpret_cast<raw_ints>(a.v) & ~sign_bit());
    }
    /// out = a with its sign flipped where s has its sign bit set.
    [[gnu::target("avx512f")]] static void flip_sign(vec& out, const vec& a, const vec& s) noexcept {
        out.v = reinterpret_cast<raw>(reinterpret_cast<raw_ints>(a.v) ^
                                      (reinterpret_cast<raw_ints>(s.v) & sign_bit()));
    }
    /// Bit i set where lane i of m is set.
    static std::uint64_t bits(const mask& m) noexcept { return m.m; }
    /// Bit i set where lane i of v has its sign bit set.
    [[gnu::target("avx512f")]] static std::uint64_t sign_bits(const vec& v) noexcept {
        return ops::negative(reinterpret_cast<raw_ints>(v.v));
    }
    /// True when any lane of m is set.
    static bool any(const mask& m) noexcept { return m.m != 0; }
};

/// The kernel with 64-byte steps (avx512_lanes), compiled for AVX-512F. Called only where
/// the CPU and the OS support AVX-512F (cpu_has_avx512f) and whole_avx512_steps<T, N>.
/// Batch: triangle_batch or vertex_batch.
template <template <class, std::size_t> class Batch, std::floating_point T, std::size_t N>
[[gnu::target("avx512f")]] [[nodiscard]] triangle_batch_hits<T, N>
intersect_batch_avx512(const ray<T>& r, const Batch<T, N>& batch, culling cull) noexcept {
    return intersect_batch<avx512_lanes<T>>(r, batch, cull);
}

} // namespace shade::detail
#endif
