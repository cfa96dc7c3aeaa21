#pragma once
// The microfacet distribution contract (shade::microfacet_distribution,
// shade::sampled_microfacet_distribution) and the roughness bounds shared by shade::ggx and
// shade::beckmann.
//
// Every term works in the local shading frame: n = +z, t = +x, b = +y (shade/core/frame.hpp),
// so a microfacet normal m or a direction w is a unit vector whose z is its cosine with the
// normal and whose x and y lie along the tangent and the bitangent (the axes of alpha_x and
// alpha_y in an anisotropic distribution).
//
// Two-sided terms. The microsurface seen from below the surface is the same surface,
// mirrored: D(m) = D(-m) (with m_z entering squared), Lambda and G1 of a direction w are
// those of its mirror image (|w_z|), so that a model may give them normals and directions on
// either side, as a rough interface between two dielectrics does (pbrt-v4's convention,
// Pharr, Jakob, Humphreys 2023, "Physically Based Rendering", 4th ed., sec. 9.6). Which side
// a microfacet faces is not D's business: models take microfacet normals on n's side (the
// generalized half vector turned there, shade/bsdf/refract.hpp), and the masking of a normal
// m seen from w, G1(w, m), carries the side test chi+((w·m)/(w·n)) (Walter, Marschner, Li,
// Torrance 2007, "Microfacet Models for Refraction through Rough Surfaces", EGSR, eq. 7):
// from above the surface w sees the microfacets whose fronts face it, from below those whose
// backs do. A normal on the horizon (m_z = 0) or a direction on it (w_z = 0) has D = 0 or
// G1 = 0.

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
/// sampler of its visible normals, all in the local frame (w, m unit vectors on either side
/// unless said, as in the header comment):
///   * `x.D(m)`: D in 1/sr, D(-m) = D(m);
///   * `x.Lambda(w)`: Smith's Lambda (dimensionless, >= 0, the same for w and its mirror
///     image below the surface, +infinity for w.z = 0);
///   * `x.G1(w)` = 1 / (1 + Lambda(w)), in [0, 1];
///   * `x.sample_visible_normal(w, u)`: for w.z > 0, a microfacet normal m drawn, for u
///     uniform in [0,1)^2, with the density of visible normals D_w(m) (shade::D_visible).
/// (shade::ggx and shade::beckmann also have G1(w, m), detail::G1_of_normal.)
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
/// w and m in the local frame; 0 unless w.z > 0 and m.z > 0 (the normals of the surface seen
/// from above; D itself is two-sided). This is the density `sample_visible_normal(w, u)`
/// draws m with.
template <sampled_microfacet_distribution X>
[[nodiscard]] inline scalar_of<X> D_visible(const X& distribution, const vec3<scalar_of<X>>& w,
                                            const vec3<scalar_of<X>>& m) noexcept {
    using T = scalar_of<X>;
    const T w_dot_m = glm::dot(w, m);
    if (!(w.z > T(0)) || !(m.z > T(0)) || !(w_dot_m > T(0))) return T(0);
    return distribution.G1(w) * w_dot_m * distribution.D(m) / w.z;
}

namespace detail {

/// chi+(a / b) without the division: true when a and b are both > 0 or both < 0 (false when
/// either is 0 or NaN). The product a b would underflow to 0 for tiny a and b.
template <std::floating_point T>
[[nodiscard]] constexpr bool same_side(T a, T b) noexcept {
    return (a > T(0) && b > T(0)) || (a < T(0) && b < T(0));
}

/// The Smith masking of the microfacet normal m seen from the direction w, on either side
/// (local frame, unit vectors):
///
///     G1(w, m) = chi+((w·m) / (w·n)) G1(w)
///
/// Walter, Marschner, Li, Torrance 2007, "Microfacet Models for Refraction through Rough
/// Surfaces", EGSR: eq. 7 (no microfacet facing away from w is seen from w: the side test
/// is on w·m relative to w·n, not on w·n alone) times Smith's G1(w) = 1/(1 + Lambda(w)), the
/// distribution's own (for Beckmann and GGX, their eqs. 26 and 34). Returns G1 in [0, 1]; 0
/// when w·m and w_z differ in sign or either is 0: from above, the microfacets whose fronts
/// face w, from below those whose backs do. The configuration mirrored below the surface,
/// its normal turned back to n's side (w -> (w_x, w_y, -w_z), m -> (-m_x, -m_y, m_z)), has
/// the same value.
template <class X>
[[nodiscard]] inline scalar_of<X> G1_of_normal(const X& distribution, const vec3<scalar_of<X>>& w,
                                               const vec3<scalar_of<X>>& m) noexcept {
    using T = scalar_of<X>;
    return same_side(glm::dot(w, m), w.z) ? distribution.G1(w) : T(0);
}

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
