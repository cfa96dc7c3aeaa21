// libFuzzer target: ray/triangle intersection with shade::moller_trumbore (see triangle_target.hpp
// for the input layout and what is checked).

#include <cstddef>
#include <cstdint>

#include "triangle_target.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return shade::fuzz::triangle_target<shade::moller_trumbore>(data, size);
}
