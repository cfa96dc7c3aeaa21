#pragma once
// shade::fuzz::expect: the one way a fuzz target reports a broken guarantee. It prints
// what failed and where, then aborts, which libFuzzer records as a crash and saves the
// input as an artifact (docs/robustness.md says how to replay one).

#include <cmath>
#include <concepts>
#include <cstdio>
#include <cstdlib>

#include <shade/core/types.hpp>

namespace shade::fuzz {

/// Aborts with a message naming `what` unless ok. Each message is unique, so it locates the
/// check (std::source_location is not available with clang 14 and libstdc++ 12).
inline void expect(bool ok, const char* what) {
    if (ok) return;
    std::fprintf(stderr, "\nshade fuzz: guarantee broken: %s\n", what);
    std::abort();
}

/// Prints a labelled vector to stderr (for the context lines before a failing expect).
template <std::floating_point T>
void show(const char* label, const vec3<T>& v) {
    std::fprintf(stderr, "  %s = (%.17g, %.17g, %.17g)\n", label, static_cast<double>(v.x),
                 static_cast<double>(v.y), static_cast<double>(v.z));
}

/// Prints a labelled scalar to stderr.
template <std::floating_point T>
void show(const char* label, T x) {
    std::fprintf(stderr, "  %s = %.17g\n", label, static_cast<double>(x));
}

/// True when every channel of c is finite and >= 0: what every BRDF value, shader
/// result and light sum must be for valid parameters.
template <std::floating_point T>
[[nodiscard]] bool finite_non_negative(const vec3<T>& c) noexcept {
    return std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z) && c.x >= T(0) &&
           c.y >= T(0) && c.z >= T(0);
}

} // namespace shade::fuzz
