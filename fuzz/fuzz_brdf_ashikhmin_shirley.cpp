// libFuzzer target: shade::ashikhmin_shirley (anisotropic: the situation's tangent matters). Input: byte 0 float/double, r_d, r_s,
// p_u, p_v, then a
// situation (brdf_target.hpp, which also says what is checked).

#include <concepts>
#include <cstddef>
#include <cstdint>

#include <shade/brdf/ashikhmin_shirley.hpp>

#include "brdf_target.hpp"

namespace {

using namespace shade;
using fuzz::build;
using fuzz::decode_rgb;

template <std::floating_point T>
void run(fuzz::input& in) {
    const rgb<T> r_d = decode_rgb<T>(in);
    const rgb<T> r_s = decode_rgb<T>(in);
    const T p_u = in.scalar<T>();
    const T p_v = in.scalar<T>();
    const auto s = fuzz::decode_situation<T>(in);
    const auto b = build<ashikhmin_shirley<T>>(r_d, r_s, p_u, p_v);
    if (b && s) fuzz::check_brdf(*b, *s);
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return shade::fuzz::dispatch(data, size, &run<float>, &run<double>);
}
