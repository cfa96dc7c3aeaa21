// libFuzzer target: shade::blinn_phong in its four forms (classic, modified,
// normalized_rtr, normalized_exact). Input: byte 0 float/double, a form byte, k_d, k_s,
// shininess, then a situation (brdf_target.hpp, which also says what is checked).

#include <concepts>
#include <cstddef>
#include <cstdint>

#include <shade/brdf/blinn_phong.hpp>

#include "brdf_target.hpp"

namespace {

template <std::floating_point T>
void run(shade::fuzz::input& in) {
    using namespace shade;
    using namespace shade::blinn_phong_form;
    fuzz::run_forms<T, blinn_phong<T, classic>, blinn_phong<T, modified>,
                    blinn_phong<T, normalized_rtr>, blinn_phong<T, normalized_exact>>(in);
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return shade::fuzz::dispatch(data, size, &run<float>, &run<double>);
}
