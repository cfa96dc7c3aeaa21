#pragma once
// Whether the long-running test cases run at their full size: SHADE_TEST_FULL, set by the
// CMake option of that name (on by default; script/test's quick run turns it off, script/test
// --all and CI keep it on). A test file compiled by hand without it runs them in full.

#ifndef SHADE_TEST_FULL
#define SHADE_TEST_FULL 1
#endif

namespace shade_test {

/// True in the full test-suite, false in script/test's quick one.
inline constexpr bool full = SHADE_TEST_FULL != 0;

} // namespace shade_test
