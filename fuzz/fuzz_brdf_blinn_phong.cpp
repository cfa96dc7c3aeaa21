// libFuzzer target: shade::blinn_phong in its four forms. Input: byte 0 float/double, a form byte, k_d, k_s,
// shininess, then a
// situation (brdf_target.hpp, which also says what is checked).

#include <concepts>
#include <cstddef>
#include <cstdint>
#include <optional>

#include <shade/brdf/blinn_phong.hpp>

#include "brdf_target.hpp"

namespace {

using namespace shade;
using fuzz::build;
using fuzz::decode_rgb;

template <class B, std::floating_point T>
void check(const rgb<T>& k_d, const rgb<T>& k_s, T shininess,
           const std::optional<fuzz::brdf_situation<T>>& s) {
    const auto b = build<B>(k_d, k_s, shininess);
    if (b && s) fuzz::check_brdf(*b, *s);
}

template <std::floating_point T>
void run(fuzz::input& in) {
    const unsigned form = in.choice(4);
    const rgb<T> k_d = decode_rgb<T>(in);
    const rgb<T> k_s = decode_rgb<T>(in);
    const T shininess = in.scalar<T>();
    const auto s = fuzz::decode_situation<T>(in);
    using namespace blinn_phong_form;
    if (form == 0) check<blinn_phong<T, classic>>(k_d, k_s, shininess, s);
    if (form == 1) check<blinn_phong<T, modified>>(k_d, k_s, shininess, s);
    if (form == 2) check<blinn_phong<T, normalized_rtr>>(k_d, k_s, shininess, s);
    if (form == 3) check<blinn_phong<T, normalized_exact>>(k_d, k_s, shininess, s);
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return shade::fuzz::dispatch(data, size, &run<float>, &run<double>);
}
