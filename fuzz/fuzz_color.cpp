// libFuzzer target: the colour conversions of shade/color (sRGB transfer and 8-bit
// quantisation, white points, Bradford adaptation, sRGB <-> L*a*b*, L*C*h, Delta E).
//
// Input: byte 0 bit 0 double/float; then two rgb colours, two L*a*b* colours, a
// chromaticity (x, y), an XYZ white and three CIEDE2000 weights (input.hpp decodes each
// scalar, non-finite values included).
//
// Checked, as documented in the headers:
//   * the transfer functions are odd (f(-x) == -f(x)), propagate NaN, keep +-inf, and map
//     finite values of moderate size (|x| <= 1e4) to finite values;
//   * encode_srgb8 throws exactly shade::invalid_parameter, and only for a NaN channel;
//     decoding then re-encoding any 8-bit pixel gives it back;
//   * white_point factories and bradford_adaptation either throw exactly
//     shade::invalid_parameter or give finite, positive whites and a finite matrix;
//   * for moderate finite colours (every component |c| <= 1e4) and whites (X, Z in
//     [1e-2, 1e2]; other whites are only exercised): finite L*a*b*, linear
//     sRGB and XYZ; L*C*h with C >= 0 and h in [0, 360); Delta E 76, 94 and 2000 finite
//     and >= 0 (CIEDE2000 weights in [1e-3, 1e3]), 0 for equal colours, and Delta E 76
//     and 2000 symmetric.

#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <optional>

#include <shade/color/convert.hpp>
#include <shade/color/delta_e.hpp>
#include <shade/color/lab.hpp>
#include <shade/color/srgb.hpp>
#include <shade/color/xyz.hpp>

#include "expect.hpp"
#include "input.hpp"

