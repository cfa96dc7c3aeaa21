#pragma once
// CIE 1931 XYZ tristimulus values, reference white points, the linear-sRGB <-> XYZ matrices
// and Bradford chromatic adaptation between white points.
//
// References:
//   - IEC 61966-2-1:1999, "Default RGB colour space - sRGB", clause 3 (primaries
//     R (0.64, 0.33), G (0.30, 0.60), B (0.15, 0.06); white D65 (0.3127, 0.3290)) and
//     clause 5.2 (the RGB -> XYZ matrix, printed to 4 decimals).
//   - SMPTE RP 177-1993, "Derivation of Basic Television Color Equations": how the
//     RGB -> XYZ matrix follows from the primaries' and the white's chromaticities.
//   - ICC.1:2010 (profile version 4.3), clause 7.2.16 (PCS illuminant D50 =
//     (0.9642, 1.0, 0.8249)) and Annex E (linearised Bradford chromatic adaptation).
//   - K. M. Lam, 1985, "Metamerism and colour constancy", PhD thesis, University of
//     Bradford (the Bradford cone-response matrix).
//
// Conventions: XYZ is scaled so that the white point has Y = 1 (not 100); linear sRGB
// (1, 1, 1) maps to the D65 white. The XYZ values of a colour depend on the white it is
// relative to; shade::xyz does not store it, the caller keeps track (a `white_point` is passed
// to every function that needs one).

#include <array>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <string_view>

#include <glm/mat3x3.hpp>

#include <shade/core/error.hpp>
#include <shade/core/types.hpp>

namespace shade {

/// CIE 1931 XYZ tristimulus values, Y = 1 for the reference white. A separate struct from
/// rgb<T> and lab<T> so the three cannot be mixed up silently.
template <std::floating_point T>
struct xyz {
    T X; ///< tristimulus X
    T Y; ///< tristimulus Y (luminance relative to the white)
    T Z; ///< tristimulus Z

    friend constexpr bool operator==(const xyz&, const xyz&) noexcept = default;
};

/// True when X, Y and Z are all finite.
template <std::floating_point T>
[[nodiscard]] inline bool is_finite(const xyz<T>& c) noexcept {
    return std::isfinite(c.X) && std::isfinite(c.Y) && std::isfinite(c.Z);
}

/// A reference white: XYZ with Y = 1 and X, Z finite and > 0. Validated on construction, so
/// every function taking a white_point may divide by its components without checks.
template <std::floating_point T>
class white_point {
public:
    /// CIE standard illuminant D65 from its chromaticity as given in IEC 61966-2-1 clause 3,
    /// x = 0.3127, y = 0.3290: XYZ = (x/y, 1, (1 - x - y)/y) = (0.950456, 1, 1.089058).
    [[nodiscard]] static white_point d65() noexcept {
        return white_point(T(0.3127 / 0.3290), T(1), T((1.0 - 0.3127 - 0.3290) / 0.3290));
    }

    /// D50 as the ICC profile connection space illuminant, ICC.1:2010 clause 7.2.16:
    /// XYZ = (0.9642, 1, 0.8249). This is the white of ICC and graphic-arts L*a*b*.
    [[nodiscard]] static white_point d50() noexcept {
        return white_point(T(0.9642), T(1), T(0.8249));
    }

    /// A white from its CIE 1931 chromaticity (x, y): XYZ = (x/y, 1, (1 - x - y)/y).
    /// Throws shade::invalid_parameter naming "x" or "y" unless x > 0, y > 0, x + y < 1.
    [[nodiscard]] static white_point from_chromaticity(T x, T y) {
        require_positive("x", x);
        require_positive("y", y);
        if (!(x + y < T(1)))
            throw invalid_parameter("y", "must satisfy x + y < 1", detail::to_text(y));
        return ratios_checked("y", "must keep x/y and (1 - x - y)/y finite and > 0", y, x / y,
                              (T(1) - x - y) / y);
    }

    /// A white from XYZ values, rescaled to Y = 1. Throws shade::invalid_parameter naming
    /// "white.X", "white.Y" or "white.Z" unless each is finite and > 0.
    [[nodiscard]] static white_point from_xyz(const xyz<T>& white) {
        require_positive("white.X", white.X);
        require_positive("white.Y", white.Y);
        require_positive("white.Z", white.Z);
        return ratios_checked("white.Y", "must keep X/Y and Z/Y finite and > 0", white.Y,
                              white.X / white.Y, white.Z / white.Y);
    }

    /// The white's XYZ (Y = 1).
    [[nodiscard]] const xyz<T>& tristimulus() const noexcept { return xyz_; }

    friend bool operator==(const white_point&, const white_point&) noexcept = default;

private:
    white_point(T X, T Y, T Z) noexcept : xyz_{X, Y, Z} {}

