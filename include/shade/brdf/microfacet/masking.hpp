#pragma once
// Shadowing-masking terms G of the microfacet models, as the small term types
// shade::cook_torrance is composed from:
//
//   v_groove<T>                  Torrance-Sparrow V-groove cavities, any distribution
//   smith_ggx<T>                 separable Smith for ggx            G1(l) G1(v)
//   smith_beckmann<T>            separable Smith for beckmann, Walter et al.'s rational G1
//   smith_separable<T>           separable Smith, exact, any distribution with Lambda/G1
//   smith_height_correlated<T>   height-correlated Smith, exact, any distribution with Lambda
//
// (The exact Smith-Beckmann is smith_separable with beckmann; smith_ggx and smith_separable
// agree for ggx.) Each returns G in [0, 1], dimensionless. A masking term gives G either of
// the local-frame directions, `G(d, l, v, h, v_dot_h)` with l, v, h unit vectors in the
// shading frame (n = +z) and v_dot_h = v·h = l·h, or, for isotropic terms written against
// the cosine-only contract, `G(d, n·l, n·v, n·h, v·h)`; shade::cook_torrance uses the first
// when it exists. The terms shipped here have both.
//
// The Smith terms are two-sided, as the distributions' Lambda and G1 are
// (shade/brdf/microfacet/distribution.hpp): l or v below the surface gives the value of its
// mirror image, 0 on the horizon. Whether the microfacet normal faces l and v (the
// chi+ factors of Walter et al. 2007, eq. 7) is the caller's test (it holds for a reflection
// half vector of l and v above the surface); G1(w, m) of ggx and beckmann carries it. The
// V-groove term is a reflection term above the surface only: 0 unless n·l, n·v, n·h, v·h > 0.

#include <cmath>
#include <concepts>

#include <glm/common.hpp>

#include <shade/brdf/microfacet/beckmann.hpp>
#include <shade/brdf/microfacet/distribution.hpp>
#include <shade/brdf/microfacet/ggx.hpp>
#include <shade/core/types.hpp>

namespace shade {

/// The V-groove shadowing-masking of Torrance and Sparrow.
///
/// Torrance, Sparrow 1967, "Theory for Off-Specular Reflection from Roughened Surfaces",
/// JOSA 57(9); in this form Blinn 1977, "Models of Light Reflection for Computer
/// Synthesized Pictures", SIGGRAPH, and Cook, Torrance 1982, "A Reflectance Model for
/// Computer Graphics", ACM ToG 1(1) (the geometrical attenuation factor G):
///
///     G = min(1, 2 (n·h)(n·v) / (v·h), 2 (n·h)(n·l) / (l·h))
///
/// with v·h = l·h. Returns G in [0, 1]; 0 if n·l, n·v or v·h is <= 0. G = 1 for l = v = n.
template <std::floating_point T>
[[nodiscard]] constexpr T G_v_groove(T n_dot_l, T n_dot_v, T n_dot_h, T v_dot_h) noexcept {
    if (!(n_dot_l > T(0)) || !(n_dot_v > T(0)) || !(n_dot_h > T(0)) || !(v_dot_h > T(0)))
        return T(0);
    // Written as min(v·h, 2 (n·h) min(n·l, n·v)) / (v·h) so there is one division, by
    // v·h > 0, and the result cannot exceed 1 through rounding.
    const T shadowed = T(2) * n_dot_h * glm::min(n_dot_l, n_dot_v);
    return glm::min(v_dot_h, shadowed) / v_dot_h;
}

/// Masking term type: V-groove (see G_v_groove); works with any distribution (it ignores
/// it). Anisotropy does not enter: the V-groove term depends on the cosines only.
template <std::floating_point T>
struct v_groove {
    using scalar_type = T;

    /// G in [0, 1] for the given cosines (n·l, n·v, n·h, v·h); the distribution is unused.
    template <class Distribution>
    [[nodiscard]] static constexpr T G(const Distribution& /*distribution*/, T n_dot_l, T n_dot_v,
                                       T n_dot_h, T v_dot_h) noexcept {
        return G_v_groove(n_dot_l, n_dot_v, n_dot_h, v_dot_h);
    }

    /// G in [0, 1] for local l, v, h (the cosines are their z components).
    template <class Distribution>
    [[nodiscard]] static constexpr T G(const Distribution& /*distribution*/, const vec3<T>& l,
                                       const vec3<T>& v, const vec3<T>& h, T v_dot_h) noexcept {
        return G_v_groove(l.z, v.z, h.z, v_dot_h);
    }
};

/// Masking term type: separable Smith for Beckmann with Walter et al.'s rational G1
/// (see G1_smith_beckmann), G = G1(l) G1(v).
template <std::floating_point T>
struct smith_beckmann {
    using scalar_type = T;

    /// G = G1(n·l) G1(n·v) in [0, 1], with the distribution's m (isotropic form).
    [[nodiscard]] static T G(const beckmann<T>& distribution, T n_dot_l, T n_dot_v,
                             T /*n_dot_h*/, T /*v_dot_h*/) noexcept {
        return G1_smith_beckmann(n_dot_l, distribution.m()) *
               G1_smith_beckmann(n_dot_v, distribution.m());
    }

