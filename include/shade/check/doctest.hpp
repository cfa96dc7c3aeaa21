#pragma once
// A thin doctest adapter for shade's property checks: include it after <doctest/doctest.h>
// is available (it includes it) and write
//   CHECK_MESSAGE(r.passed, r);       // the message printed on failure is the finding
// or use shade::check::doctest_expect(r) / doctest_expect_failure(r) /
// doctest_expect_inconclusive(r).

#include <string>

#include <doctest/doctest.h>

#include <shade/check/result.hpp>

namespace doctest {

/// Lets doctest print a shade::check::result as its message.
template <std::floating_point T>
struct StringMaker<shade::check::result<T>> {
    static String convert(const shade::check::result<T>& r) { return r.message.c_str(); }
};

} // namespace doctest

namespace shade::check {

/// Records a doctest CHECK that the property held, printing the finding if not.
template <std::floating_point T>
void doctest_expect(const result<T>& r) {
    CHECK_MESSAGE(r.passed, r.message);
}

/// Records a doctest CHECK that the property was violated (for known offenders): the
/// verdict must be fail, not merely inconclusive.
template <std::floating_point T>
void doctest_expect_failure(const result<T>& r) {
    const std::string said = "expected a violation, but: " + r.message;
    CHECK_MESSAGE(r.outcome == verdict::fail, said);
}

/// Records a doctest CHECK that the check could not decide (estimate within its error).
template <std::floating_point T>
void doctest_expect_inconclusive(const result<T>& r) {
    const std::string said = "expected an inconclusive verdict, but: " + r.message;
    CHECK_MESSAGE(r.outcome == verdict::inconclusive, said);
}

} // namespace shade::check
