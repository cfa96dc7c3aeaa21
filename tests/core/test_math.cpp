// The power-of-two helpers of shade/core/math.hpp against the C library's std::ldexp and
// std::frexp, which they replace in hot code (ray/sphere) and must match bit for bit.

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include <doctest/doctest.h>

#include <shade/core/math.hpp>

namespace {

// Same bits, so that +0 and -0 differ and a NaN equals a NaN of the same payload.
template <class T>
bool same_bits(T a, T b) {
    using U = std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint64_t>;
    return std::bit_cast<U>(a) == std::bit_cast<U>(b);
}

// Values whose scaling exercises every rounding case: ones, odd significands (their low
// bits are lost when the result is subnormal), the largest and smallest normals, the
// smallest subnormal, zeros, infinities, both signs.
template <class T>
std::vector<T> probe_values() {
    using L = std::numeric_limits<T>;
    std::vector<T> values = {T(1),          T(0.75),        T(1.5),          T(3),
                             T(0.1),        T(1) / T(3),    L::max(),        L::min(),
                             L::denorm_min(), L::min() / T(3), T(0),         L::infinity(),
                             std::nextafter(T(1), T(2)),    std::nextafter(L::min(), T(0))};
    const std::size_t n = values.size();
    for (std::size_t i = 0; i < n; ++i) values.push_back(-values[i]);
    return values;
}

} // namespace

TEST_CASE_TEMPLATE("times_power_of_two equals std::ldexp bit for bit, for every exponent", T, float, double) {
    using L = std::numeric_limits<T>;
    // Every k for which 2^k is a T, and beyond on both sides (where std::ldexp is used).
    const int k_lo = L::min_exponent - L::digits - 40;
    const int k_hi = L::max_exponent + 40;
    for (const T x : probe_values<T>()) {
        for (int k = k_lo; k <= k_hi; ++k) {
            const T expected = std::ldexp(x, k);
            const T got = shade::detail::times_power_of_two(x, k);
            if (!same_bits(expected, got)) {
                CAPTURE(x);
                CAPTURE(k);
                CAPTURE(expected);
                CAPTURE(got);
                FAIL("times_power_of_two differs from std::ldexp");
            }
        }
    }
    // The two ends of the table, spelled out: 2^(min_exponent - digits) is the smallest
    // subnormal, 2^(max_exponent - 1) the largest power of two.
    CHECK(shade::detail::times_power_of_two(T(1), L::min_exponent - L::digits) == L::denorm_min());
    CHECK(shade::detail::times_power_of_two(T(1), L::max_exponent - 1) ==
          std::ldexp(T(1), L::max_exponent - 1));
    CHECK(shade::detail::times_power_of_two(T(1), L::max_exponent) == L::infinity());
}

TEST_CASE_TEMPLATE("power_of_two_rescale_exponent is minus frexp's exponent of the largest component", T, float, double) {
    using L = std::numeric_limits<T>;
    using v = shade::vec3<T>;
    const std::vector<v> vectors = {v(1, 0, 0),          v(0, -0.75, 0.5),      v(3, -7, 2),
                                    v(0, 0, L::max()),   v(L::min(), 0, 0),     v(0, L::denorm_min(), 0),
                                    v(-L::min() / 3, 0, L::denorm_min()),       v(1e-3, 2e-3, -4e-3),
                                    v(-1e30, 5, 0)};
    for (const v& x : vectors) {
        const T m = std::max(std::abs(x.x), std::max(std::abs(x.y), std::abs(x.z)));
        int e = 0;
        const T mantissa = std::frexp(m, &e);
        CAPTURE(m);
        CHECK(mantissa >= T(0.5));
        CHECK(mantissa < T(1));
        CHECK(shade::detail::power_of_two_rescale_exponent(x) == -e);
        CHECK(shade::detail::power_of_two_rescale_exponent(m) == -e); // the scalar form
        // The rescaled largest component lies in [0.5, 1), exactly m * 2^-e.
        const int s = shade::detail::power_of_two_rescale_exponent(x);
        CHECK(shade::detail::times_power_of_two(m, s) == mantissa);
    }
    // Every normal exponent: m = 2^j has frexp exponent j + 1.
    for (int j = L::min_exponent - 1; j <= L::max_exponent - 1; ++j) {
        const T m = std::ldexp(T(1), j);
        CAPTURE(j);
        CHECK(shade::detail::power_of_two_rescale_exponent(v(0, m, 0)) == -(j + 1));
        const T just_below = std::nextafter(m, T(0)); // 0.11...1 x 2^j: exponent j
        if (just_below >= L::min())
            CHECK(shade::detail::power_of_two_rescale_exponent(v(just_below, 0, 0)) == -j);
    }
}
