#include <cmath>
#include <limits>
#include <type_traits>

#include <doctest/doctest.h>

#include <shade/color/srgb.hpp>

namespace {

// Round-trip tolerance in encoded/linear units (values of order 1): 1e-6 for double, far
// below the 1/255 step of 8-bit sRGB (the actual error is ~1e-15); for float 2e-6, about 16
// ulps at 1, the rounding of pow and of the two divisions in float.
template <class T>
constexpr T round_trip_tolerance = std::is_same_v<T, float> ? T(2e-6) : T(1e-6);

} // namespace

TEST_CASE_TEMPLATE("sRGB transfer: end points and the 8-bit extremes are exact", T, float, double) {
    CHECK(shade::srgb_to_linear(T(0)) == T(0));
    CHECK(shade::linear_to_srgb(T(0)) == T(0));
    // ((1 + 0.055)/1.055)^2.4 = 1^2.4 = 1 and 1.055 * 1 - 0.055 = 1, up to the rounding of
    // the decimal constants.
    CHECK(shade::srgb_to_linear(T(1)) == doctest::Approx(1).epsilon(4 * std::numeric_limits<T>::epsilon()));
    CHECK(shade::linear_to_srgb(T(1)) == doctest::Approx(1).epsilon(4 * std::numeric_limits<T>::epsilon()));
    CHECK(shade::decode_srgb8<T>({0, 0, 0}) == shade::rgb<T>(0));
    CHECK(shade::encode_srgb8(shade::rgb<T>(1)) == shade::srgb8{255, 255, 255});
    CHECK(shade::encode_srgb8(shade::rgb<T>(0)) == shade::srgb8{0, 0, 0});
}

TEST_CASE_TEMPLATE("sRGB transfer: hand-evaluated values on both branches", T, float, double) {
    const T tol = std::is_same_v<T, float> ? T(1e-6) : T(1e-8);
    // Power branch: ((0.5 + 0.055)/1.055)^2.4 = 0.5260664^2.4 = exp(2.4 ln 0.5260664)
    // = exp(-1.5415870) = 0.21404114.
    CHECK(std::abs(shade::srgb_to_linear(T(0.5)) - T(0.21404114)) <= tol);
    // 1.055 * 0.5^(1/2.4) - 0.055 = 1.055 * 0.7491535 - 0.055 = 0.7903570 - 0.055 = 0.73535698.
    CHECK(std::abs(shade::linear_to_srgb(T(0.5)) - T(0.73535698)) <= tol);
    // Linear branch: 0.04 <= 0.04045, so 0.04/12.92 = 0.0030959752; and
    // 0.002 <= 0.0031308, so 12.92 * 0.002 = 0.02584.
    CHECK(std::abs(shade::srgb_to_linear(T(0.04)) - T(0.0030959752)) <= tol);
    CHECK(std::abs(shade::linear_to_srgb(T(0.002)) - T(0.02584)) <= tol);
    // 0.73535698 * 255 = 187.516, so linear 0.5 quantises to code 188 (a well-known value:
    // "50% linear grey is sRGB 188").
    CHECK(shade::encode_srgb8(shade::rgb<T>(T(0.5))) == shade::srgb8{188, 188, 188});
}

TEST_CASE_TEMPLATE("sRGB transfer: the two branches meet at the published thresholds", T, float, double) {
    // 12.92 * 0.0031308 = 0.040449936 and 1.055 * 0.0031308^(1/2.4) - 0.055 = 0.040449907:
    // the standard's rounded constants leave a jump of 3e-8 in encoded units.
    const T knee = T(0.0031308);
    const T above = std::nextafter(knee, T(1));
    CHECK(std::abs(shade::linear_to_srgb(above) - shade::linear_to_srgb(knee)) <= T(1e-7));
    const T knee_encoded = T(0.04045);
    const T above_encoded = std::nextafter(knee_encoded, T(1));
    CHECK(std::abs(shade::srgb_to_linear(above_encoded) - shade::srgb_to_linear(knee_encoded)) <= T(1e-8));
}

