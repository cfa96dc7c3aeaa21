#pragma once
// The sRGB transfer function (encoded sRGB <-> linear RGB) and 8-bit quantisation.
//
// Reference: IEC 61966-2-1:1999, "Multimedia systems and equipment - Colour measurement and
// management - Part 2-1: Colour management - Default RGB colour space - sRGB",
// clause 5.2 (sRGB -> CIE XYZ, decoding) and clause 5.3 (CIE XYZ -> sRGB, encoding).
//
// Vocabulary used throughout shade/color:
//   - "linear RGB" (shade::rgb<T>) is proportional to light: what a renderer computes.
//   - "encoded sRGB" is a value in [0, 1] after the sRGB transfer function: what a PNG stores
//     divided by 255. shade uses plain T for one channel and rgb<T> for three, and every
//     function name says which side it is on (`srgb_to_linear`, `linear_to_srgb`).
//   - shade::srgb8 is encoded sRGB quantised to 8 bits, one byte per channel.
//
// Non-finite input: the transfer functions are noexcept and propagate NaN (NaN in, NaN out;
// +inf maps to +inf, -inf to -inf). Quantisation to 8 bits cannot represent NaN, so
// encode_srgb8 throws shade::invalid_parameter for NaN and clamps +-inf like any other value.

#include <cmath>
#include <concepts>
#include <cstdint>
#include <string_view>

#include <shade/core/error.hpp>
#include <shade/core/types.hpp>

namespace shade {

/// One pixel of encoded sRGB quantised to 8 bits per channel (0..255), channel order R, G, B.
/// Three bytes with no padding, so a std::vector<srgb8> is a packed RGB8 image buffer.
struct srgb8 {
    std::uint8_t r; ///< red code value, 0..255
    std::uint8_t g; ///< green code value, 0..255
    std::uint8_t b; ///< blue code value, 0..255

    friend constexpr bool operator==(const srgb8&, const srgb8&) noexcept = default;
};
static_assert(sizeof(srgb8) == 3, "srgb8 must be three packed bytes");

// IEC 61966-2-1:1999, clause 5.2 (decoding, "sRGB -> linear"):
//   C_lin = C' / 12.92                        for C' <= 0.04045
//   C_lin = ((C' + 0.055) / 1.055)^2.4        for C' >  0.04045
// The standard defines C' in [0, 1]. shade extends it to all reals by odd symmetry,
// f(-x) = -f(x), the usual "extended sRGB" convention, so that out-of-gamut values (from
// a colour outside the sRGB gamut, or a slightly negative filter result) round-trip
// instead of turning into NaN from pow of a negative base.
/// Returns the linear value of one encoded sRGB channel `c` (1 = diffuse white).
template <std::floating_point T>
[[nodiscard]] inline T srgb_to_linear(T c) noexcept {
    const T magnitude = std::abs(c);
    const T linear = magnitude <= T(0.04045)
                         ? magnitude / T(12.92)
                         : std::pow((magnitude + T(0.055)) / T(1.055), T(2.4));
    return std::copysign(linear, c);
}

// IEC 61966-2-1:1999, clause 5.3 (encoding, "linear -> sRGB"):
//   C' = 12.92 C_lin                          for C_lin <= 0.0031308
//   C' = 1.055 C_lin^(1/2.4) - 0.055          for C_lin >  0.0031308
// Extended by odd symmetry as srgb_to_linear. The two published thresholds are rounded, so
// the branches meet only to about 3e-8 (0.040449936 vs 0.040449907); both functions are
// still inverse to each other within 3e-9 in linear units near the knee.
/// Returns the encoded sRGB value of one linear channel `c` (1 = diffuse white -> 1).
template <std::floating_point T>
[[nodiscard]] inline T linear_to_srgb(T c) noexcept {
    const T magnitude = std::abs(c);
    const T encoded = magnitude <= T(0.0031308)
                          ? T(12.92) * magnitude
                          : T(1.055) * std::pow(magnitude, T(1) / T(2.4)) - T(0.055);
    return std::copysign(encoded, c);
}

/// Returns the linear RGB colour of an encoded sRGB colour, channel by channel
/// (IEC 61966-2-1 clause 5.2).
template <std::floating_point T>
[[nodiscard]] inline rgb<T> srgb_to_linear(const rgb<T>& c) noexcept {
    return {srgb_to_linear(c.x), srgb_to_linear(c.y), srgb_to_linear(c.z)};
}

/// Returns the encoded sRGB colour of a linear RGB colour, channel by channel
/// (IEC 61966-2-1 clause 5.3). Values outside [0, 1] are not clamped.
template <std::floating_point T>
[[nodiscard]] inline rgb<T> linear_to_srgb(const rgb<T>& c) noexcept {
    return {linear_to_srgb(c.x), linear_to_srgb(c.y), linear_to_srgb(c.z)};
}

/// Returns the linear RGB colour of an 8-bit sRGB pixel: code value v -> srgb_to_linear(v/255)
/// (IEC 61966-2-1 clause 5.2 with bit depth 8). Code 0 gives exactly 0, code 255 exactly 1.
template <std::floating_point T>
[[nodiscard]] inline rgb<T> decode_srgb8(srgb8 p) noexcept {
    return {srgb_to_linear(T(p.r) / T(255)), srgb_to_linear(T(p.g) / T(255)),
            srgb_to_linear(T(p.b) / T(255))};
}

namespace detail {

// One channel of encode_srgb8. Clamping to [0, 1] first is what the standard's 8-bit
// encoding (clause 5.3: 255 C' rounded to the nearest integer) needs: a linear value
// outside the gamut has no code. Ties round up: floor(x + 0.5), with x in [0, 255].
template <std::floating_point T>
[[nodiscard]] inline std::uint8_t quantise_srgb8(std::string_view name, T linear) {
    if (std::isnan(linear)) throw invalid_parameter(name, "must not be NaN", to_text(linear));
    const T clamped = linear < T(0) ? T(0) : (linear > T(1) ? T(1) : linear);
    const T code = std::floor(linear_to_srgb(clamped) * T(255) + T(0.5));
    return static_cast<std::uint8_t>(code);
}

} // namespace detail

/// Returns the 8-bit sRGB pixel of a linear RGB colour: each channel is clamped to [0, 1]
/// (so +inf -> 255 and -inf -> 0), encoded with linear_to_srgb and rounded to the nearest
/// code, ties up (IEC 61966-2-1 clause 5.3). Throws shade::invalid_parameter naming the
/// channel ("linear.r", "linear.g", "linear.b") when it is NaN.
template <std::floating_point T>
[[nodiscard]] inline srgb8 encode_srgb8(const rgb<T>& linear) {
    return {detail::quantise_srgb8("linear.r", linear.x),
            detail::quantise_srgb8("linear.g", linear.y),
            detail::quantise_srgb8("linear.b", linear.z)};
}

} // namespace shade
