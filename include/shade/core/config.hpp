#pragma once
// The few macros shade has: an assertion for internal invariants and a host/device
// qualifier hook. Each is prefixed SHADE_ and can be overridden by defining it before
// including any shade header.

#include <cassert>

/// SHADE_ASSERT(cond): checks an internal invariant in debug builds. It never guards
/// user input; bad input is rejected with shade::invalid_parameter instead.
#ifndef SHADE_ASSERT
#define SHADE_ASSERT(cond) assert(cond)
#endif

/// SHADE_HOST_DEVICE: prepended to hot functions so a CUDA/HIP build can define it as
/// `__host__ __device__`. Empty by default.
#ifndef SHADE_HOST_DEVICE
#define SHADE_HOST_DEVICE
#endif
