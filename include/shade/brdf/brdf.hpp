#pragma once
// The BRDF contract. Every reflection model in shade/brdf satisfies shade::brdf, and so can
// any user type: the property checks (shade/check) and the shader lift (shade/shading)
// accept anything that does.
//
// A BRDF is a small class with
//   * a member type `scalar_type` (float or double), and
//   * a const member `f(l, v, at)` returning rgb<scalar_type>: the BRDF value in 1/sr,
//     WITHOUT the cosine factor, for unit directions l (toward the light) and v (toward the
//     viewer) given in world space, at the surface point `at` (position and shading frame).
//     f is zero when l or v is not above the surface (dot(at.n(), w) <= 0).
//
// A BRDF may also expose `f_diffuse(l, v, at)` and `f_specular(l, v, at)` with
// f == f_diffuse + f_specular; the shader lift then lights the two parts with a light's
// diffuse and specular colours respectively (shade::split_brdf).

#include <concepts>

#include <shade/core/surface_point.hpp>
#include <shade/core/types.hpp>

namespace shade {

/// B names its scalar type as B::scalar_type, and that type is float or double.
template <class B>
concept has_scalar_type =
    requires { typename B::scalar_type; } && std::floating_point<typename B::scalar_type>;

/// B is a BRDF: `b.f(l, v, at)` returns the BRDF value (1/sr, no cosine) as linear RGB.
template <class B>
concept brdf = has_scalar_type<B> &&
    requires(const B& b, const vec3<typename B::scalar_type>& w,
             const surface_point<typename B::scalar_type>& at) {
        { b.f(w, w, at) } -> std::same_as<rgb<typename B::scalar_type>>;
    };

/// A BRDF that also reports its diffuse and specular parts separately (they sum to f).
template <class B>
concept split_brdf = brdf<B> &&
    requires(const B& b, const vec3<typename B::scalar_type>& w,
             const surface_point<typename B::scalar_type>& at) {
        { b.f_diffuse(w, w, at) } -> std::same_as<rgb<typename B::scalar_type>>;
        { b.f_specular(w, w, at) } -> std::same_as<rgb<typename B::scalar_type>>;
    };

/// Tag selecting a BRDF's unchecked constructor: `phong<float>(shade::unchecked, ...)`.
/// The unchecked constructors skip parameter validation (for hot loops that build models
/// from parameters already validated once); the caller promises the parameters satisfy the
/// documented rules of the validating constructor, otherwise f may return NaN, Inf or
/// negative values.
struct unchecked_t {
    explicit constexpr unchecked_t() = default;
};

/// The unchecked-construction tag value.
inline constexpr unchecked_t unchecked{};

/// The scalar type of a BRDF, shader or light.
template <has_scalar_type X>
using scalar_of = typename X::scalar_type;

} // namespace shade
