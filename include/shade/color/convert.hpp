#pragma once
// The whole chain from (8-bit or linear) sRGB to CIE L*a*b* and back, for a chosen white:
//   sRGB8 --decode--> linear sRGB --matrix--> XYZ (D65) --Bradford--> XYZ (white) --> L*a*b*
//
// References: IEC 61966-2-1:1999 (sRGB, clauses 5.2 and 5.3), ICC.1:2010 Annex E (Bradford
// adaptation), CIE 15:2004 section 8.2.1 (L*a*b*); see srgb.hpp, xyz.hpp and lab.hpp.
//
// sRGB is defined relative to D65. For L*a*b* relative to another white (D50 for ICC and
// graphic-arts measurements) the colour is first adapted with Bradford, as ICC colour
// management does. For white = D65 no adaptation is applied.

#include <concepts>

#include <glm/mat3x3.hpp>

#include <shade/color/lab.hpp>
#include <shade/color/srgb.hpp>
#include <shade/color/xyz.hpp>
#include <shade/core/types.hpp>

namespace shade {

/// Converts between sRGB and L*a*b* relative to one white point. Precomputes the combined
/// linear-sRGB -> XYZ(white) matrix and its inverse, so per-pixel use costs two small
/// matrix products plus the transfer and L*a*b* functions. NaN propagates in every
/// conversion; 8-bit output is not offered here (see encode_srgb8 in srgb.hpp).
template <std::floating_point T>
class srgb_lab_converter {
public:
    /// Converter for L*a*b* relative to `white` (default D65, the white of sRGB). A white
    /// other than D65 is reached by Bradford adaptation from D65. Throws
    /// shade::invalid_parameter only when bradford_adaptation does (implausible white).
    explicit srgb_lab_converter(const white_point<T>& white = white_point<T>::d65())
        : white_(white),
          to_xyz_(linear_srgb_to_xyz_matrix<T>()),
          from_xyz_(xyz_to_linear_srgb_matrix<T>()) {
        if (white == white_point<T>::d65()) return; // sRGB's own white: no adaptation
        to_xyz_ = bradford_adaptation<T>(white_point<T>::d65(), white).matrix() * to_xyz_;
        from_xyz_ = from_xyz_ * bradford_adaptation<T>(white, white_point<T>::d65()).matrix();
    }

    /// Returns the L*a*b* (relative to white()) of a linear sRGB colour.
    [[nodiscard]] lab<T> to_lab(const rgb<T>& linear) const noexcept {
        return xyz_to_lab(detail::to_xyz(to_xyz_ * linear), white_);
    }

    /// Returns the L*a*b* (relative to white()) of an 8-bit sRGB pixel.
    [[nodiscard]] lab<T> to_lab(srgb8 pixel) const noexcept {
        return to_lab(decode_srgb8<T>(pixel));
    }

    /// Returns the linear sRGB colour of an L*a*b* colour relative to white(). Colours outside
    /// the sRGB gamut give channels outside [0, 1]; nothing is clamped.
    [[nodiscard]] rgb<T> to_linear(const lab<T>& c) const noexcept {
        return from_xyz_ * detail::to_vec(lab_to_xyz(c, white_));
    }

    /// The white the L*a*b* values are relative to.
    [[nodiscard]] const white_point<T>& white() const noexcept { return white_; }

private:
    white_point<T> white_;
    glm::mat<3, 3, T> to_xyz_;   // linear sRGB -> XYZ relative to white_
    glm::mat<3, 3, T> from_xyz_; // XYZ relative to white_ -> linear sRGB
};

/// Returns the L*a*b* of a linear sRGB colour relative to `white` (default D65). Builds a
/// srgb_lab_converter each call; keep one converter for many colours.
template <std::floating_point T>
[[nodiscard]] inline lab<T> linear_srgb_to_lab(const rgb<T>& linear,
                                               const white_point<T>& white = white_point<T>::d65()) {
    return srgb_lab_converter<T>(white).to_lab(linear);
}

/// Returns the linear sRGB colour of an L*a*b* colour relative to `white` (default D65).
template <std::floating_point T>
[[nodiscard]] inline rgb<T> lab_to_linear_srgb(const lab<T>& c,
                                               const white_point<T>& white = white_point<T>::d65()) {
    return srgb_lab_converter<T>(white).to_linear(c);
}

} // namespace shade
