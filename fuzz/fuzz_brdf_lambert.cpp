// libFuzzer target: shade::lambert. Input: byte 0 float/double, k_d, then a
// situation (brdf_target.hpp, which also says what is checked).

#include <concepts>
#include <cstddef>
#include <cstdint>

#include <shade/brdf/lambert.hpp>

#include "brdf_target.hpp"

namespace {

using namespace shade;
using fuzz::build;
using fuzz::decode_rgb;

template <std::floating_point T>
void run(fuzz::input& in) {
    const rgb<T> k_d = decode_rgb<T>(in);
    const auto s = fuzz::decode_situation<T>(in);
    const auto b = build<lambert<T>>(k_d);
    if (b && s) fuzz::check_brdf(*b, *s);
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return shade::fuzz::dispatch(data, size, &run<float>, &run<double>);
}