    // The white (X, 1, Z) from ratios computed by a factory. A tiny y or Y makes a ratio
    // overflow to infinity (or a huge Y underflow it to 0) even for valid inputs; reject
    // that here, naming the divisor, so every white_point keeps finite components > 0.
    static white_point ratios_checked(std::string_view name, std::string_view rule, T got, T X,
                                      T Z) {
        if (!(std::isfinite(X) && std::isfinite(Z) && X > T(0) && Z > T(0)))
            throw invalid_parameter(name, rule, detail::to_text(got));
        return white_point(X, T(1), Z);
    }

    xyz<T> xyz_;
};

namespace detail {

// Row-major 3x3 matrix in double, used to derive shade's colour matrices at compile time so
// that each matrix and its inverse are exact inverses (to double rounding) rather than two
// independently rounded 4-decimal tables whose product is off by ~1e-4.
using mat3d = std::array<double, 9>;

[[nodiscard]] constexpr mat3d multiply(const mat3d& p, const mat3d& q) noexcept {
    mat3d r{};
    for (std::size_t i = 0; i < 3; ++i)
        for (std::size_t j = 0; j < 3; ++j)
            r[i * 3 + j] = p[i * 3 + 0] * q[0 * 3 + j] + p[i * 3 + 1] * q[1 * 3 + j] +
                           p[i * 3 + 2] * q[2 * 3 + j];
    return r;
}

[[nodiscard]] constexpr std::array<double, 3> multiply(const mat3d& p,
                                                       const std::array<double, 3>& v) noexcept {
    return {p[0] * v[0] + p[1] * v[1] + p[2] * v[2], p[3] * v[0] + p[4] * v[1] + p[5] * v[2],
            p[6] * v[0] + p[7] * v[1] + p[8] * v[2]};
}

// Inverse by cofactors (adjugate / determinant). Only applied to the well-conditioned
// colour matrices below, whose determinants are far from 0.
[[nodiscard]] constexpr mat3d inverse(const mat3d& m) noexcept {
    const double c00 = m[4] * m[8] - m[5] * m[7];
    const double c01 = m[5] * m[6] - m[3] * m[8];
    const double c02 = m[3] * m[7] - m[4] * m[6];
    const double det = m[0] * c00 + m[1] * c01 + m[2] * c02;
    return {c00 / det,
            (m[2] * m[7] - m[1] * m[8]) / det,
            (m[1] * m[5] - m[2] * m[4]) / det,
            c01 / det,
            (m[0] * m[8] - m[2] * m[6]) / det,
            (m[2] * m[3] - m[0] * m[5]) / det,
            c02 / det,
            (m[1] * m[6] - m[0] * m[7]) / det,
            (m[0] * m[4] - m[1] * m[3]) / det};
}

// SMPTE RP 177-1993, section 3.3: with P the matrix whose columns are the primaries' XYZ at
// Y = 1, (x/y, 1, (1-x-y)/y), and W the white's XYZ, the scale S = P^-1 W makes
// M = P diag(S) map RGB (1,1,1) to W. Returns M (linear RGB -> XYZ), row-major.
[[nodiscard]] constexpr mat3d rgb_to_xyz_matrix(double x_r, double y_r, double x_g, double y_g,
                                                double x_b, double y_b, double x_w,
                                                double y_w) noexcept {
    const mat3d p{x_r / y_r,
                  x_g / y_g,
                  x_b / y_b,
                  1.0,
                  1.0,
                  1.0,
                  (1.0 - x_r - y_r) / y_r,
                  (1.0 - x_g - y_g) / y_g,
                  (1.0 - x_b - y_b) / y_b};
    const std::array<double, 3> w{x_w / y_w, 1.0, (1.0 - x_w - y_w) / y_w};
    const std::array<double, 3> s = multiply(inverse(p), w);
    return {p[0] * s[0], p[1] * s[1], p[2] * s[2], p[3] * s[0], p[4] * s[1],
            p[5] * s[2], p[6] * s[0], p[7] * s[1], p[8] * s[2]};
}

// Linear sRGB -> XYZ (D65) from the IEC 61966-2-1 chromaticities. Rounded to 4 decimals it
// is the matrix printed in clause 5.2 (0.4124 0.3576 0.1805 / 0.2126 0.7152 0.0722 /
// 0.0193 0.1192 0.9505); the test checks that.
inline constexpr mat3d linear_srgb_to_xyz_d65 =
    rgb_to_xyz_matrix(0.64, 0.33, 0.30, 0.60, 0.15, 0.06, 0.3127, 0.3290);

// XYZ (D65) -> linear sRGB: the exact inverse of the matrix above.
inline constexpr mat3d xyz_d65_to_linear_srgb = inverse(linear_srgb_to_xyz_d65);

// Bradford cone-response matrix M_BFD (Lam 1985; ICC.1:2010 Annex E), row-major.
inline constexpr mat3d bradford_cone = {0.8951, 0.2664, -0.1614,  //
                                        -0.7502, 1.7135, 0.0367,  //
                                        0.0389, -0.0685, 1.0296};
inline constexpr mat3d bradford_cone_inverse = inverse(bradford_cone);

template <std::floating_point T>
[[nodiscard]] inline glm::mat<3, 3, T> to_glm(const mat3d& m) noexcept {
    // glm is column-major: element (row i, column j) is stored at result[j][i].
    glm::mat<3, 3, T> result(T(0));
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) result[j][i] = T(m[static_cast<std::size_t>(i * 3 + j)]);
    return result;
}

template <std::floating_point T>
[[nodiscard]] inline vec3<T> to_vec(const xyz<T>& c) noexcept {
    return {c.X, c.Y, c.Z};
}

template <std::floating_point T>
[[nodiscard]] inline xyz<T> to_xyz(const vec3<T>& v) noexcept {
    return {v.x, v.y, v.z};
}

} // namespace detail

