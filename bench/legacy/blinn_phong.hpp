#pragma once
// shade::blinn_phong: Blinn's half-vector lobe (n·h)^n over a Lambertian base, in four
// forms chosen by a type:
//
//   blinn_phong<T, blinn_phong_form::classic>           k_s (n·h)^n / (pi n·l)     divides by n·l
//   blinn_phong<T, blinn_phong_form::modified>          k_s (n·h)^n                 reciprocal
//   blinn_phong<T, blinn_phong_form::normalized_rtr>    k_s (n+8)/(8 pi) (n·h)^n    approximate normalization
//   blinn_phong<T, blinn_phong_form::normalized_exact>  k_s (n+2)(n+4)/(8 pi (2^(-n/2) + n)) (n·h)^n
//
// Every form adds the diffuse part k_d / pi. h = normalize(l + v); (n·h) is clamped to
// [0, 1] before the power (0^0 = 1, so shininess 0 gives a constant lobe).

#include <cmath>
#include <concepts>

#include <shade/brdf/brdf.hpp>
#include "power_lobe.hpp"
#include <shade/core/math.hpp>
#include <shade/core/types.hpp>
#include "namespace.hpp"

namespace shade_legacy {

/// The forms of the Blinn-Phong specular lobe, used as the Form parameter of
/// shade::blinn_phong. Each is a stateless type with `normalization<T>(shininess)` (the
/// constant c multiplying k_s (n·h)^n), `divides_by_n_dot_l` and `reciprocal`.
namespace blinn_phong_form {

/// The classic Blinn-Phong lighting model written as a BRDF. This form DIVIDES BY n·l.
///
/// Blinn 1977, "Models of Light Reflection for Computer Synthesized Pictures", SIGGRAPH
/// '77, Computer Graphics 11(2): 192-198 (Phong's model with (r·v) replaced by (n·h)): the
/// classic specular term is I_s k_s (n·h)^n; shade::lit computes pi f I_s (n·l), so
///
///     f_s = k_s (n·h)^n / (pi (n·l))      (1/sr)
///
/// reproduces it exactly. Not reciprocal. Not energy conserving in general (for n = 0 the
/// specular albedo is 2 k_s). n·l is floored at machine epsilon (detail::cos_floor) to keep
/// f finite near grazing light.
struct classic {
    static constexpr bool divides_by_n_dot_l = true;
    static constexpr bool reciprocal = false;
    template <std::floating_point T>
    [[nodiscard]] static constexpr T normalization(T /*shininess*/) noexcept {
        return inv_pi<T>;
    }
};

/// The reciprocal, unnormalized lobe f_s = k_s (n·h)^n (1/sr), the analogue of Lewis
/// 1994's modified Phong ("Making Shaders More Physically Plausible", CGF 13(2)).
/// Reciprocal: yes (h is symmetric in l and v). Energy conserving only for small enough
/// k_s: at v = n the specular albedo is k_s / c_exact with c_exact the factor of
/// normalized_exact.
struct modified {
    static constexpr bool divides_by_n_dot_l = false;
    static constexpr bool reciprocal = true;
    template <std::floating_point T>
    [[nodiscard]] static constexpr T normalization(T /*shininess*/) noexcept {
        return T(1);
    }
};

/// The common approximate normalization c = (n + 8)/(8 pi).
///
/// Akenine-Möller, Haines, Hoffman 2008, "Real-Time Rendering", 3rd ed., ch. 7 (the
/// normalized Blinn-Phong BRDF (m + 8)/(8 pi) cos^m(theta_h)). It is an APPROXIMATION of
/// normalized_exact's factor: exact at n = 0, and up to ~7.5% larger around n ~ 8 (ratio
/// 1.0625 at n = 4, 1.0748 at n = 10, 1.018 at n = 100). Reciprocal: yes. Energy
/// conserving only if k_d + 1.075 k_s <= 1 (the specular albedo at v = n is up to 7.5% above
/// k_s).
struct normalized_rtr {
    static constexpr bool divides_by_n_dot_l = false;
    static constexpr bool reciprocal = true;
    template <std::floating_point T>
    [[nodiscard]] static constexpr T normalization(T shininess) noexcept {
        return (shininess + T(8)) / (T(8) * pi<T>);
    }
};

/// The exact normalization at normal incidence, c = (n+2)(n+4) / (8 pi (2^(-n/2) + n)).
///
/// Giesen 2009, "The Blinn-Phong Normalization Zoo" (blog post, ryg's blog), the factor
/// that makes the cosine-weighted lobe integrate to 1 for v = n. Derivation: with v = n,
/// theta_h = theta_l / 2, and substituting c = cos(theta_l/2),
///   2 pi int_0^{pi/2} cos^n(theta/2) cos(theta) sin(theta) dtheta
///     = 8 pi int_{1/sqrt 2}^1 c^(n+1) (2c^2 - 1) dc = 8 pi (n + 2^(-n/2)) / ((n+2)(n+4)).
/// So the specular albedo is exactly k_s at v = n (and, as the lobe tilts and is cut by
/// the horizon, below k_s elsewhere). Reciprocal: yes. Energy conserving: yes iff
/// k_d + k_s <= 1 in every channel. Computed as ((n+2)/(8 pi)) ((n+4)/(n + 2^(-n/2))) so
/// that the product does not overflow for huge n.
struct normalized_exact {
    static constexpr bool divides_by_n_dot_l = false;
    static constexpr bool reciprocal = true;
    template <std::floating_point T>
    [[nodiscard]] static T normalization(T shininess) noexcept {
        const T n = shininess;
        return (n + T(2)) / (T(8) * pi<T>) * ((n + T(4)) / (n + std::exp2(-n / T(2))));
    }
};

} // namespace blinn_phong_form

/// F is one of the shade::blinn_phong_form types (or a user type with the same members).
template <class F, class T>
concept blinn_phong_lobe_form = detail::power_lobe_form<F, T>;

/// Blinn-Phong reflection: Lambertian base k_d / pi plus the lobe in the form `Form` (see
/// shade::blinn_phong_form for the formulas, citations and properties of each):
///
///     f = k_d / pi + k_s c (n·h)^n [/ (n·l) for blinn_phong_form::classic]     (1/sr)
///
/// h = normalize(l + v), c = Form::normalization(n), n = shininess. Returns 0 unless
/// n·l > 0 and n·v > 0. Satisfies shade::split_brdf.
///
/// Constructors, accessors (k_d, k_s, shininess, normalization = c) and f, f_diffuse,
/// f_specular are those of detail::power_lobe_brdf (shade/brdf/detail/power_lobe.hpp),
/// which Phong shares: blinn_phong(k_d, k_s, shininess) validates and throws
/// shade::invalid_parameter naming the offending parameter; blinn_phong(unchecked, ...)
/// does not.
template <std::floating_point T, class Form = blinn_phong_form::normalized_exact>
    requires blinn_phong_lobe_form<Form, T>
class blinn_phong : public detail::power_lobe_brdf<T, Form, detail::half_vector_cosine> {
public:
    using detail::power_lobe_brdf<T, Form, detail::half_vector_cosine>::power_lobe_brdf;
};

} // namespace shade_legacy
