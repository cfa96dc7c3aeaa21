// libFuzzer target: ray/triangle intersection with shade::plane_then_areas (see triangle_target.hpp
// for the input layout and what is checked).

#include <cstddef>
#include <cstdint>

#include "triangle_target.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return shade::fuzz::triangle_target<shade::plane_then_areas>(data, size);
}
