#pragma once
// shade::invalid_parameter and the validation helpers that raise it. Validating
// constructors and factories call these so that a bad parameter fails loudly, once, with
// its name, instead of turning into NaN deep inside a renderer.

#include <charconv>
#include <cmath>
#include <concepts>
#include <stdexcept>
#include <string>
#include <string_view>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <shade/core/math.hpp>
#include <shade/core/types.hpp>

namespace shade {

/// Thrown when a parameter is out of its valid domain. what() names the parameter, says
/// which rule it broke and shows the offending value, e.g.
/// "shade: parameter 'roughness' must be > 0 (got -0.5)".
class invalid_parameter : public std::invalid_argument {
public:
    invalid_parameter(std::string_view parameter, std::string_view rule, std::string_view got)
        : std::invalid_argument(compose(parameter, rule, got)), parameter_(parameter) {}

    /// The name of the rejected parameter, as the user would write it.
    [[nodiscard]] const std::string& parameter() const noexcept { return parameter_; }

private:
    static std::string compose(std::string_view parameter, std::string_view rule,
                               std::string_view got) {
        std::string s = "shade: parameter '";
        s += parameter;
        s += "' ";
        s += rule;
        s += " (got ";
        s += got;
        s += ")";
        return s;
    }

    std::string parameter_;
};

namespace detail {

/// Appends x to s with `digits` significant digits (at most 17) in the shorter of fixed
/// and scientific notation, as printf's "%.<digits>g" writes it ("0.5", "1e+30", "inf",
/// "nan"). The default, 9, tells any two floats apart.
template <std::floating_point T>
void append_text(std::string& s, T x, int digits = 9) {
    char buffer[64]; // sign, 17 digits, point, exponent of a long double: 29 at most
    const std::to_chars_result r =
        std::to_chars(buffer, buffer + sizeof buffer, x, std::chars_format::general, digits);
    s.append(buffer, r.ptr);
}

/// x as text for an error message, as append_text writes it.
template <std::floating_point T>
std::string to_text(T x) {
    std::string s;
    append_text(s, x);
    return s;
}

/// v as "(x, y, z)", each component as append_text writes it. Built with append rather
/// than `"(" + to_text(...) + ...`: g++ 12 at -O3 reports a false -Wrestrict on that chain
/// of std::string operator+ (GCC bug 105329), which -Werror would turn into a build
/// failure in Release builds of user code.
template <std::floating_point T>
std::string to_text(const vec3<T>& v) {
    std::string s = "(";
    append_text(s, v.x);
    s += ", ";
    append_text(s, v.y);
    s += ", ";
    append_text(s, v.z);
    s += ')';
    return s;
}

} // namespace detail

/// Throws invalid_parameter unless x is finite. Returns x for use in member initialisers.
template <std::floating_point T>
T require_finite(std::string_view name, T x) {
    if (!std::isfinite(x)) throw invalid_parameter(name, "must be finite", detail::to_text(x));
    return x;
}

/// Throws invalid_parameter unless every component of v is finite.
template <std::floating_point T>
vec3<T> require_finite(std::string_view name, const vec3<T>& v) {
    if (!is_finite(v)) throw invalid_parameter(name, "must be finite", detail::to_text(v));
    return v;
}

/// Throws invalid_parameter unless x is finite and x >= 0.
template <std::floating_point T>
T require_non_negative(std::string_view name, T x) {
    if (!std::isfinite(x) || !(x >= T(0)))
        throw invalid_parameter(name, "must be finite and >= 0", detail::to_text(x));
    return x;
}

/// Throws invalid_parameter unless every component of v is finite and >= 0 (colours,
/// reflectances).
template <std::floating_point T>
vec3<T> require_non_negative(std::string_view name, const vec3<T>& v) {
    if (!is_finite(v) || !(v.x >= T(0) && v.y >= T(0) && v.z >= T(0)))
        throw invalid_parameter(name, "must be finite and >= 0 in every channel",
                                detail::to_text(v));
    return v;
}

/// Throws invalid_parameter unless x is finite and x > 0.
template <std::floating_point T>
T require_positive(std::string_view name, T x) {
    if (!std::isfinite(x) || !(x > T(0)))
        throw invalid_parameter(name, "must be finite and > 0", detail::to_text(x));
    return x;
}

/// Throws invalid_parameter unless lo <= x <= hi (and x finite).
template <std::floating_point T>
T require_in_range(std::string_view name, T x, T lo, T hi) {
    if (!std::isfinite(x) || !(x >= lo && x <= hi))
        throw invalid_parameter(name, "must lie in [" + detail::to_text(lo) + ", " +
                                          detail::to_text(hi) + "]",
                                detail::to_text(x));
    return x;
}

/// Throws invalid_parameter unless every component of v lies in [lo, hi].
template <std::floating_point T>
vec3<T> require_in_range(std::string_view name, const vec3<T>& v, T lo, T hi) {
    const bool ok = is_finite(v) && v.x >= lo && v.x <= hi && v.y >= lo && v.y <= hi &&
                    v.z >= lo && v.z <= hi;
    if (!ok)
        throw invalid_parameter(name, "must lie in [" + detail::to_text(lo) + ", " +
                                          detail::to_text(hi) + "] in every channel",
                                detail::to_text(v));
    return v;
}

/// Throws invalid_parameter unless v is finite and of unit length (is_unit_length: |v|^2
/// within 1e-3 of 1). For directions a caller promises are normalised; require_direction
/// normalises instead.
template <std::floating_point T>
vec3<T> require_unit_length(std::string_view name, const vec3<T>& v) {
    if (!is_unit_length(v))
        throw invalid_parameter(name, "must be a finite unit vector (|v|^2 within 1e-3 of 1)", detail::to_text(v));
    return v;
}

/// Returns v normalised; throws invalid_parameter if v is non-finite or zero. Any finite,
/// non-zero v works, however tiny or huge: v is first divided by its largest component so
/// that squaring can neither underflow to 0 nor overflow to infinity.
template <std::floating_point T>
vec3<T> require_direction(std::string_view name, const vec3<T>& v) {
    if (!is_finite(v)) throw invalid_parameter(name, "must be finite", detail::to_text(v));
    const T m = glm::max(std::abs(v.x), glm::max(std::abs(v.y), std::abs(v.z)));
    if (!(m > T(0))) throw invalid_parameter(name, "must have non-zero length", detail::to_text(v));
    const vec3<T> w = v / m;
    return w / glm::length(w);
}

} // namespace shade
