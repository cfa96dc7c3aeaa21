#pragma once
// shade::check::result: what a property check found, as data and as a sentence.

#include <concepts>
#include <cstddef>
#include <iosfwd>
#include <string>

#include <shade/core/error.hpp>
#include <shade/core/surface_point.hpp>
#include <shade/core/types.hpp>

namespace shade::check {

/// The outcome of one property check (positivity, reciprocity, energy conservation).
///
/// `worst` is the check's violation measure at its worst (documented by each check), and
/// l, v, at and the values beside it say exactly where that happened, so a failure can be
/// reproduced by evaluating the BRDF there. `message` says all of it in one sentence.
template <std::floating_point T>
struct result {
    std::string property;      ///< "positivity", "reciprocity" or "energy conservation"
    std::string model;         ///< the name the caller gave the BRDF under test
    bool passed = true;        ///< whether the property held everywhere it was tested
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

    /// True when the property held.
    [[nodiscard]] explicit operator bool() const noexcept { return passed; }
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

/// x with 6 significant digits: enough to read, short enough for a sentence.
inline std::string number(double x) {
    std::string s;
    shade::detail::append_text(s, x, 6);
    return s;
}

} // namespace detail

} // namespace shade::check
