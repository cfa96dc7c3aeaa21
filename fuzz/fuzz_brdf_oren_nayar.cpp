// libFuzzer target: shade::oren_nayar, trig-free and trigonometric evaluation. Input: byte 0 float/double, an evaluation
// byte, rho, sigma, then a
// situation (brdf_target.hpp, which also says what is checked).

#include <concepts>
#include <cstddef>
#include <cstdint>

#include <shade/brdf/oren_nayar.hpp>

#include "brdf_target.hpp"

namespace {

using namespace shade;
using fuzz::build;
using fuzz::decode_rgb;

template <std::floating_point T>
void run(fuzz::input& in) {
    const bool trig = in.flag();
    const rgb<T> rho = decode_rgb<T>(in);
    const T sigma = in.scalar<T>();
    const auto s = fuzz::decode_situation<T>(in);
    if (trig) {
        const auto b = build<oren_nayar_trig<T>>(rho, sigma);
        if (b && s) fuzz::check_brdf(*b, *s);
    } else {
        const auto b = build<oren_nayar<T>>(rho, sigma);
        if (b && s) fuzz::check_brdf(*b, *s);
    }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return shade::fuzz::dispatch(data, size, &run<float>, &run<double>);
}
