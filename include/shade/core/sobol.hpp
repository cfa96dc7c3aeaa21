#pragma once
// shade::sobol_sampler: Owen-scrambled Sobol points with per-pixel decorrelation, after
// Burley 2020, "Practical Hash-based Owen Scrambling", JCGT 9(4).
//
// Each call of next_1d()/next_2d() (one "dimension" of the sample) uses the first two
// dimensions of the Sobol sequence (Sobol 1967; the van der Corput sequence in base 2 and
// the one of the primitive polynomial x + 1), so it needs no table of direction numbers,
// and decorrelates the calls instead by "padding" (Kollig and Keller 2002, "Efficient
// Multidimensional Sampling", Eurographics): the sample index is shuffled by a nested
// uniform scramble seeded by (seed, pixel, dimension) before the point is generated, and
// each coordinate is Owen-scrambled (nested uniform scramble, Owen 1995) with its own seed.
// Both scrambles are Burley's hash-based form: bit reversal, the Laine-Karras permutation
// (Laine and Karras 2011, "Stratified Sampling for Stochastic Transparency", EGSR), bit
// reversal again.
//
// What that gives: for every pixel and dimension, the points of any 2^k consecutive
// sample indices starting at a multiple of 2^k (in particular the first 2^k) form a
// (0, k, 2)-net in base 2: each of the 2^k boxes [a 2^-i, (a + 1) 2^-i) x [b 2^-(k-i),
// (b + 1) 2^-(k-i)) holds exactly one point, for every i in [0, k]. One coordinate alone
// is then stratified into 2^k equal intervals. Integrating a smooth 2D integrand with N
// scrambled net points has variance O(N^-3 (log N)) against O(N^-1) for independent
// points (Owen 1997, "Scrambled Net Variance for Integrals of Smooth Functions", Annals
// of Statistics 25(4)). Use sample counts that are powers of two.

#include <concepts>
#include <cstdint>

#include <shade/core/sampler.hpp>
#include <shade/core/types.hpp>

namespace shade {

namespace detail {

/// The generator of Sobol dimension 1 (primitive polynomial x + 1, m_1 = 1): column k of
/// its matrix is v_k, with v_0 = 2^31 and v_k = v_(k-1) xor (v_(k-1) >> 1) (Pascal's
/// triangle mod 2 read along the bits).
[[nodiscard]] constexpr std::uint32_t sobol_dimension_1(std::uint32_t index) noexcept {
    std::uint32_t result = 0;
    std::uint32_t v = 0x80000000u;
    for (; index != 0; index >>= 1) {
        if (index & 1u) result ^= v;
        v ^= v >> 1;
    }
    return result;
}

/// Sobol dimension 0: the van der Corput radical inverse in base 2, i.e. the bits of the
/// index reversed.
[[nodiscard]] constexpr std::uint32_t sobol_dimension_0(std::uint32_t index) noexcept {
    index = (index << 16) | (index >> 16);
    index = ((index & 0x00ff00ffu) << 8) | ((index & 0xff00ff00u) >> 8);
    index = ((index & 0x0f0f0f0fu) << 4) | ((index & 0xf0f0f0f0u) >> 4);
    index = ((index & 0x33333333u) << 2) | ((index & 0xccccccccu) >> 2);
    index = ((index & 0x55555555u) << 1) | ((index & 0xaaaaaaaau) >> 1);
    return index;
}

/// The Laine-Karras permutation with Burley's constants (Burley 2020, listing 3): each
/// output bit depends only on the same and the lower input bits, and every pattern of
/// those is mapped one to one, so applied to bit-reversed numbers it is a nested uniform
/// (Owen) scramble.
[[nodiscard]] constexpr std::uint32_t laine_karras_permutation(std::uint32_t x, std::uint32_t seed) noexcept {
    x += seed;
    x ^= x * 0x6c50b47cu;
    x ^= x * 0xb82f1e52u;
    x ^= x * 0xc7afe638u;
    x ^= x * 0x8d22f6e6u;
    return x;
}

/// A nested uniform scramble of the bits of x (the most significant bit first), keyed by
/// seed (Burley 2020, listing 4).
[[nodiscard]] constexpr std::uint32_t nested_uniform_scramble(std::uint32_t x, std::uint32_t seed) noexcept {
    return sobol_dimension_0(laine_karras_permutation(sobol_dimension_0(x), seed));
}

/// A 32-bit fixed-point fraction x 2^-32 as a T in [0, 1): float keeps the top 24 bits
/// (so the result never rounds up to 1), double all 32.
template <std::floating_point T>
[[nodiscard]] constexpr T fraction_of(std::uint32_t x) noexcept {
    if constexpr (sizeof(T) <= 4)
        return T(x >> 8) * T(0x1p-24);
    else
        return T(x) * T(0x1p-32);
}

} // namespace detail

/// Owen-scrambled Sobol points (see the top of this header); satisfies shade::sampler.
/// Sample indices above 2^32 - 1 are not supported (the index is 32 bits).
template <std::floating_point T>
class sobol_sampler {
public:
    using scalar_type = T;

    /// Samplers with different seeds give independent scrambles (their estimates are
    /// independent, so they can be averaged and their spread measured).
    explicit sobol_sampler(std::uint64_t seed = 0) noexcept : seed_(seed) {}

    /// Starts sample `index` of pixel (x, y).
    void start_pixel_sample(std::uint32_t x, std::uint32_t y, std::uint32_t index) noexcept {
        pixel_seed_ = detail::hash_seed(seed_, x, y);
        index_ = index;
        dimension_ = 0;
    }

    /// The next dimension: one Owen-scrambled coordinate (Sobol dimension 0).
    [[nodiscard]] T next_1d() noexcept {
        const std::uint64_t h = detail::hash_seed(pixel_seed_, dimension_++);
        const std::uint32_t i = detail::nested_uniform_scramble(index_, static_cast<std::uint32_t>(h));
        const std::uint32_t x = detail::nested_uniform_scramble(detail::sobol_dimension_0(i),
                                                                static_cast<std::uint32_t>(h >> 32));
        return detail::fraction_of<T>(x);
    }

    /// The next dimension: an Owen-scrambled point of Sobol dimensions 0 and 1.
    [[nodiscard]] vec2<T> next_2d() noexcept {
        const std::uint64_t h = detail::hash_seed(pixel_seed_, dimension_++);
        const std::uint64_t h2 = detail::mix64(h);
        const std::uint32_t i = detail::nested_uniform_scramble(index_, static_cast<std::uint32_t>(h));
        const std::uint32_t x = detail::nested_uniform_scramble(detail::sobol_dimension_0(i),
                                                                static_cast<std::uint32_t>(h >> 32));
        const std::uint32_t y = detail::nested_uniform_scramble(detail::sobol_dimension_1(i),
                                                                static_cast<std::uint32_t>(h2));
        return {detail::fraction_of<T>(x), detail::fraction_of<T>(y)};
    }

private:
    std::uint64_t seed_;
    std::uint64_t pixel_seed_ = 0;
    std::uint32_t index_ = 0;
    std::uint32_t dimension_ = 0;
};

} // namespace shade
