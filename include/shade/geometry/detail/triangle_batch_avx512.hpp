#pragma once
// The triangle_batch kernel with AVX-512F intrinsics (16 floats or 8 doubles per step)
// for the run-time dispatch of x86-64 builds without -mavx, and the CPU test that enables
// it. Nothing here exists on other targets.

#include <bit>
#include <concepts>
#include <cstddef>
#include <cstdint>

#include <shade/geometry/detail/triangle_batch_kernel.hpp>

#if defined(__GNUC__) && defined(__x86_64__)
#include <immintrin.h>

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
/// dispatch of the default build. The comparisons of 64-byte GNU vector extensions give
/// vector masks, converted to and from the mask registers at every step; here a comparison writes a mask register that the next & and the
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

} // namespace shade::detail
#endif
