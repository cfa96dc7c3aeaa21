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
//     f is zero when l or v is not above the surface (dot(at.n(), w) <= 0). Unit length is
//     a precondition, not checked in release builds; shade's models check it with
//     SHADE_ASSERT in debug builds (detail::assert_unit_directions).
//
// A BRDF that can also draw directions (shade::sampled_brdf) has
//   * `sample(v, uc, u, at)` -> std::optional<brdf_sample<T>>: draws a direction l toward
//     the light for the view v, using uc in [0,1) to choose a lobe and u in [0,1)^2 for the
//     direction within it; nullopt when v is not above the surface or the drawn direction
//     is not, and
//   * `pdf(l, v, at)` -> T: the solid-angle density (1/sr) with which sample() draws l for
//     this v (0 where it never does; for a mixture of lobes, the mixture density).
// The pair follows pbrt-v4's BxDF interface (Pharr, Jakob, Humphreys 2023, "Physically
// Based Rendering", 4th ed., sec. 9.1.2): f, Sample_f and PDF.
//
// A BRDF may also expose `f_diffuse(l, v, at)` and `f_specular(l, v, at)` with
// f == f_diffuse + f_specular; the shader lift then lights the two parts with a light's
// diffuse and specular colours respectively (shade::split_brdf).

#include <cmath>
#include <concepts>
#include <limits>
#include <optional>

#include <shade/core/config.hpp>
#include <shade/core/math.hpp>
#include <shade/core/scalar.hpp>
#include <shade/core/surface_point.hpp>
#include <shade/core/types.hpp>

namespace shade {

/// B is a BRDF: `b.f(l, v, at)` returns the BRDF value (1/sr, no cosine) as linear RGB.
template <class B>
concept brdf = has_scalar_type<B> &&
    requires(const B& b, const vec3<typename B::scalar_type>& w,
             const surface_point<typename B::scalar_type>& at) {
        { b.f(w, w, at) } -> std::same_as<rgb<typename B::scalar_type>>;
    };

/// A direction drawn by a BRDF's sample(): everything an estimator of the reflected
/// radiance needs, so that a path tracer never re-evaluates f at the sampled direction.
template <std::floating_point T>
struct brdf_sample {
    using scalar_type = T;

    vec3<T> l{0, 0, 1}; ///< sampled unit direction toward the light, world space
    rgb<T> f{0};        ///< f(l, v, at), 1/sr, without the cosine
    T pdf{0};           ///< solid-angle density of l (1/sr), > 0
    rgb<T> weight{0};   ///< f * |n·l| / pdf: the Monte-Carlo weight of this sample
};

/// B is a BRDF that can also draw directions and report their density:
/// `b.sample(v, uc, u, at)` returns std::optional<brdf_sample<T>> and `b.pdf(l, v, at)`
/// the solid-angle density sample() draws l with (see the contract above).
template <class B>
concept sampled_brdf = brdf<B> &&
    requires(const B& b, const vec3<typename B::scalar_type>& w, typename B::scalar_type uc,
             const vec2<typename B::scalar_type>& u,
             const surface_point<typename B::scalar_type>& at) {
        { b.sample(w, uc, u, at) } -> std::same_as<std::optional<brdf_sample<typename B::scalar_type>>>;
        { b.pdf(w, w, at) } -> std::same_as<typename B::scalar_type>;
    };

namespace detail {

/// The debug-build check of f's precondition (SHADE_ASSERT, core/config.hpp): l, v and the
/// shading normal are unit vectors (shade::is_unit_length). A model's f calls it first;
/// with NDEBUG it compiles to nothing.
template <std::floating_point T>
inline void assert_unit_directions(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) noexcept {
    SHADE_ASSERT(is_unit_length(l));
    SHADE_ASSERT(is_unit_length(v));
    SHADE_ASSERT(is_unit_length(at.n()));
    (void)l;
    (void)v;
    (void)at;
}

/// The brdf_sample for direction l with value f, density pdf and |n·l| = abs_n_dot_l:
/// weight = f |n·l| / pdf. nullopt unless pdf is finite and > 0 (a direction the sampler
/// cannot have drawn carries no usable weight).
template <std::floating_point T>
[[nodiscard]] inline std::optional<brdf_sample<T>> make_brdf_sample(const vec3<T>& l, const rgb<T>& f,
                                                                    T pdf, T abs_n_dot_l) noexcept {
    if (!(pdf > T(0)) || !(pdf <= std::numeric_limits<T>::max())) return std::nullopt;
    // f (|n·l| / pdf) when that ratio is a normal number. Otherwise the ratio has
    // underflowed (lost precision) or overflowed (0 x inf would be NaN), as happens with a
    // subnormal pdf or |n·l|: each factor is then split into mantissa and exponent
    // (std::frexp, exact), the mantissas combined in [1/4, 4], and the exponents applied
    // once at the end (std::ldexp), so only the final result can underflow or overflow.
    const T ratio = abs_n_dot_l / pdf;
    if (ratio >= std::numeric_limits<T>::min() && ratio <= std::numeric_limits<T>::max())
        return brdf_sample<T>{l, f, pdf, f * ratio};
    int e_cos = 0;
    int e_pdf = 0;
    const T m_cos = std::frexp(abs_n_dot_l, &e_cos);
    const T m_pdf = std::frexp(pdf, &e_pdf);
    rgb<T> weight(0);
    for (int i = 0; i < 3; ++i) {
        int e_f = 0;
        const T m_f = std::frexp(f[i], &e_f);
        weight[i] = std::ldexp(m_f * m_cos / m_pdf, e_f + e_cos - e_pdf);
    }
    return brdf_sample<T>{l, f, pdf, weight};
}

/// The brdf_sample for direction l with value f and density pdf when the caller knows the
/// weight f |n·l| / pdf in closed form (`exact`, e.g. a colour times an albedo). The
/// closed form is kept in each channel where f is a normal number. Where f has
/// underflowed to a subnormal or to 0 (a tiny colour channel times a tiny lobe value), it
/// has lost the digits the closed form still has, and the weight of that channel is
/// computed from f as make_brdf_sample does, so that f, pdf and weight stay consistent.
/// nullopt unless pdf is finite and > 0.
template <std::floating_point T>
[[nodiscard]] inline std::optional<brdf_sample<T>> make_brdf_sample(const vec3<T>& l, const rgb<T>& f, T pdf,
                                                                    T abs_n_dot_l, const rgb<T>& exact) noexcept {
    std::optional<brdf_sample<T>> s = make_brdf_sample(l, f, pdf, abs_n_dot_l);
    if (!s) return std::nullopt;
    for (int i = 0; i < 3; ++i)
        if (f[i] >= std::numeric_limits<T>::min()) s->weight[i] = exact[i];
    return s;
}

} // namespace detail

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

} // namespace shade
