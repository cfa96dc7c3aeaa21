#pragma once
// The shader contract and the lift of any BRDF to a shader.
//
// A shader is a small class with a member type `scalar_type` and a const member
//   shade(at, v, light) -> rgb<scalar_type>
// returning the radiance reflected toward v at the surface point `at` from one light sample
// (shade::light_sample), ambient term included. Stylised models (toon, Gooch) are shaders
// only; every BRDF becomes one through shade::lit.

#include <concepts>
#include <utility>

#include <shade/brdf/brdf.hpp>
#include <shade/core/config.hpp>
#include <shade/core/error.hpp>
#include <shade/core/math.hpp>
#include <shade/core/surface_point.hpp>
#include <shade/light/light_sample.hpp>

namespace shade {

/// S is a shader: `s.shade(at, v, sample)` returns reflected radiance as linear RGB.
template <class S>
concept shader = has_scalar_type<S> &&
    requires(const S& s, const surface_point<typename S::scalar_type>& at,
             const vec3<typename S::scalar_type>& v,
             const light_sample<typename S::scalar_type>& sample) {
        { s.shade(at, v, sample) } -> std::same_as<rgb<typename S::scalar_type>>;
    };

/// A BRDF lit by one light sample: the shader of a BRDF.
///
///   shade = k_a * I_a + pi * (f_d * I_d + f_s * I_s) * max(n.l, 0)
///
/// where f_d and f_s are the BRDF's diffuse and specular parts (shade::split_brdf), or
/// f_d = f and f_s = 0 for a BRDF that does not split. The factor pi converts the light's
/// classic colour to irradiance (shade::light_sample), so a Lambert BRDF k_d/pi reproduces
/// the classic term k_d I_d (n.l) exactly. `ambient` is the ambient reflectance k_a
/// (0 by default: physically based renders have no ambient term).
template <brdf B>
class lit {
public:
    using scalar_type = scalar_of<B>;
    using T = scalar_type;

    /// `brdf` lit with ambient reflectance `ambient` (k_a, per channel). Throws
    /// invalid_parameter naming "ambient" unless every channel is finite and >= 0.
    explicit lit(B brdf, const rgb<T>& ambient = rgb<T>(0))
        : brdf_(std::move(brdf)), ambient_(require_non_negative("ambient", ambient)) {}

    /// The reflection model.
    [[nodiscard]] const B& brdf() const noexcept { return brdf_; }
    /// The ambient reflectance k_a, finite and >= 0 in every channel.
    [[nodiscard]] const rgb<T>& ambient() const noexcept { return ambient_; }

    /// Radiance toward v from one light sample (the formula above). Preconditions: v,
    /// s.l and at.n() unit length (checked by SHADE_ASSERT in debug builds).
    [[nodiscard]] rgb<T> shade(const surface_point<T>& at, const vec3<T>& v,
                               const light_sample<T>& s) const {
        SHADE_ASSERT(is_unit_length(v) && is_unit_length(s.l) && is_unit_length(at.n()));
        rgb<T> out = ambient_ * s.ambient;
        const T n_dot_l = clamped_dot(at.n(), s.l);
        if (n_dot_l <= T(0)) return out;
        if constexpr (split_brdf<B>) {
            out += pi<T> * n_dot_l *
                   (brdf_.f_diffuse(s.l, v, at) * s.diffuse + brdf_.f_specular(s.l, v, at) * s.specular);
        } else {
            out += pi<T> * n_dot_l * brdf_.f(s.l, v, at) * s.diffuse;
        }
        return out;
    }

private:
    B brdf_;
    rgb<T> ambient_;
};

template <brdf B>
lit(B) -> lit<B>;
template <brdf B>
lit(B, rgb<scalar_of<B>>) -> lit<B>;

/// S can be shaded: it is a shader, or a BRDF (which shade_of lifts with shade::lit).
template <class S>
concept shader_or_brdf = shader<S> || brdf<S>;

/// The radiance s reflects toward v at `at` from one light sample: s.shade(at, v, sample)
/// for a shader, else lit<S>{s}.shade(at, v, sample) for a BRDF (no ambient term; wrap the
/// BRDF in shade::lit yourself to give it an ambient reflectance). Lets combinators and
/// light sums accept shaders and BRDFs alike.
template <shader_or_brdf S>
[[nodiscard]] rgb<scalar_of<S>> shade_of(const S& s, const surface_point<scalar_of<S>>& at,
                                         const vec3<scalar_of<S>>& v,
                                         const light_sample<scalar_of<S>>& sample) {
    if constexpr (shader<S>) {
        return s.shade(at, v, sample);
    } else {
        return lit<S>{s, rgb<scalar_of<S>>(0)}.shade(at, v, sample);
    }
}

} // namespace shade
