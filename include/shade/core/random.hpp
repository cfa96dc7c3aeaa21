#pragma once
// shade::rng: a small, fast, seedable random number generator whose output is the same on
// every platform and compiler (unlike the distributions of <random>, whose algorithms are
// implementation-defined). Used by the property checks and the examples.

#include <concepts>
#include <cstdint>

namespace shade {

/// PCG32 (O'Neill 2014, "PCG: A Family of Simple Fast Space-Efficient Statistically Good
/// Algorithms for Random Number Generation", HMC-CS-2014-0905): a 64-bit linear
/// congruential state with the XSH-RR output permutation, giving 32-bit outputs.
class rng {
public:
    /// Seeds the generator. Different `stream` values give independent sequences.
    constexpr explicit rng(std::uint64_t seed = 0x853c49e6748fea9bULL,
                           std::uint64_t stream = 0xda3e39cb94b95bdbULL) noexcept
        : increment_((stream << 1u) | 1u) {
        next_u32();
        state_ += seed;
        next_u32();
    }

    /// A uniformly distributed 32-bit integer.
    constexpr std::uint32_t next_u32() noexcept {
        const std::uint64_t old = state_;
        // Knuth's MMIX multiplier, as recommended by O'Neill for 64-bit LCG state.
        state_ = old * 6364136223846793005ULL + increment_;
        const auto xorshifted = static_cast<std::uint32_t>(((old >> 18u) ^ old) >> 27u);
        const auto rot = static_cast<std::uint32_t>(old >> 59u);
        return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
    }

    /// A uniformly distributed number in [0, 1). For float, 24 random bits are used so the
    /// result can never round up to 1; for double, 53 bits from two outputs.
    template <std::floating_point T>
    constexpr T uniform() noexcept {
        if constexpr (sizeof(T) <= 4) {
            return T(next_u32() >> 8) * T(0x1p-24);
        } else {
            const std::uint64_t hi = next_u32() >> 5; // 27 bits
            const std::uint64_t lo = next_u32() >> 6; // 26 bits
            return T((hi << 26) | lo) * T(0x1p-53);
        }
    }

private:
    std::uint64_t state_ = 0;
    std::uint64_t increment_;
};

} // namespace shade
