#pragma once
// The microfacet distribution contract (shade::microfacet_distribution,
// shade::sampled_microfacet_distribution) and the roughness bounds shared by shade::ggx and
// shade::beckmann.
//
// Every term works in the local shading frame: n = +z, t = +x, b = +y (shade/core/frame.hpp),
// so a microfacet normal m or a direction w is a unit vector whose z is its cosine with the
// normal and whose x and y lie along the tangent and the bitangent (the axes of alpha_x and
// alpha_y in an anisotropic distribution).

#include <concepts>
#include <string_view>

#include <glm/geometric.hpp>

#include <shade/core/error.hpp>
#include <shade/core/scalar.hpp>
#include <shade/core/types.hpp>

namespace shade {

/// Smallest accepted microfacet roughness parameter (Beckmann m, GGX alpha, and each of
/// their anisotropic pairs): 1e-4. A lobe narrower than this is below what float can
/// resolve around the mirror direction (the float spacing of cos(theta_h) just below 1,
/// 6e-8, is theta_h ~ 3.5e-4 rad), and the peak value 1/(pi m^2) = 3.2e7 still leaves f far
/// from overflow.
template <std::floating_point T>
inline constexpr T microfacet_parameter_min = T(1e-4);

/// Largest accepted microfacet roughness parameter: 1e4. Beyond it the distributions are
/// numerically flat, and the bound keeps every term's intermediate values finite.
template <std::floating_point T>
inline constexpr T microfacet_parameter_max = T(1e4);

namespace detail {

/// Throws invalid_parameter naming `name` unless x lies in [1e-4, 1e4].
template <std::floating_point T>
T require_microfacet_parameter(std::string_view name, T x) {
    return require_in_range(name, x, microfacet_parameter_min<T>, microfacet_parameter_max<T>);
}

} // namespace detail

/// X is a microfacet distribution: it names its scalar type T, `x.peak()` returns an upper
/// bound of D, and it evaluates D in 1/sr either of a microfacet normal given in the local
/// frame, `x.D(m)` with m a unit vec3<T> (shade::ggx and shade::beckmann, anisotropic
/// included), or, for isotropic distributions written against the cosine-only contract,
/// `x.D(n_dot_h)`. shade::cook_torrance uses the local form when it exists.
template <class X>
concept microfacet_distribution = has_scalar_type<X> &&
    requires(const X& x) {
        { x.peak() } -> std::same_as<typename X::scalar_type>;
    } &&
    (requires(const X& x, const vec3<typename X::scalar_type>& m) {
        { x.D(m) } -> std::same_as<typename X::scalar_type>;
    } || requires(const X& x, typename X::scalar_type c) {
        { x.D(c) } -> std::same_as<typename X::scalar_type>;
    });

/// X is a microfacet distribution with the Smith masking of its own microsurface and a
/// sampler of its visible normals, all in the local frame (w, m unit vectors, w.z > 0):
///   * `x.D(m)`: D in 1/sr;
///   * `x.Lambda(w)`: Smith's Lambda (dimensionless, >= 0, +infinity for w.z <= 0);
///   * `x.G1(w)` = 1 / (1 + Lambda(w)), in [0, 1];
///   * `x.sample_visible_normal(w, u)`: a microfacet normal m drawn, for u uniform in
///     [0,1)^2, with the density of visible normals D_w(m) (shade::D_visible).
template <class X>
concept sampled_microfacet_distribution = microfacet_distribution<X> &&
    requires(const X& x, const vec3<typename X::scalar_type>& w,
             const vec2<typename X::scalar_type>& u) {
        { x.D(w) } -> std::same_as<typename X::scalar_type>;
        { x.Lambda(w) } -> std::same_as<typename X::scalar_type>;
        { x.G1(w) } -> std::same_as<typename X::scalar_type>;
        { x.sample_visible_normal(w, u) } -> std::same_as<vec3<typename X::scalar_type>>;
    };

/// The distribution of normals visible from w, in 1/sr:
///
///     D_w(m) = G1(w) max(0, w·m) D(m) / (n·w)
///
/// Heitz, d'Eon 2014, "Importance Sampling Microfacet-Based BSDFs using the Distribution
/// of Visible Normals", EGSR (Computer Graphics Forum 33(4)); normalized by the
/// relation of Heitz 2014, "Understanding the Masking-Shadowing Function in
/// Microfacet-Based BRDFs", JCGT 3(2), eq. 2: integral of G1(w) max(0, w·m) D(m) dm = n·w.
/// w and m in the local frame; 0 unless w.z > 0. This is the density
/// `sample_visible_normal(w, u)` draws m with.
template <sampled_microfacet_distribution X>
[[nodiscard]] inline scalar_of<X> D_visible(const X& distribution, const vec3<scalar_of<X>>& w,
                                            const vec3<scalar_of<X>>& m) noexcept {
    using T = scalar_of<X>;
    const T w_dot_m = glm::dot(w, m);
    if (!(w.z > T(0)) || !(w_dot_m > T(0))) return T(0);
    return distribution.G1(w) * w_dot_m * distribution.D(m) / w.z;
}

namespace detail {

/// The name of the parameter that sets the distribution's peak value (for error messages
/// when the peak overflows): `x.peak_parameter()` when the distribution has it, else
/// "distribution".
template <class X>
[[nodiscard]] constexpr std::string_view peak_parameter_of(const X& x) noexcept {
    if constexpr (requires { { x.peak_parameter() } -> std::convertible_to<std::string_view>; })
        return x.peak_parameter();
    else
        return "distribution";
}

} // namespace detail

} // namespace shade