/// The 3x3 matrix taking linear sRGB to XYZ relative to D65 (column j = XYZ of primary j).
template <std::floating_point T>
[[nodiscard]] inline glm::mat<3, 3, T> linear_srgb_to_xyz_matrix() noexcept {
    return detail::to_glm<T>(detail::linear_srgb_to_xyz_d65);
}

/// The 3x3 matrix taking XYZ relative to D65 to linear sRGB; the inverse of
/// linear_srgb_to_xyz_matrix().
template <std::floating_point T>
[[nodiscard]] inline glm::mat<3, 3, T> xyz_to_linear_srgb_matrix() noexcept {
    return detail::to_glm<T>(detail::xyz_d65_to_linear_srgb);
}

/// Returns the XYZ (relative to D65, white Y = 1) of a linear sRGB colour (IEC 61966-2-1
/// clause 5.2, matrix derived from the primaries per SMPTE RP 177). NaN propagates.
template <std::floating_point T>
[[nodiscard]] inline xyz<T> linear_srgb_to_xyz(const rgb<T>& linear) noexcept {
    return detail::to_xyz(linear_srgb_to_xyz_matrix<T>() * linear);
}

/// Returns the linear sRGB colour of XYZ relative to D65 (IEC 61966-2-1 clause 5.3). Colours
/// outside the sRGB gamut give channels < 0 or > 1; nothing is clamped. NaN propagates.
template <std::floating_point T>
[[nodiscard]] inline rgb<T> xyz_to_linear_srgb(const xyz<T>& c) noexcept {
    return xyz_to_linear_srgb_matrix<T>() * detail::to_vec(c);
}

/// Linearised Bradford chromatic adaptation (Lam 1985; ICC.1:2010 Annex E) from one white to
/// another: XYZ_dst = M_BFD^-1 diag(rho_dst / rho_src) M_BFD XYZ_src, where rho = M_BFD W are
/// the cone responses of the two whites. It maps the source white exactly to the
/// destination white. Build once, apply to many colours.
template <std::floating_point T>
class bradford_adaptation {
public:
    /// Adaptation taking colours relative to `source` to colours relative to `destination`.
    /// Throws shade::invalid_parameter naming "source" or "destination" if a white's cone
    /// responses M_BFD W are not all > 0 (only for implausible whites far from the Planckian
    /// locus, e.g. x = 0.7, y = 0.29); the von Kries ratios would be meaningless or infinite.
    bradford_adaptation(const white_point<T>& source, const white_point<T>& destination) {
        const auto rho_s = cone_response("source", source);
        const auto rho_d = cone_response("destination", destination);
        const detail::mat3d scale{rho_d[0] / rho_s[0], 0, 0, 0, rho_d[1] / rho_s[1], 0,
                                  0, 0, rho_d[2] / rho_s[2]};
        matrix_ = detail::to_glm<T>(detail::multiply(
            detail::bradford_cone_inverse, detail::multiply(scale, detail::bradford_cone)));
    }

    /// Returns c, given relative to the source white, adapted to the destination white.
    [[nodiscard]] xyz<T> operator()(const xyz<T>& c) const noexcept {
        return detail::to_xyz(matrix_ * detail::to_vec(c));
    }

    /// The 3x3 adaptation matrix (XYZ_dst = matrix() * XYZ_src).
    [[nodiscard]] const glm::mat<3, 3, T>& matrix() const noexcept { return matrix_; }

private:
    static std::array<double, 3> cone_response(std::string_view name, const white_point<T>& w) {
        const xyz<T>& c = w.tristimulus();
        const std::array<double, 3> white{double(c.X), double(c.Y), double(c.Z)};
        const auto rho = detail::multiply(detail::bradford_cone, white);
        if (!(rho[0] > 0.0 && rho[1] > 0.0 && rho[2] > 0.0))
            throw invalid_parameter(name, "must have positive Bradford cone responses",
                                    detail::to_text(vec3<T>(c.X, c.Y, c.Z)));
        return rho;
    }

    glm::mat<3, 3, T> matrix_;
};

} // namespace shade
