#pragma once
// CIE 1976 L*a*b* (CIELAB) and its cylindrical form L*C*h (CIE LCh_ab), relative to a
// white point given as a parameter.
//
// Reference: CIE 15:2004, "Colorimetry", 3rd edition, section 8.2.1 (CIE 1976 L*a*b*
// colour space) and 8.2.2 (chroma C*_ab and hue angle h_ab).
//
// Conventions: L* is in [0, 100] for colours between black and the white (L* = 100 at the
// white); a*, b* and C*_ab are in the same units; hue angles h are in degrees in [0, 360).
// A lab<T> does not store its white point: convert with the same white_point both ways.
//
// Non-finite input: every function here is noexcept and propagates NaN (a NaN component
// gives NaN components out). Use require_finite(name, lab) to reject such values with a
// shade::invalid_parameter where they enter a program (a measured value, a file).

#include <cmath>
#include <concepts>
#include <string_view>

#include <shade/color/xyz.hpp>
#include <shade/core/error.hpp>
#include <shade/core/math.hpp>

namespace shade {

/// A CIE 1976 L*a*b* colour: L = L* (lightness, 0 black .. 100 white), a = a* (green-red),
/// b = b* (blue-yellow). Relative to a white point kept by the caller.
template <std::floating_point T>
struct lab {
    T L; ///< lightness L*
    T a; ///< a* (negative green, positive red)
    T b; ///< b* (negative blue, positive yellow)

    friend constexpr bool operator==(const lab&, const lab&) noexcept = default;
};

/// A CIE L*C*h colour (cylindrical L*a*b*): L = L*, C = C*_ab = sqrt(a*^2 + b*^2) >= 0,
/// h = h_ab = atan2(b*, a*) in degrees, in [0, 360).
template <std::floating_point T>
struct lch {
    T L; ///< lightness L*
    T C; ///< chroma C*_ab
    T h; ///< hue angle h_ab in degrees

    friend constexpr bool operator==(const lch&, const lch&) noexcept = default;
};

/// True when L*, a* and b* are all finite.
template <std::floating_point T>
[[nodiscard]] inline bool is_finite(const lab<T>& c) noexcept {
    return std::isfinite(c.L) && std::isfinite(c.a) && std::isfinite(c.b);
}

/// Throws shade::invalid_parameter naming `name` unless every component of c is finite.
/// Returns c.
template <std::floating_point T>
lab<T> require_finite(std::string_view name, const lab<T>& c) {
    if (!is_finite(c)) throw invalid_parameter(name, "must be finite", detail::to_text(vec3<T>(c.L, c.a, c.b)));
    return c;
}

namespace detail {

// CIE 15:2004 section 8.2.1: f(t) = t^(1/3) for t > (24/116)^3, else
// (841/108) t + 16/116. The exact fractions (not the rounded 0.008856 and 7.787 of older
// texts) make f and its slope continuous at the join. Below the join the linear branch
// also keeps f finite for t <= 0 (out-of-gamut XYZ), where a cube-root law would not be
// what CIE defines.
template <std::floating_point T>
[[nodiscard]] inline T lab_f(T t) noexcept {
    constexpr T delta = T(24.0 / 116.0);
    return t > delta * delta * delta ? std::cbrt(t) : T(841.0 / 108.0) * t + T(16.0 / 116.0);
}

// The inverse of lab_f: u^3 for u > 24/116, else (108/841)(u - 16/116).
template <std::floating_point T>
[[nodiscard]] inline T lab_f_inverse(T u) noexcept {
    return u > T(24.0 / 116.0) ? u * u * u : T(108.0 / 841.0) * (u - T(16.0 / 116.0));
}

// Hue angle in degrees in [0, 360) of the direction (a, b); 0 when a = b = 0. Without the
// explicit zero test atan2(+0, -0) would give 180 degrees for an achromatic colour.
template <std::floating_point T>
[[nodiscard]] inline T hue_degrees(T a, T b) noexcept {
    if (a == T(0) && b == T(0)) return T(0);
    T h = std::atan2(b, a) * (T(180) / pi<T>);
    if (h < T(0)) h += T(360);
    // A tiny negative angle plus 360 can round to exactly 360, outside [0, 360).
    if (h >= T(360)) h -= T(360);
    return h;
}

} // namespace detail

// CIE 15:2004 section 8.2.1:
//   L* = 116 f(Y/Y_n) - 16,  a* = 500 [f(X/X_n) - f(Y/Y_n)],  b* = 200 [f(Y/Y_n) - f(Z/Z_n)].
/// Returns the L*a*b* of XYZ colour c relative to `white` (both with the same scale, white
/// Y = 1). The white itself gives (100, 0, 0), black gives (0, 0, 0).
template <std::floating_point T>
[[nodiscard]] inline lab<T> xyz_to_lab(const xyz<T>& c, const white_point<T>& white) noexcept {
    const xyz<T>& n = white.tristimulus();
    const T f_x = detail::lab_f(c.X / n.X);
    const T f_y = detail::lab_f(c.Y / n.Y);
    const T f_z = detail::lab_f(c.Z / n.Z);
    return {T(116) * f_y - T(16), T(500) * (f_x - f_y), T(200) * (f_y - f_z)};
}

// The inverse of xyz_to_lab (CIE 15:2004 section 8.2.1 solved for X, Y, Z):
//   f_y = (L* + 16)/116,  f_x = f_y + a*/500,  f_z = f_y - b*/200,
//   X = X_n f^-1(f_x),  Y = Y_n f^-1(f_y),  Z = Z_n f^-1(f_z).
/// Returns the XYZ (white Y = 1) of L*a*b* colour c relative to `white`.
template <std::floating_point T>
[[nodiscard]] inline xyz<T> lab_to_xyz(const lab<T>& c, const white_point<T>& white) noexcept {
    const xyz<T>& n = white.tristimulus();
    const T f_y = (c.L + T(16)) / T(116);
    const T f_x = f_y + c.a / T(500);
    const T f_z = f_y - c.b / T(200);
    return {n.X * detail::lab_f_inverse(f_x), n.Y * detail::lab_f_inverse(f_y),
            n.Z * detail::lab_f_inverse(f_z)};
}

// CIE 15:2004 section 8.2.2: C*_ab = sqrt(a*^2 + b*^2), h_ab = arctan(b*/a*) in the quadrant
// of (a*, b*), in degrees.
/// Returns the L*C*h of an L*a*b* colour. Achromatic colours (a* = b* = 0) get h = 0.
template <std::floating_point T>
[[nodiscard]] inline lch<T> lab_to_lch(const lab<T>& c) noexcept {
    return {c.L, std::hypot(c.a, c.b), detail::hue_degrees(c.a, c.b)};
}

/// Returns the L*a*b* of an L*C*h colour: a* = C cos h, b* = C sin h (h in degrees, any
/// value; it is used modulo 360 through cos and sin).
template <std::floating_point T>
[[nodiscard]] inline lab<T> lch_to_lab(const lch<T>& c) noexcept {
    const T h = c.h * (pi<T> / T(180));
    return {c.L, c.C * std::cos(h), c.C * std::sin(h)};
}

} // namespace shade