namespace {

using shade::fuzz::expect;

/// The magnitude up to which a finite input must give finite output; beyond it products
/// in the 3x3 matrices and cube laws may legitimately overflow float.
template <std::floating_point T>
[[nodiscard]] bool moderate(T x) noexcept {
    return std::isfinite(x) && std::abs(x) <= T(1e4);
}

template <std::floating_point T>
[[nodiscard]] bool moderate(const shade::vec3<T>& v) noexcept {
    return moderate(v.x) && moderate(v.y) && moderate(v.z);
}

template <std::floating_point T>
[[nodiscard]] bool moderate(const shade::lab<T>& c) noexcept {
    return moderate(c.L) && moderate(c.a) && moderate(c.b);
}

/// The documented behaviour of one transfer function f on x.
template <std::floating_point T, class F>
void check_transfer(F f, T x) {
    const T y = f(x);
    const T y_neg = f(-x);
    if (std::isnan(x)) {
        expect(std::isnan(y), "an sRGB transfer function turned NaN into a number");
        return;
    }
    expect(y_neg == -y, "an sRGB transfer function is not odd: f(-x) != -f(x)");
    if (std::isinf(x)) expect(y == x, "an sRGB transfer function does not keep +-inf");
    if (moderate(x)) {
        if (!std::isfinite(y)) shade::fuzz::show("x", x);
        expect(std::isfinite(y), "an sRGB transfer function gave a non-finite value");
    }
    if (x > T(0)) expect(y >= T(0), "an sRGB transfer function changed the sign of its input");
}

template <std::floating_point T>
void check_srgb(shade::fuzz::input& in, const shade::rgb<T>& c) {
    using namespace shade;
    check_transfer<T>([](T x) { return srgb_to_linear(x); }, c.x);
    check_transfer<T>([](T x) { return linear_to_srgb(x); }, c.y);

    const bool has_nan = std::isnan(c.x) || std::isnan(c.y) || std::isnan(c.z);
    try {
        (void)encode_srgb8(c);
        expect(!has_nan, "encode_srgb8 accepted a NaN channel");
    } catch (const invalid_parameter&) {
        expect(has_nan, "encode_srgb8 rejected a colour without NaN");
    }

    const srgb8 pixel{in.byte(), in.byte(), in.byte()};
    const rgb<T> linear = decode_srgb8<T>(pixel);
    expect(is_finite(linear) && linear.x >= T(0) && linear.x <= T(1) && linear.y >= T(0) &&
               linear.y <= T(1) && linear.z >= T(0) && linear.z <= T(1),
           "decode_srgb8 gave a channel outside [0, 1]");
    expect(encode_srgb8(linear) == pixel, "decode_srgb8 then encode_srgb8 changed a pixel");
}

/// Returns the white from the input's chromaticity or XYZ, if the factory accepts it.
template <std::floating_point T>
[[nodiscard]] std::optional<shade::white_point<T>> decode_white(shade::fuzz::input& in) {
    using namespace shade;
    const T x = in.scalar<T>();
    const T y = in.scalar<T>();
    const xyz<T> w{in.scalar<T>(), in.scalar<T>(), in.scalar<T>()};
    std::optional<white_point<T>> white;
    try {
        white = in.flag() ? white_point<T>::from_chromaticity(x, y) : white_point<T>::from_xyz(w);
    } catch (const invalid_parameter&) {
        return std::nullopt;
    }
    const xyz<T>& t = white->tristimulus();
    const bool ok = std::isfinite(t.X) && std::isfinite(t.Z) && t.X > T(0) && t.Y == T(1) &&
                    t.Z > T(0);
    if (!ok) {
        fuzz::show("chromaticity (x, y)", vec3<T>(x, y, T(0)));
        fuzz::show("XYZ", vec3<T>(w.X, w.Y, w.Z));
        fuzz::show("white", vec3<T>(t.X, t.Y, t.Z));
    }
    expect(ok, "a white_point factory accepted input giving a non-finite or non-positive white");
    return white;
}

template <std::floating_point T>
[[nodiscard]] bool finite_matrix(const glm::mat<3, 3, T>& m) noexcept {
    return shade::is_finite(m[0]) && shade::is_finite(m[1]) && shade::is_finite(m[2]);
}

template <std::floating_point T>
void check_lab(shade::fuzz::input& in, const shade::rgb<T>& linear, const shade::lab<T>& c1,
               const shade::lab<T>& c2) {
    using namespace shade;
    auto white = decode_white<T>(in);
    if (white) {
        // A white like (1e-40, 1, 1) divides X by 1e-40 in L*a*b*, which overflows for any
        // colour; finite results are promised for whites of ordinary size only.
        const xyz<T>& t = white->tristimulus();
        const auto usable = [](T k) { return k >= T(1e-2) && k <= T(1e2); };
        if (!usable(t.X) || !usable(t.Z)) {
            try {
                (void)srgb_lab_converter<T>(*white).to_lab(linear); // must not crash
            } catch (const invalid_parameter&) {
            }
            white.reset();
        }
    }
    std::optional<srgb_lab_converter<T>> converter;
    if (white) {
        try {
            converter.emplace(*white);
            expect(finite_matrix(bradford_adaptation<T>(white_point<T>::d65(), *white).matrix()),
                   "bradford_adaptation accepted a white but gave a non-finite matrix");
        } catch (const invalid_parameter&) {
            // An implausible white (cone responses <= 0): rejected as documented.
        }
    }
    if (!converter) converter.emplace();

    if (moderate(linear)) {
        if (!is_finite(converter->to_lab(linear))) {
            fuzz::show("linear", linear);
            const xyz<T>& t = converter->white().tristimulus();
            fuzz::show("white", vec3<T>(t.X, t.Y, t.Z));
        }
        expect(is_finite(converter->to_lab(linear)), "to_lab of a moderate colour is not finite");
        expect(is_finite(linear_srgb_to_xyz(linear)),
               "linear_srgb_to_xyz of a moderate colour is not finite");
    }
    if (moderate(c1)) {
        expect(is_finite(converter->to_linear(c1)), "to_linear of a moderate L*a*b* is not finite");
        const lch<T> p = lab_to_lch(c1);
        expect(std::isfinite(p.C) && p.C >= T(0), "L*C*h chroma is not finite and >= 0");
        expect(p.h >= T(0) && p.h < T(360), "L*C*h hue is outside [0, 360)");
        const lab<T> back = lch_to_lab(p);
        expect(is_finite(back), "lch_to_lab of a moderate colour is not finite");
    }
    if (!moderate(c1) || !moderate(c2)) return;

    ciede2000_weights<T> weights;
    try {
        const ciede2000_weights<T> decoded(in.scalar<T>(), in.scalar<T>(), in.scalar<T>());
        // Weights far from 1 (k = 1e-40 divides a difference of 1 into an overflow) cannot
        // give a finite Delta E; the finiteness promise is for weights in [1e-3, 1e3].
        const auto usable = [](T k) { return k >= T(1e-3) && k <= T(1e3); };
        if (usable(decoded.k_L()) && usable(decoded.k_C()) && usable(decoded.k_H()))
            weights = decoded;
    } catch (const invalid_parameter&) {
        // Rejected weights; keep the reference ones.
    }
    const T e76 = delta_e_76(c1, c2);
    const T e94 = delta_e_94(c1, c2);
    const T e00 = delta_e_2000(c1, c2, weights);
    const T e00_swapped = delta_e_2000(c2, c1, weights);
    if (!(std::isfinite(e00) && e00 >= T(0) && e00 == e00_swapped)) {
        fuzz::show("c1", vec3<T>(c1.L, c1.a, c1.b));
        fuzz::show("c2", vec3<T>(c2.L, c2.a, c2.b));
        fuzz::show("delta_e_2000(c1, c2)", e00);
        fuzz::show("delta_e_2000(c2, c1)", e00_swapped);
    }
    expect(std::isfinite(e76) && e76 >= T(0), "Delta E 76 is not finite and >= 0");
    expect(std::isfinite(e94) && e94 >= T(0), "Delta E 94 is not finite and >= 0");
    expect(std::isfinite(e00) && e00 >= T(0), "Delta E 2000 is not finite and >= 0");
    expect(e76 == delta_e_76(c2, c1), "Delta E 76 is not symmetric");
    expect(e00 == e00_swapped, "Delta E 2000 is not symmetric");
    expect(delta_e_76(c1, c1) == T(0) && delta_e_94(c1, c1) == T(0) &&
               delta_e_2000(c1, c1, weights) == T(0),
           "a Delta E of a colour with itself is not 0");
}

template <std::floating_point T>
void run(shade::fuzz::input& in) {
    const shade::rgb<T> c = in.vector<T>();
    const shade::rgb<T> linear = in.vector<T>();
    const shade::vec3<T> p = in.vector<T>();
    const shade::vec3<T> q = in.vector<T>();
    check_srgb<T>(in, c);
    check_lab<T>(in, linear, shade::lab<T>{p.x, p.y, p.z}, shade::lab<T>{q.x, q.y, q.z});
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    shade::fuzz::input in(data, size);
    if ((in.byte() & 1u) != 0)
        run<double>(in);
    else
        run<float>(in);
    return 0;
}
