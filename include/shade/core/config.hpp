#pragma once
// The one macro shade has: the precondition assertion, prefixed SHADE_ and overridable by
// defining it before including any shade header.

#include <cassert>

/// SHADE_ASSERT(cond): checks a documented precondition of an unchecked, noexcept entry
/// point in debug builds: unit-length directions (shade::is_unit_length) passed to a BRDF's
/// f, to shade::lit::shade or to surface_point::at, and sample pairs u in [0,1)^2
/// (shade::is_in_unit_square) passed to the square_to_* sampling functions. By default it
/// is the standard assert: on when NDEBUG is not defined (a failure prints the condition
/// and aborts), compiled out, its condition not evaluated, when NDEBUG is defined (CMake's
/// Release and RelWithDebInfo). Define SHADE_ASSERT(cond) yourself before including shade
/// to log or count failures instead (the functions it guards are noexcept, so a throwing
/// definition ends in std::terminate), or as `((void)0)` to turn it off in a debug build
/// (tests/core/preconditions.cpp counts). It never replaces validation: parameters
/// of validating constructors and checked factories are rejected with
/// shade::invalid_parameter in every build.
#ifndef SHADE_ASSERT
#define SHADE_ASSERT(cond) assert(cond)
#endif
