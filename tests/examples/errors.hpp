#pragma once
// Shared by the tests of the example programs' file readers (test_pfm.cpp, test_exr.cpp).

#include <stdexcept>
#include <string>

namespace examples_test {

/// The message f throws as std::runtime_error, or "" when it does not throw.
template <class F>
std::string error_of(F f) {
    try {
        f();
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    return "";
}

} // namespace examples_test
