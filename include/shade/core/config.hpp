#pragma once
// The few macros shade has: an assertion for internal invariants. Each is prefixed
// SHADE_ and can be overridden by defining it before including any shade header.

#include <cassert>

/// SHADE_ASSERT(cond): checks an internal invariant in debug builds. It never guards
/// user input; bad input is rejected with shade::invalid_parameter instead.
#ifndef SHADE_ASSERT
#define SHADE_ASSERT(cond) assert(cond)
#endif
