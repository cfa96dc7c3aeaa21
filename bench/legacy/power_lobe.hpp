#pragma once
// Internal: what shade::phong and shade::blinn_phong have in common. Both are a Lambertian
// base k_d / pi plus a lobe k_s c cos^n [/ (n·l)], and differ only in the cosine raised to
// the power n (r·v for Phong, n·h for Blinn-Phong) and in their forms (the constant c).
// Each public class derives from power_lobe_brdf with its own cosine and documents its
// forms; the constructor rules, accessors and evaluation live here once.

#include <algorithm>
#include <cmath>
#include <concepts>

#include <glm/geometric.hpp>

#include <shade/brdf/brdf.hpp>
#include "directions.hpp"
#include <shade/core/error.hpp>
#include <shade/core/math.hpp>
#include <shade/core/surface_point.hpp>
#include <shade/core/types.hpp>
#include "namespace.hpp"

namespace shade_legacy::detail {

/// F describes a form of a power lobe: `normalization<T>(shininess)` (the constant c
/// multiplying k_s cos^n), `divides_by_n_dot_l` (the lobe is further divided by n·l) and
/// `reciprocal` (whether f(l, v) == f(v, l)).
template <class F, class T>
concept power_lobe_form = std::floating_point<T> && requires(T x) {
    { F::template normalization<T>(x) } -> std::same_as<T>;
    { F::divides_by_n_dot_l } -> std::convertible_to<bool>;
    { F::reciprocal } -> std::convertible_to<bool>;
};

/// Cosine is a type with `static T cosine(n, l, v)`: the lobe's cosine in [0, 1] for unit
/// n, l, v with n·l > 0 and n·v > 0.
template <class C, class T>
concept lobe_cosine = std::floating_point<T> && requires(const vec3<T>& d) {
    { C::cosine(d, d, d) } -> std::same_as<T>;
};

/// Phong's cosine max(r·v, 0) with r = 2 (n·l) n - l, l mirrored about n; capped at 1,
/// which rounding can exceed, so that a large exponent cannot overflow.
struct mirror_cosine {
    template <std::floating_point T>
    [[nodiscard]] static T cosine(const vec3<T>& n, const vec3<T>& l, const vec3<T>& v) noexcept {
        const vec3<T> r = T(2) * glm::dot(n, l) * n - l;
        return std::min(clamped_dot(r, v), T(1));
    }
};

/// Blinn's cosine n·h with h = normalize(l + v) (detail::half_vector), clamped to [0, 1].
struct half_vector_cosine {
    template <std::floating_point T>
    [[nodiscard]] static T cosine(const vec3<T>& n, const vec3<T>& l, const vec3<T>& v) noexcept {
        return std::min(clamped_dot(n, half_vector(l, v)), T(1));
    }
};

/// The Lambertian base plus the power lobe:
///
///     f = k_d / pi + k_s c cos^n [/ (n·l) when Form::divides_by_n_dot_l]     (1/sr)
///
/// with c = Form::normalization(n), n = shininess and cos = Cosine::cosine(n, l, v);
/// 0 unless n·l > 0 and n·v > 0. n·l in the divisor is floored at detail::cos_floor.
/// Satisfies shade::split_brdf (f_diffuse = k_d / pi, f_specular = the lobe), so
/// shade::lit lights the lobe with the light's specular colour.
template <std::floating_point T, class Form, class Cosine>
    requires power_lobe_form<Form, T> && lobe_cosine<Cosine, T>
class power_lobe_brdf {
public:
    using scalar_type = T;
    using form_type = Form;

    /// Validating constructor. Throws shade::invalid_parameter naming
    ///   "k_d" or "k_s" unless every channel is finite and >= 0,
    ///   "shininess" unless it is finite and >= 0, or if the form's constant c overflows T,
    ///   "k_s" / "k_d" if the peak value of f overflows T.
    power_lobe_brdf(const rgb<T>& k_d, const rgb<T>& k_s, T shininess)
        : k_d_(require_non_negative("k_d", k_d)), k_s_(require_non_negative("k_s", k_s)),
          shininess_(require_non_negative("shininess", shininess)),
          c_(Form::template normalization<T>(shininess)) {
        require_finite_peak("shininess", c_);
        T peak = max_channel(k_s_) * c_;
        if constexpr (Form::divides_by_n_dot_l) peak /= cos_floor<T>;
        require_finite_peak("k_s", peak);
        require_finite_peak("k_d", max_channel(k_d_) * inv_pi<T> + peak);
    }

    /// Unchecked: the caller guarantees the rules of the validating constructor.
    power_lobe_brdf(unchecked_t, const rgb<T>& k_d, const rgb<T>& k_s, T shininess) noexcept
        : k_d_(k_d), k_s_(k_s), shininess_(shininess),
          c_(Form::template normalization<T>(shininess)) {}

    [[nodiscard]] constexpr const rgb<T>& k_d() const noexcept { return k_d_; } ///< diffuse reflectance
    [[nodiscard]] constexpr const rgb<T>& k_s() const noexcept { return k_s_; } ///< specular coefficient
    [[nodiscard]] constexpr T shininess() const noexcept { return shininess_; } ///< exponent n
    /// The form's constant c.
    [[nodiscard]] constexpr T normalization() const noexcept { return c_; }

    /// Diffuse part k_d / pi (1/sr), 0 unless n·l > 0 and n·v > 0.
    [[nodiscard]] rgb<T> f_diffuse(const vec3<T>& l, const vec3<T>& v,
                                   const surface_point<T>& at) const noexcept {
        if (!above(l, v, at)) return rgb<T>(0);
        return k_d_ * inv_pi<T>;
    }

    /// Specular lobe k_s c cos^n [/ (n·l)] (1/sr), 0 unless n·l > 0 and n·v > 0.
    [[nodiscard]] rgb<T> f_specular(const vec3<T>& l, const vec3<T>& v,
                                    const surface_point<T>& at) const noexcept {
        if (!above(l, v, at)) return rgb<T>(0);
        const vec3<T>& n = at.n();
        T lobe = c_ * std::pow(Cosine::cosine(n, l, v), shininess_);
        if constexpr (Form::divides_by_n_dot_l) lobe /= floored_cos(glm::dot(n, l));
        return k_s_ * lobe;
    }

    /// BRDF value in 1/sr without the cosine: f_diffuse + f_specular.
    [[nodiscard]] rgb<T> f(const vec3<T>& l, const vec3<T>& v,
                           const surface_point<T>& at) const noexcept {
        return f_diffuse(l, v, at) + f_specular(l, v, at);
    }

private:
    [[nodiscard]] static bool above(const vec3<T>& l, const vec3<T>& v,
                                    const surface_point<T>& at) noexcept {
        return glm::dot(at.n(), l) > T(0) && glm::dot(at.n(), v) > T(0);
    }

    rgb<T> k_d_;
    rgb<T> k_s_;
    T shininess_;
    T c_;
};

} // namespace shade_legacy::detail
