#pragma once
// shade::check::result: what a property check found, as data and as a sentence, and the
// three-way verdict every check reports.

#include <cmath>
#include <concepts>
#include <cstddef>
#include <iosfwd>
#include <string>

#include <shade/core/error.hpp>
#include <shade/core/surface_point.hpp>
#include <shade/core/types.hpp>

namespace shade::check {

/// What a check concluded. A check built on an estimate (an albedo from samples, an
/// integral from quadrature) says `inconclusive` when the estimate's own error does not
/// support either answer: too few samples, or an estimate within its error of the bound.
enum class verdict {
    pass,         ///< the property held, with margin for the estimate's error
    fail,         ///< the property is violated, beyond the estimate's error
    inconclusive, ///< the error is too large to tell: rerun with more samples
};

/// "pass", "fail" or "inconclusive".
[[nodiscard]] constexpr const char* to_string(verdict v) noexcept {
    switch (v) {
    case verdict::pass: return "pass";
    case verdict::fail: return "fail";
    case verdict::inconclusive: return "inconclusive";
    }
    return "inconclusive";
}

/// The verdict on "the true value is at most `bound`" from an estimate with standard error
/// (or error bound) `error`: pass when estimate + k error <= bound, fail when
/// estimate - k error > bound, inconclusive in between. A non-finite estimate fails (a
/// check only sees one when the model returned NaN or infinity); a non-finite error is
/// inconclusive. With a normal estimate and an honest standard error, k = 4 makes a wrong
/// pass or a wrong fail less likely than 3.2e-5 per decision (one-sided normal tail).
[[nodiscard]] inline verdict decide_at_most(double estimate, double error, double bound, double k) noexcept {
    if (!std::isfinite(estimate)) return verdict::fail;
    if (!std::isfinite(error) || error < 0) return verdict::inconclusive;
    if (estimate + k * error <= bound) return verdict::pass;
    if (estimate - k * error > bound) return verdict::fail;
    return verdict::inconclusive;
}

/// The outcome of one property check (positivity, reciprocity, energy conservation, or a
/// sampling check of shade/check/sampling.hpp).
///
/// `worst` is the check's violation measure at its worst (documented by each check), and
/// l, v, at and the values beside it say exactly where that happened, so a failure can be
/// reproduced by evaluating the BRDF there. `message` says all of it in one sentence.
template <std::floating_point T>
struct result {
    std::string property;      ///< "positivity", "reciprocity", "energy conservation", ...
    std::string model;         ///< the name the caller gave the BRDF under test
    verdict outcome = verdict::pass; ///< pass, fail or inconclusive (see verdict)
    bool passed = true;        ///< outcome == verdict::pass
    double error = 0;          ///< the error of `worst` where it is an estimate (the
                               ///< standard error of an albedo, the error bound of an
                               ///< integral); 0 for exact pointwise checks
    std::size_t tried = 0;     ///< how many direction pairs (or views) were evaluated
    std::size_t failures = 0;  ///< how many of them violated the property
    double worst = 0;          ///< the worst violation measure found (see each check)
    double tolerance = 0;      ///< the tolerance the measure was compared against
    vec3<T> l{0, 0, 1};        ///< light direction at the worst case (world space)
    vec3<T> v{0, 0, 1};        ///< view direction at the worst case (world space)
    surface_point<T> at{};     ///< the surface point the check ran at
    rgb<T> value{0, 0, 0};     ///< f(l, v) at the worst case, or the albedo for energy
    rgb<T> other{0, 0, 0};     ///< f(v, l) at the worst case (reciprocity only)
    std::string message;       ///< the whole finding as a sentence a person can act on

    /// True when the property held (outcome == verdict::pass).
    [[nodiscard]] explicit operator bool() const noexcept { return passed; }

    /// Sets outcome and passed together.
    void decide(verdict outcome_now) noexcept {
        outcome = outcome_now;
        passed = outcome_now == verdict::pass;
    }
};

/// Writes r.message (include <ostream> where you stream it).
template <std::floating_point T>
std::ostream& operator<<(std::ostream& out, const result<T>& r) {
    return out << r.message;
}

namespace detail {

/// "l = (x, y, z), v = (x, y, z) at p = (...) with n = (...)".
template <std::floating_point T>
std::string where(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) {
    return "l = " + shade::detail::to_text(l) + ", v = " + shade::detail::to_text(v) +
           " at p = " + shade::detail::to_text(at.p) +
           " with n = " + shade::detail::to_text(at.n());
}

/// x with `digits` significant digits (6 by default: enough to read, short enough for a
/// sentence).
inline std::string number(double x, int digits = 6) {
    std::string s;
    shade::detail::append_text(s, x, digits);
    return s;
}

} // namespace detail

} // namespace shade::check