    /// G = G1(l) G1(v) in [0, 1] for local l, v; anisotropic: the rational G1 of
    /// a = w_z / sqrt(m_x^2 w_x^2 + m_y^2 w_y^2) (the projected slope of Heitz 2014, JCGT
    /// 3(2), eq. 80). Two-sided (l or v below: the value of its mirror image); 0 on the
    /// horizon.
    [[nodiscard]] static T G(const beckmann<T>& distribution, const vec3<T>& l, const vec3<T>& v,
                             const vec3<T>& /*h*/, T /*v_dot_h*/) noexcept {
        return G1(distribution, l) * G1(distribution, v);
    }

private:
    [[nodiscard]] static T G1(const beckmann<T>& d, const vec3<T>& w) noexcept {
        if (!(std::abs(w.z) > T(0))) return T(0);
        return detail::G1_beckmann_rational_of_a(detail::beckmann_a(w, d.m_x(), d.m_y()));
    }
};

/// Masking term type: separable Smith for GGX, G1(l) G1(v) (see G1_smith_ggx).
template <std::floating_point T>
struct smith_ggx {
    using scalar_type = T;

    /// G = G1(n·l) G1(n·v) in [0, 1], with the distribution's alpha (isotropic form).
    [[nodiscard]] static T G(const ggx<T>& distribution, T n_dot_l, T n_dot_v, T /*n_dot_h*/,
                             T /*v_dot_h*/) noexcept {
        return G1_smith_ggx(n_dot_l, distribution.alpha()) *
               G1_smith_ggx(n_dot_v, distribution.alpha());
    }

    /// G = G1(l) G1(v) in [0, 1] for local l, v, anisotropic (see G1_smith_ggx(w, ...)).
    [[nodiscard]] static T G(const ggx<T>& distribution, const vec3<T>& l, const vec3<T>& v,
                             const vec3<T>& /*h*/, T /*v_dot_h*/) noexcept {
        return distribution.G1(l) * distribution.G1(v);
    }
};

/// Masking term type: separable (uncorrelated) Smith shadowing-masking with the
/// distribution's own exact G1, for any shade::sampled_microfacet_distribution:
///
///     G2(l, v, h) = G1(l) G1(v)
///
/// Heitz 2014, "Understanding the Masking-Shadowing Function in Microfacet-Based BRDFs",
/// JCGT 3(2), eq. 98 (the heaviside factors on l·h and v·h are 1 for the reflection half
/// vector). With beckmann this is the exact (erf) Smith-Beckmann; with ggx it equals
/// smith_ggx. Returns G2 in [0, 1].
template <std::floating_point T>
struct smith_separable {
    using scalar_type = T;

    /// G2 = G1(l) G1(v) for local l, v.
    template <sampled_microfacet_distribution D>
        requires std::same_as<scalar_of<D>, T>
    [[nodiscard]] static T G(const D& distribution, const vec3<T>& l, const vec3<T>& v,
                             const vec3<T>& /*h*/, T /*v_dot_h*/) noexcept {
        return distribution.G1(l) * distribution.G1(v);
    }
};

/// Masking term type: height-correlated Smith shadowing-masking with the distribution's own
/// exact Lambda, for any shade::sampled_microfacet_distribution:
///
///     G2(l, v, h) = 1 / (1 + Lambda(l) + Lambda(v))
///
/// Heitz 2014, JCGT 3(2), eq. 99 (the heaviside factors on l·h and v·h are 1 for the
/// reflection half vector). A microfacet that is high on the surface is both less masked and
/// less shadowed; this form accounts for that correlation, so G2 >= the separable
/// G1(l) G1(v) (as (1 + a)(1 + b) >= 1 + a + b for a, b >= 0). Returns G2 in [0, 1]; 0 if
/// l or v lies on the horizon (Lambda = +infinity there); two-sided as Lambda.
template <std::floating_point T>
struct smith_height_correlated {
    using scalar_type = T;

    /// G2 = 1/(1 + Lambda(l) + Lambda(v)) for local l, v.
    template <sampled_microfacet_distribution D>
        requires std::same_as<scalar_of<D>, T>
    [[nodiscard]] static T G(const D& distribution, const vec3<T>& l, const vec3<T>& v,
                             const vec3<T>& /*h*/, T /*v_dot_h*/) noexcept {
        // 1 + (Lambda(l) + Lambda(v)): the inner sum is the same number in either order, so
        // G2(l, v) == G2(v, l) to the last bit (reciprocity).
        return T(1) / (T(1) + (distribution.Lambda(l) + distribution.Lambda(v)));
    }
};

/// X is a masking term usable with distribution D: it gives G in [0, 1] either of local
/// directions, `x.G(d, l, v, h, v_dot_h)` (vec3s in the shading frame), or of cosines,
/// `x.G(d, n·l, n·v, n·h, v·h)`. (smith_beckmann accepts only beckmann, smith_ggx only
/// ggx, the generic Smith terms any sampled_microfacet_distribution.)
template <class X, class D>
concept masking_for = microfacet_distribution<D> &&
    (requires(const X& x, const D& d, const vec3<typename D::scalar_type>& w, typename D::scalar_type c) {
        { x.G(d, w, w, w, c) } -> std::same_as<typename D::scalar_type>;
    } || requires(const X& x, const D& d, typename D::scalar_type c) {
        { x.G(d, c, c, c, c) } -> std::same_as<typename D::scalar_type>;
    });

} // namespace shade
