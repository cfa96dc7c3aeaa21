#pragma once
// shade::fuzz::input: turns libFuzzer's byte string into the scalars, vectors and choices a
// fuzz target needs.
//
// Each scalar starts with a selector byte whose low two bits choose how the payload is
// read, so that the fuzzer reaches both "meaningful" values and every bit pattern:
//   0  a special value, one byte indexing special_values() (0, -0, 1, infinities, NaN,
//      the smallest subnormal, the largest finite value, ...);
//   1  fixed point: a little-endian int16 divided by 256 (exact, range +-128), the
//      format the seed corpora use for ordinary coordinates and parameters;
//   2  wide: an int16 mantissa / 32768 times 2^e with e a signed byte, for tiny and
//      huge magnitudes (overflow gives infinity, underflow subnormals or zero);
//   3  raw: sizeof(T) bytes copied into T, every bit pattern (signalling NaN included).
// An exhausted input reads as zero bytes, so every byte string is a valid input.

#include <array>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>

#include <shade/core/types.hpp>

namespace shade::fuzz {

/// The values a selector-0 scalar picks from: every edge case of IEEE arithmetic that a
/// shading or intersection routine must survive.
template <std::floating_point T>
[[nodiscard]] constexpr std::array<T, 16> special_values() noexcept {
    using limits = std::numeric_limits<T>;
    return {T(0),           -T(0),           T(1),           T(-1),
            T(0.5),         T(2),            limits::infinity(), -limits::infinity(),
            limits::quiet_NaN(), limits::denorm_min(), limits::min(), limits::max(),
            -limits::max(), limits::epsilon(), T(1) - limits::epsilon() / T(2), T(1e-4)};
}

/// A cursor over the fuzz input.
class input {
public:
    input(const std::uint8_t* data, std::size_t size) noexcept : data_(data), size_(size) {}

    /// The next byte, or 0 once the input is exhausted.
    [[nodiscard]] std::uint8_t byte() noexcept { return pos_ < size_ ? data_[pos_++] : 0; }

    /// True once every byte has been read (further reads give zeros).
    [[nodiscard]] bool exhausted() const noexcept { return pos_ >= size_; }

    /// The next byte's lowest bit.
    [[nodiscard]] bool flag() noexcept { return (byte() & 1u) != 0; }

    /// A choice in [0, n) (n >= 1) from the next byte.
    [[nodiscard]] unsigned choice(unsigned n) noexcept { return byte() % n; }

    /// A little-endian 16-bit signed integer.
    [[nodiscard]] std::int16_t int16() noexcept {
        const auto lo = static_cast<unsigned>(byte());
        const auto hi = static_cast<unsigned>(byte());
        return static_cast<std::int16_t>(static_cast<std::uint16_t>(lo | (hi << 8u)));
    }

    /// A scalar decoded as described at the top of this file; may be NaN or infinite.
    template <std::floating_point T>
    [[nodiscard]] T scalar() noexcept {
        switch (byte() & 3u) {
        case 0: {
            constexpr auto table = special_values<T>();
            return table[byte() % table.size()];
        }
        case 1:
            return T(int16()) / T(256);
        case 2: {
            const T mantissa = T(int16()) / T(32768);
            const auto exponent = static_cast<std::int8_t>(byte());
            return std::ldexp(mantissa, exponent);
        }
        default: {
            std::array<unsigned char, sizeof(T)> bits{};
            for (auto& b : bits) b = byte();
            T x;
            std::memcpy(&x, bits.data(), sizeof(T));
            return x;
        }
        }
    }

    /// Three scalars; any length, any direction, possibly non-finite.
    template <std::floating_point T>
    [[nodiscard]] vec3<T> vector() noexcept {
        const T x = scalar<T>();
        const T y = scalar<T>();
        const T z = scalar<T>();
        return {x, y, z};
    }

private:
    const std::uint8_t* data_;
    std::size_t size_;
    std::size_t pos_ = 0;
};

/// A cursor's scalars plus running verdicts on their magnitudes, for targets whose
/// guarantees hold only for moderate or bounded numbers: `moderate` stays true while every
/// scalar read through it is finite and within moderate_limit in magnitude, `bounded`
/// while every one is within bounded_limit.
template <std::floating_point T>
struct tracking_reader {
    input& in;
    T moderate_limit;
    T bounded_limit;
    bool moderate = true;
    bool bounded = true;

    /// The next scalar (input::scalar), recorded in the verdicts.
    T scalar() {
        const T x = in.scalar<T>();
        moderate = moderate && std::isfinite(x) && std::abs(x) <= moderate_limit;
        bounded = bounded && std::isfinite(x) && std::abs(x) <= bounded_limit;
        return x;
    }
    /// Three scalars, recorded in the verdicts.
    vec3<T> vector() {
        const T x = scalar();
        const T y = scalar();
        const T z = scalar();
        return {x, y, z};
    }
};

} // namespace shade::fuzz
