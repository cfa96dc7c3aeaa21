// libFuzzer target: shade::phong in its three forms (classic, modified, normalized).
// Input: byte 0 float/double, a form byte, k_d, k_s, shininess, then a situation
// (brdf_target.hpp, which also says what is checked).

#include <concepts>
#include <cstddef>
#include <cstdint>

#include <shade/brdf/phong.hpp>

#include "brdf_target.hpp"

namespace {

template <std::floating_point T>
void run(shade::fuzz::input& in) {
    using namespace shade;
    fuzz::run_forms<T, phong<T, phong_form::classic>, phong<T, phong_form::modified>,
                    phong<T, phong_form::normalized>>(in);
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return shade::fuzz::dispatch(data, size, &run<float>, &run<double>);
}
