#include <cmath>
#include <cstdint>
#include <type_traits>

#include <doctest/doctest.h>

#include <shade/color/convert.hpp>

namespace {

// L*a*b* tolerance: 1e-6 for double (a millionth of the just-noticeable Delta E of 1), 1e-4
// for float (8 ulps at 100; see test_lab.cpp). Linear RGB tolerance: 1e-6 for double, 1e-5
// for float (the chain multiplies ~4 float roundings by the inverse matrix's gain of up to
// ~5).
template <class T>
constexpr T lab_tolerance = std::is_same_v<T, float> ? T(1e-4) : T(1e-6);
template <class T>
constexpr T rgb_tolerance = std::is_same_v<T, float> ? T(1e-5) : T(1e-6);

} // namespace

TEST_CASE_TEMPLATE("sRGB white is L*a*b* (100, 0, 0) relative to D65 and to D50", T, float, double) {
    // White (255, 255, 255) decodes to linear 1, which is the D65 white; Bradford maps the
    // D65 white exactly to the D50 white; a white is (100, 0, 0) relative to itself.
    for (const auto& w : {shade::white_point<T>::d65(), shade::white_point<T>::d50()}) {
        const shade::srgb_lab_converter<T> convert(w);
        const auto white = convert.to_lab(shade::srgb8{255, 255, 255});
        CHECK(std::abs(white.L - T(100)) <= lab_tolerance<T>);
        CHECK(std::abs(white.a) <= lab_tolerance<T>);
        CHECK(std::abs(white.b) <= lab_tolerance<T>);
        CHECK(convert.to_lab(shade::srgb8{0, 0, 0}) == shade::lab<T>{0, 0, 0});
    }
}

TEST_CASE_TEMPLATE("sRGB greys are neutral in L*a*b*, with L* from Y alone", T, float, double) {
    // A grey g (1,1,1) has XYZ = g * white (after adaptation too), so a* = b* = 0 and
    // L* = 116 f(g) - 16. Code 119 decodes to g = ((119/255 + 0.055)/1.055)^2.4 = 0.1844750,
    // L* = 116 * 0.1844750^(1/3) - 16 = 116 * 0.5692624 - 16 = 50.034439.
    for (const auto& w : {shade::white_point<T>::d65(), shade::white_point<T>::d50()}) {
        const shade::srgb_lab_converter<T> convert(w);
        const auto grey = convert.to_lab(shade::srgb8{119, 119, 119});
        CHECK(std::abs(grey.L - T(50.034439)) <= (std::is_same_v<T, float> ? T(1e-4) : T(2e-6)));
        CHECK(std::abs(grey.a) <= lab_tolerance<T>);
        CHECK(std::abs(grey.b) <= lab_tolerance<T>);
    }
}

TEST_CASE_TEMPLATE("linear sRGB -> L*a*b* -> linear sRGB round trip, D65 and D50", T, float, double) {
    for (const auto& w : {shade::white_point<T>::d65(), shade::white_point<T>::d50()}) {
        const shade::srgb_lab_converter<T> convert(w);
        for (int r = 0; r <= 10; ++r)
            for (int g = 0; g <= 10; ++g)
                for (int b = 0; b <= 10; ++b) {
                    const shade::rgb<T> c(T(r) / T(10), T(g) / T(10), T(b) / T(10));
                    const auto back = convert.to_linear(convert.to_lab(c));
                    CHECK(std::abs(back.x - c.x) <= rgb_tolerance<T>);
                    CHECK(std::abs(back.y - c.y) <= rgb_tolerance<T>);
                    CHECK(std::abs(back.z - c.z) <= rgb_tolerance<T>);
                }
    }
}

TEST_CASE_TEMPLATE("8-bit sRGB -> L*a*b* -> 8-bit sRGB is the identity", T, float, double) {
    const shade::srgb_lab_converter<T> convert(shade::white_point<T>::d50());
    for (int r = 0; r <= 255; r += 15)
        for (int g = 0; g <= 255; g += 15)
            for (int b = 0; b <= 255; b += 15) {
                const shade::srgb8 p{std::uint8_t(r), std::uint8_t(g), std::uint8_t(b)};
                CHECK(shade::encode_srgb8(convert.to_linear(convert.to_lab(p))) == p);
            }
}

TEST_CASE_TEMPLATE("free functions agree with the converter", T, float, double) {
    const shade::rgb<T> c(T(0.2), T(0.5), T(0.8));
    const auto d50 = shade::white_point<T>::d50();
    CHECK(shade::linear_srgb_to_lab(c, d50) == shade::srgb_lab_converter<T>(d50).to_lab(c));
    CHECK(shade::linear_srgb_to_lab(c) == shade::srgb_lab_converter<T>().to_lab(c));
    const shade::lab<T> l{T(40), T(10), T(-20)};
    CHECK(shade::lab_to_linear_srgb(l, d50) == shade::srgb_lab_converter<T>(d50).to_linear(l));
    CHECK(shade::srgb_lab_converter<T>(d50).white() == d50);
}
