#pragma once
// shade::phong: Phong's specular lobe (r·v)^n over a Lambertian base, in three forms
// chosen by a type: the classic lighting model, the reciprocal "modified Phong", and the
// normalized energy-conserving modified Phong.
//
//   shade::phong<T, phong_form::classic>     k_s (r·v)^n / (pi n·l)     divides by n·l
//   shade::phong<T, phong_form::modified>    k_s (r·v)^n                 reciprocal
//   shade::phong<T, phong_form::normalized>  k_s (n+2)/(2 pi) (r·v)^n    reciprocal, energy conserving
//
// Every form adds the diffuse part k_d / pi. r = 2 (n·l) n - l is l mirrored about n, and
// (r·v) is clamped to >= 0 before the power (0^0 = 1, so shininess 0 gives a constant lobe).

#include <concepts>

#include <shade/brdf/brdf.hpp>
#include "power_lobe.hpp"
#include <shade/core/math.hpp>
#include <shade/core/types.hpp>
#include "namespace.hpp"

namespace shade_legacy {

/// The forms of the Phong specular lobe, used as the Form parameter of shade::phong.
/// Each form is a stateless type with
///   * `normalization<T>(shininess)`: the constant c multiplying k_s (r·v)^n, and
///   * `divides_by_n_dot_l`: whether the lobe is further divided by n·l,
///   * `reciprocal`: whether f(l, v) == f(v, l).
namespace phong_form {

/// (a) The classic Phong lighting model written as a BRDF. This form DIVIDES BY n·l.
///
/// Phong 1975, "Illumination for Computer Generated Pictures", CACM 18(6): 311-317, the
/// specular term of the shading function: I_s k_s (r·v)^n. shade::lit computes
/// pi f I_s (n·l), so the BRDF that reproduces the classic term exactly is
///
///     f_s = k_s (r·v)^n / (pi (n·l))      (1/sr)
///
/// Not reciprocal (the 1/(n·l) factor is not symmetric). Not energy conserving in general:
/// at v = n the specular albedo is 2 k_s / (n + 1) (= 2 k_s for n = 0). Near grazing
/// light f_s grows like 1/(n·l); n·l is floored at machine epsilon (detail::cos_floor)
/// so f stays finite, which changes the lit result only for lights within rounding error
/// of the horizon.
struct classic {
    static constexpr bool divides_by_n_dot_l = true;
    static constexpr bool reciprocal = false;
    template <std::floating_point T>
    [[nodiscard]] static constexpr T normalization(T /*shininess*/) noexcept {
        return inv_pi<T>;
    }
};

/// (b) The reciprocal, unnormalized "modified Phong" lobe.
///
/// Lewis 1994, "Making Shaders More Physically Plausible", Computer Graphics Forum 13(2):
/// 109-120 (the modified Phong BRDF, without the 1/(n·l) of the classic model):
///
///     f_s = k_s (r·v)^n                   (1/sr)
///
/// Reciprocal: yes (r·v = 2 (n·l)(n·v) - l·v is symmetric in l and v). Energy conserving only if
/// k_s <= (n + 2)/(2 pi): at v = n the specular albedo is 2 pi k_s / (n + 2). Note that
/// through shade::lit this form reflects pi k_s I_s (r·v)^n (n·l), i.e. pi (n·l) times the
/// classic term.
struct modified {
    static constexpr bool divides_by_n_dot_l = false;
    static constexpr bool reciprocal = true;
    template <std::floating_point T>
    [[nodiscard]] static constexpr T normalization(T /*shininess*/) noexcept {
        return T(1);
    }
};

/// (c) The normalized, energy-conserving modified Phong lobe.
///
/// Lafortune, Willems 1994, "Using the Modified Phong Reflectance Model for Physically
/// Based Rendering", Technical Report CW 197, K.U. Leuven (the specular BRDF with the
/// normalization factor (n + 2)/(2 pi)); the same factor is derived in Lewis 1994:
///
///     f_s = k_s (n + 2)/(2 pi) (r·v)^n    (1/sr)
///
/// The factor makes the specular albedo exactly k_s at normal incidence (v = n:
/// integral of (n+2)/(2 pi) cos^n(theta) cos(theta) dw = 1) and smaller elsewhere (the lobe
/// is cut by the horizon). Reciprocal: yes. Energy conserving: yes iff k_d + k_s <= 1 in
/// every channel.
struct normalized {
    static constexpr bool divides_by_n_dot_l = false;
    static constexpr bool reciprocal = true;
    template <std::floating_point T>
    [[nodiscard]] static constexpr T normalization(T shininess) noexcept {
        return (shininess + T(2)) / (T(2) * pi<T>);
    }
};

} // namespace phong_form

/// F is one of the shade::phong_form types (or a user type with the same members).
/// F is one of the shade::phong_form types (or a user type with the same members).
template <class F, class T>
concept phong_lobe_form = detail::power_lobe_form<F, T>;

/// Phong reflection: Lambertian base k_d / pi plus the Phong specular lobe in the form
/// `Form` (see shade::phong_form for the formulas, citations and properties of each):
///
///     f = k_d / pi + k_s c (max(r·v, 0))^n [/ (n·l) for phong_form::classic]     (1/sr)
///
/// with r = 2 (n·l) n - l, c = Form::normalization(n), n = shininess. Returns 0 unless
/// n·l > 0 and n·v > 0. Satisfies shade::split_brdf (f_diffuse = k_d / pi, f_specular = the
/// lobe), so shade::lit lights the lobe with the light's specular colour.
///
/// Constructors, accessors (k_d, k_s, shininess, normalization = c) and f, f_diffuse,
/// f_specular are those of detail::power_lobe_brdf (shade/brdf/detail/power_lobe.hpp),
/// which Blinn-Phong shares: phong(k_d, k_s, shininess) validates and throws
/// shade::invalid_parameter naming the offending parameter; phong(unchecked, ...) does not.
template <std::floating_point T, class Form = phong_form::normalized>
    requires phong_lobe_form<Form, T>
class phong : public detail::power_lobe_brdf<T, Form, detail::mirror_cosine> {
public:
    using detail::power_lobe_brdf<T, Form, detail::mirror_cosine>::power_lobe_brdf;
};

/// The classic Phong lighting model as a BRDF (divides by n·l; not reciprocal).
template <std::floating_point T>
using classic_phong = phong<T, phong_form::classic>;

/// Lewis's reciprocal, unnormalized modified Phong.
template <std::floating_point T>
using modified_phong = phong<T, phong_form::modified>;

/// Lafortune and Willems's normalized, energy-conserving modified Phong.
template <std::floating_point T>
using normalized_phong = phong<T, phong_form::normalized>;

} // namespace shade_legacy
