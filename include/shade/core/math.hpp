#pragma once
// Scalar constants and small numeric helpers shared by all of shade.

#include <bit>
#include <cmath>
#include <concepts>
#include <cstdint>
#include <limits>
#include <numbers>
#include <type_traits>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <shade/core/types.hpp>

namespace shade {

/// pi in the scalar type T.
template <std::floating_point T>
inline constexpr T pi = std::numbers::pi_v<T>;

/// 1/pi in the scalar type T.
template <std::floating_point T>
inline constexpr T inv_pi = std::numbers::inv_pi_v<T>;

/// +infinity in the scalar type T (the t_max of an unbounded ray).
template <std::floating_point T>
inline constexpr T infinity = std::numeric_limits<T>::infinity();

/// x squared.
template <std::floating_point T>
[[nodiscard]] constexpr T sqr(T x) noexcept {
    return x * x;
}

/// sqrt(max(x, 0)): for quantities that are non-negative in exact arithmetic but may round
/// to a tiny negative (1 - cos^2, discriminants). Without the clamp sqrt would return NaN.
template <std::floating_point T>
[[nodiscard]] inline T safe_sqrt(T x) noexcept {
    return std::sqrt(x > T(0) ? x : T(0));
}

/// True when every component of v is finite (no NaN, no infinity).
template <std::floating_point T>
[[nodiscard]] inline bool is_finite(const vec3<T>& v) noexcept {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

/// True when every component of v is finite (no NaN, no infinity).
template <std::floating_point T>
[[nodiscard]] inline bool is_finite(const vec2<T>& v) noexcept {
    return std::isfinite(v.x) && std::isfinite(v.y);
}

/// How far |v|^2 may be from 1 for is_unit_length: 1e-3, about 8000 float ulps, so a
/// vector normalised in float (a few ulps off) or in float and converted to double passes,
/// and a forgotten normalisation (an interpolated normal, a ray direction of length 2)
/// fails.
template <std::floating_point T>
inline constexpr T unit_length_tolerance = T(1e-3);

/// True when v is finite and | |v|^2 - 1 | <= unit_length_tolerance: the "unit length"
/// precondition of directions and normals (SHADE_ASSERT, surface_point::checked).
template <std::floating_point T>
[[nodiscard]] inline bool is_unit_length(const vec3<T>& v) noexcept {
    return std::abs(glm::dot(v, v) - T(1)) <= unit_length_tolerance<T>; // NaN fails
}

/// True when u lies in [0,1)^2, the domain of the square_to_* sampling maps.
template <std::floating_point T>
[[nodiscard]] constexpr bool is_in_unit_square(const vec2<T>& u) noexcept {
    return u.x >= T(0) && u.x < T(1) && u.y >= T(0) && u.y < T(1);
}

/// max(a·b, 0): the clamped cosine used by every reflection model.
template <std::floating_point T>
[[nodiscard]] inline T clamped_dot(const vec3<T>& a, const vec3<T>& b) noexcept {
    const T d = glm::dot(a, b);
    return d > T(0) ? d : T(0);
}

namespace detail {

/// The x in [0, 1] at which f, increasing on [0, 1], reaches `target`, by bisection: 64
/// halvings of [0, 1], which end on adjacent doubles (for the inverses of the tables'
/// coordinate maps, computed when a table or grid is built, not per lookup). A target
/// outside f's range returns the nearer end.
template <class F>
[[nodiscard]] double bisect_increasing(const F& f, double target) noexcept {
    double lo = 0, hi = 1;
    for (int k = 0; k < 64; ++k) {
        const double mid = 0.5 * (lo + hi);
        (f(mid) < target ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

/// True when T is IEEE 754 binary32 or binary64 (float and double on every platform shade
/// targets), whose bit layout the power-of-two helpers below read directly. For other
/// types (long double) they call the C library instead.
template <std::floating_point T>
inline constexpr bool ieee_binary32_or_64 =
    std::numeric_limits<T>::is_iec559 && std::numeric_limits<T>::radix == 2 &&
    ((sizeof(T) == 4 && std::numeric_limits<T>::digits == 24) ||
     (sizeof(T) == 8 && std::numeric_limits<T>::digits == 53));

/// Layout of an IEEE binary32/binary64 T: sign bit, biased exponent field, fraction
/// (IEEE 754-2019, "Standard for Floating-Point Arithmetic", §3.4, binary interchange
/// format encodings: a field E in 1 .. 2 bias is the normal number 1.f 2^(E - bias); E = 0
/// encodes zero and the subnormals 0.f 2^(1 - bias); E = 2 bias + 1 infinities and NaNs).
template <std::floating_point T>
struct ieee_layout {
    using bits = std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint64_t>;
    static constexpr int fraction_bits = std::numeric_limits<T>::digits - 1;    // 23, 52
    static constexpr int bias = std::numeric_limits<T>::max_exponent - 1;       // 127, 1023
    static constexpr int max_field = 2 * std::numeric_limits<T>::max_exponent - 1; // 255, 2047
    /// Smallest k with 2^k a T (the smallest subnormal): -149, -1074.
    static constexpr int min_power = std::numeric_limits<T>::min_exponent - std::numeric_limits<T>::digits;
    /// The biased exponent field of x (0: zero or subnormal, max_field: inf or NaN).
    [[nodiscard]] static int exponent_field(T x) noexcept {
        return static_cast<int>((std::bit_cast<bits>(x) >> fraction_bits) & bits(max_field));
    }
};

/// x * 2^k rounded once, exactly as std::ldexp(x, k) (a power of two only shifts the
/// exponent; a result in the subnormal range is rounded to nearest by both, one past the
/// largest T is infinity for both). For float and double, when 2^k is itself a T, this is
/// a multiplication by 2^k built from its bits (no library call); otherwise std::ldexp.
template <std::floating_point T>
[[nodiscard]] inline T times_power_of_two(T x, int k) noexcept {
    if constexpr (ieee_binary32_or_64<T>) {
        using L = ieee_layout<T>;
        using B = typename L::bits;
        if (k >= 1 - L::bias && k <= L::bias) // a normal power of two
            return x * std::bit_cast<T>(B(k + L::bias) << L::fraction_bits);
        if (k >= L::min_power && k < 1 - L::bias) // a subnormal power of two
            return x * std::bit_cast<T>(B(1) << (k - L::min_power));
    }
    return std::ldexp(x, k);
}

/// -e for the e with m = f 2^e, f in [0.5, 1) (std::frexp's exponent of m >= 0):
/// times_power_of_two(x, that) rescales a number of size m into [0.5, 1) without any
/// rounding. Returned as an exponent, not as the factor 2^-e, because that factor
/// overflows to infinity when m is subnormal (float: m < 2^-126 has e down to -148, and
/// 2^148 is not a float). Read from m's exponent bits for float and double when m is
/// normal, else from std::frexp. For a zero or non-finite m the result is some int (no
/// undefined behaviour), meaningless as a scale.
template <std::floating_point T>
[[nodiscard]] inline int power_of_two_rescale_exponent(T m) noexcept {
    if constexpr (ieee_binary32_or_64<T>) {
        using L = ieee_layout<T>;
        // m = 1.f 2^(field - bias) = 0.1f 2^(field - bias + 1): e = field - bias + 1.
        if (const int field = L::exponent_field(m); field != 0 && field != L::max_field)
            return L::bias - 1 - field;
    }
    int e = 0;
    (void)std::frexp(m, &e);
    return -e;
}

/// The scalar form's exponent for m = max|v_i|: times_power_of_two(v_i, that) rescales v
/// so that its largest component lies in [0.5, 1), so v·v can neither overflow nor
/// underflow.
template <std::floating_point T>
[[nodiscard]] inline int power_of_two_rescale_exponent(const vec3<T>& v) noexcept {
    return power_of_two_rescale_exponent(glm::max(std::abs(v.x), glm::max(std::abs(v.y), std::abs(v.z))));
}

} // namespace detail

} // namespace shade
