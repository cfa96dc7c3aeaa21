#pragma once
// Floats written as C++ source, for the generators of shade's tables
// (examples/albedo_tables.cpp, examples/dielectric_albedo_tables.cpp).

#include <cstddef>
#include <cstdio>

namespace shade::examples {

/// Writes x[0..count) to f as C++ float literals separated by ", ", each with `digits`
/// significant digits ("%.*g") and an 'f' suffix; a number printed without a point or
/// exponent gets one ("1" becomes "1.f"), so every literal is a float.
void write_float_literals(std::FILE* f, const float* x, std::size_t count, int digits = 7);

} // namespace shade::examples
