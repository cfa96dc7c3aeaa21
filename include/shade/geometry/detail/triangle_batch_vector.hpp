#pragma once
// The triangle_batch kernel's lanes in GNU vector extensions (vector_size), which g++
// and clang++ compile from the same source to the target's SIMD instructions: 4 floats or
// 2 doubles per step with the x86-64 baseline SSE2, 8/4 with -mavx or better, NEON on
// ARM. The only target-specific code turns a comparison mask into lane bits with the x86
// movmsk builtins (a loop elsewhere). Without GNU vector extensions the default lanes are
// scalar_lanes (triangle_batch_kernel.hpp).

#include <bit>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <type_traits>

#include <shade/geometry/detail/triangle_batch_kernel.hpp>

namespace shade::detail {

#if defined(__GNUC__) // g++ and clang++
/// Bytes of the vectors the kernel uses: 32 with AVX (also when AVX-512 is enabled: the
/// comparisons of 64-byte generic vectors give vector masks, converted to and from the
/// mask registers at every step; triangle_batch_avx512.hpp uses the mask registers
/// directly), else 16 (SSE2, NEON and the like). Vectors wider than the target's would
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
/// clang++ 14 inline this call too. A single vmovmskps or vmovmskpd reads the whole
/// mask, where the generic 32-byte vector would take two 16-byte movmsk, one per half.
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
        // __builtin_memcpy (g++ and clang++ only, as is this block): no <cstring> needed.
        __builtin_memcpy(&out, p, sizeof out);
    }
    [[gnu::always_inline]] static void store(T* p, const vec& v) noexcept {
        __builtin_memcpy(p, &v, sizeof v);
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

} // namespace shade::detail