TEST_CASE_TEMPLATE("sRGB transfer: round trips both ways, including out-of-range values", T, float, double) {
    const T tol = round_trip_tolerance<T>;
    // Extended by odd symmetry, so negative and > 1 values round-trip too.
    for (int i = -1500; i <= 1500; ++i) {
        const T x = T(i) / T(1000);
        CAPTURE(x);
        CHECK(std::abs(shade::linear_to_srgb(shade::srgb_to_linear(x)) - x) <= tol * std::max(T(1), std::abs(x)));
        CHECK(std::abs(shade::srgb_to_linear(shade::linear_to_srgb(x)) - x) <= tol * std::max(T(1), std::abs(x)));
        CHECK(shade::srgb_to_linear(-x) == -shade::srgb_to_linear(x));
    }
    // Fine steps across both knees.
    for (int i = 0; i <= 2000; ++i) {
        const T x = T(0.003) + T(i) * T(1e-7);
        CHECK(std::abs(shade::srgb_to_linear(shade::linear_to_srgb(x)) - x) <= tol * x);
        const T c = T(0.0403) + T(i) * T(1e-6);
        CHECK(std::abs(shade::linear_to_srgb(shade::srgb_to_linear(c)) - c) <= tol * c);
    }
}

TEST_CASE_TEMPLATE("sRGB transfer: is increasing", T, float, double) {
    T previous = shade::srgb_to_linear(T(0));
    for (int i = 1; i <= 4096; ++i) {
        const T next = shade::srgb_to_linear(T(i) / T(4096));
        CHECK(next > previous);
        previous = next;
    }
}

TEST_CASE_TEMPLATE("sRGB 8-bit: every code survives decode then encode", T, float, double) {
    for (int v = 0; v <= 255; ++v) {
        const auto code = static_cast<std::uint8_t>(v);
        const shade::srgb8 p{code, static_cast<std::uint8_t>(255 - v), code};
        CHECK(shade::encode_srgb8(shade::decode_srgb8<T>(p)) == p);
    }
}

TEST_CASE_TEMPLATE("sRGB 8-bit: rounds to the nearest code", T, float, double) {
    // The encoded value (k + 0.49)/255 is nearer code k, (k + 0.51)/255 nearer k + 1.
    for (int k = 0; k < 255; ++k) {
        const T below = shade::srgb_to_linear((T(k) + T(0.49)) / T(255));
        const T above = shade::srgb_to_linear((T(k) + T(0.51)) / T(255));
        CHECK(int(shade::encode_srgb8(shade::rgb<T>(below)).r) == k);
        CHECK(int(shade::encode_srgb8(shade::rgb<T>(above)).r) == k + 1);
    }
}

TEST_CASE_TEMPLATE("sRGB 8-bit: clamps out-of-range and infinite values, rejects NaN", T, float, double) {
    const T inf = std::numeric_limits<T>::infinity();
    const T nan = std::numeric_limits<T>::quiet_NaN();
    CHECK(shade::encode_srgb8(shade::rgb<T>(T(-0.5), T(1.5), T(1e30))) == shade::srgb8{0, 255, 255});
    CHECK(shade::encode_srgb8(shade::rgb<T>(-inf, inf, T(0))) == shade::srgb8{0, 255, 0});
    CHECK_THROWS_AS((void)shade::encode_srgb8(shade::rgb<T>(T(0.5), nan, T(0.5))), shade::invalid_parameter);
    try {
        (void)shade::encode_srgb8(shade::rgb<T>(T(0.5), nan, T(0.5)));
    } catch (const shade::invalid_parameter& e) {
        CHECK(e.parameter() == "linear.g");
    }
}

TEST_CASE_TEMPLATE("sRGB transfer: NaN propagates, infinities keep their sign", T, float, double) {
    const T inf = std::numeric_limits<T>::infinity();
    const T nan = std::numeric_limits<T>::quiet_NaN();
    CHECK(std::isnan(shade::srgb_to_linear(nan)));
    CHECK(std::isnan(shade::linear_to_srgb(nan)));
    CHECK(shade::srgb_to_linear(inf) == inf);
    CHECK(shade::linear_to_srgb(-inf) == -inf);
}
