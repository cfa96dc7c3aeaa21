#pragma once
// shade::rough_dielectric: a rough interface between two dielectrics (etched or frosted
// glass), microfacet reflection and refraction, sampled by visible normals.

#include <cmath>
#include <concepts>
#include <limits>
#include <optional>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <shade/brdf/brdf.hpp>
#include <shade/brdf/detail/sampling.hpp>
#include <shade/brdf/fresnel.hpp>
#include <shade/brdf/microfacet/distribution.hpp>
#include <shade/bsdf/bsdf.hpp>
#include <shade/bsdf/refract.hpp>
#include <shade/core/error.hpp>
#include <shade/core/math.hpp>
#include <shade/core/scalar.hpp>
#include <shade/core/surface_point.hpp>
#include <shade/core/types.hpp>

namespace shade {

/// A rough dielectric interface over a microfacet distribution (shade::ggx or
/// shade::beckmann, isotropic or anisotropic), from either side.
///
/// Walter, Marschner, Li, Torrance 2007, "Microfacet Models for Refraction through Rough
/// Surfaces", EGSR. With eta' = eta_l / eta_v (1 for a reflection; for a refraction eta
/// when v is outside, 1/eta when inside), the microfacet normal m of a pair (l, v) is the
/// generalized half vector of their eq. 16, m = normalize(v + eta' l) turned to the
/// outside (+z), and, with F the exact Fresnel reflectance at m (eq. 22; of v·m from v's
/// side for a reflection, from the rarer side for a refraction, where it is the same),
/// G = 1 / (1 + Lambda(v) + Lambda(l)) the height-correlated Smith term (Heitz 2014,
/// "Understanding the Masking-Shadowing Function in Microfacet-Based BRDFs", JCGT 3(2),
/// eq. 99, used for transmission as well, as Pharr, Jakob, Humphreys 2023, "Physically
/// Based Rendering", 4th ed., sec. 9.7 do) and D the distribution,
///
///     reflection (eq. 20):  f = F G D / (4 |n·l| |n·v|)
///     refraction (eq. 21):  f = |l·m| |v·m| / (|n·l| |n·v|) (1 - F) G D / (eta' (l·m) + v·m)^2
///
/// in radiance mode (eq. 21 with eta_o^2 / eta_i^2 divided out: the 1/eta'^2 change of
/// radiance included); in importance mode the refraction is eta'^2 times that, which is
/// f_radiance(v, l) (Veach 1997, eq. 5.14). Pairs whose m faces away from l or v
/// (l·m or v·m of the wrong sign) give 0.
///
/// Sampling (the scheme of Walter et al. 2007, with the visible normals of Heitz 2018,
/// "Sampling the GGX Distribution of Visible Normals", JCGT 7(4), as
/// Distribution::sample_visible_normal draws them): m from D_v(m) = G1(v) (v·m) D(m) / |n·v|
/// seen from v's side, then the reflection about m when uc < F (probability F) or the
/// refraction through m (probability 1 - F). The density of l is D_v(m) times the Jacobian
/// of l with respect to m (eqs. 14 and 17):
///
///     reflection: pdf = F D_v(m) / (4 v·m)
///     refraction: pdf = (1 - F) D_v(m) |l·m| / (l·m + v·m / eta')^2
///
/// A drawn l on the wrong side of the surface (reflected below, refracted back up) is
/// lost: sample returns nullopt, and pdf integrates over the sphere to the probability of
/// a direction. Flags glossy reflection or glossy transmission.
///
/// Parameters: eta = n_inside / n_outside in [1e-4, 1e4], not 1 (an index-matched
/// interface transmits straight through, a delta that shade::smooth_dielectric has);
/// the distribution's roughness as it validates it.
template <sampled_microfacet_distribution Distribution>
class rough_dielectric {
    using T = scalar_of<Distribution>;

public:
    using scalar_type = T;

    /// An interface with the given distribution of microfacet normals and relative index
    /// eta = n_inside / n_outside. Throws shade::invalid_parameter naming "eta" unless eta
    /// lies in [1e-4, 1e4] and is not 1.
    rough_dielectric(const Distribution& distribution, T eta)
        : distribution_(distribution), eta_(require_in_range("eta", eta, dielectric_eta_min<T>, dielectric_eta_max<T>)) {
        if (eta == T(1))
            throw invalid_parameter("eta", "must not be 1 (an index-matched interface is a delta: smooth_dielectric)",
                                    detail::to_text(eta));
    }

    /// Unchecked: the caller guarantees eta in [1e-4, 1e4], eta != 1.
    constexpr rough_dielectric(unchecked_t, const Distribution& distribution, T eta) noexcept
        : distribution_(distribution), eta_(eta) {}

    /// The distribution of microfacet normals.
    [[nodiscard]] constexpr const Distribution& distribution() const noexcept { return distribution_; }

    /// The relative index of refraction n_inside / n_outside.
    [[nodiscard]] constexpr T eta() const noexcept { return eta_; }

    /// The BSDF value in 1/sr without the cosine, radiance mode, for l and v on either side
    /// (eqs. 20 and 21 above); 0 when either lies on the surface.
    [[nodiscard]] rgb<T> f(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const noexcept {
        return f_and_pdf(l, v, at).f;
    }

    /// The density (1/sr, over the sphere) with which sample() draws l for v.
    [[nodiscard]] T pdf(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const noexcept {
        const view_side side = side_of(at.shading.to_local(v));
        if (!side.valid) return T(0);
        return evaluate(side.mirrored(at.shading.to_local(l)), side).pdf;
    }

    /// f(l, v, at) and pdf(l, v, at) from one evaluation of their shared terms.
    struct value_and_density {
        rgb<T> f{0}; ///< as f()
        T pdf = 0;   ///< as pdf()
    };
    [[nodiscard]] value_and_density f_and_pdf(const vec3<T>& l, const vec3<T>& v,
                                              const surface_point<T>& at) const noexcept {
        detail::assert_unit_directions(l, v, at);
        return f_and_pdf_local(at.shading.to_local(l), at.shading.to_local(v));
    }

    /// f_and_pdf(l, v, at) for l and v given in the shading frame of `at` (l_local =
    /// at.shading.to_local(l), likewise v), for a caller that has them already.
    [[nodiscard]] value_and_density f_and_pdf_local(const vec3<T>& l_local, const vec3<T>& v_local) const noexcept {
        const view_side side = side_of(v_local);
        if (!side.valid) return {};
        const lobe value = evaluate(side.mirrored(l_local), side);
        return {rgb<T>(value.f), value.pdf};
    }

    /// The direction l that sample(v, uc, u, at) draws, without f and pdf (for a mixture
    /// that evaluates itself at l); nullopt where sample()'s direction is.
    [[nodiscard]] std::optional<vec3<T>> draw(const vec3<T>& v, T uc, const vec2<T>& u,
                                              const surface_point<T>& at) const noexcept {
        const std::optional<vec3<T>> l_local = draw_local(at.shading.to_local(v), uc, u);
        if (!l_local) return std::nullopt;
        return at.shading.to_world(*l_local);
    }

    /// draw() in the shading frame: l_local for v_local (both local, n = +z).
    [[nodiscard]] std::optional<vec3<T>> draw_local(const vec3<T>& v_local, T uc, const vec2<T>& u) const noexcept {
        const view_side side = side_of(v_local);
        if (!side.valid) return std::nullopt;
        const vec3<T>& v_up = side.v;
        const vec3<T> m = distribution_.sample_visible_normal(v_up, u);
        const T v_dot_m = glm::dot(v_up, m);
        if (!(v_dot_m > T(0))) return std::nullopt;
        if (uc < F_dielectric(v_dot_m, side.eta)) {
            const vec3<T> l_up = detail::reflect_about(v_up, m);
            if (!(l_up.z > T(0))) return std::nullopt;
            return side.mirrored(l_up);
        }
        const std::optional<vec3<T>> t = refract(v_up, m, side.eta);
        if (!t || !(t->z < T(0))) return std::nullopt;
        return side.mirrored(*t);
    }

    /// Draws l for v (either side): a visible normal m from u, then the reflection about m
    /// when uc < F, else the refraction through m. f and weight in the given mode; eta of
    /// the sample eta' for a refraction, 1 for a reflection. nullopt when v lies on the
    /// surface or l lands on the wrong side of it.
    [[nodiscard]] std::optional<bsdf_sample<T>> sample(const vec3<T>& v, T uc, const vec2<T>& u,
                                                       const surface_point<T>& at,
                                                       transport_mode mode = transport_mode::radiance) const noexcept {
        const view_side side = side_of(at.shading.to_local(v));
        if (!side.valid) return std::nullopt;
        // draw()'s steps, with the direction kept in the mirrored frame for evaluate.
        const vec3<T>& v_up = side.v;
        const vec3<T> m = distribution_.sample_visible_normal(v_up, u);
        const T v_dot_m = glm::dot(v_up, m);
        if (!(v_dot_m > T(0))) return std::nullopt;
        vec3<T> l_up;
        if (uc < F_dielectric(v_dot_m, side.eta)) {
            l_up = detail::reflect_about(v_up, m);
            if (!(l_up.z > T(0))) return std::nullopt;
        } else {
            const std::optional<vec3<T>> t = refract(v_up, m, side.eta);
            if (!t || !(t->z < T(0))) return std::nullopt;
            l_up = *t;
        }
        const lobe value = evaluate(l_up, side);
        const bool transmitted = l_up.z < T(0);
        const T f = transmitted && mode == transport_mode::importance ? value.f * sqr(side.eta) : value.f;
        const vec3<T> l = at.shading.to_world(side.mirrored(l_up));
        const std::optional<brdf_sample<T>> s = detail::make_brdf_sample(l, rgb<T>(f), value.pdf, std::abs(l_up.z));
        if (!s) return std::nullopt;
        return bsdf_sample<T>{s->l, s->f, s->pdf, s->weight,
                              transmitted ? bsdf_flags::glossy_transmission : bsdf_flags::glossy_reflection,
                              transmitted ? side.eta : T(1)};
    }

private:
    /// The view in the local frame mirrored to the outside (z > 0) when it is inside, with
    /// the index of the far side over v's side: the interface seen from inside is the same
    /// microsurface, mirrored, with eta inverted.
    struct view_side {
        vec3<T> v{0, 0, 1}; ///< v with z >= 0
        T eta = 1;          ///< n_far / n_v: eta outside, 1/eta inside
        bool inside = false;
        bool valid = false; ///< false when v lies on the surface (or is not finite)

        /// w in the same mirrored frame (z negated when v is inside).
        [[nodiscard]] vec3<T> mirrored(const vec3<T>& w) const noexcept {
            return inside ? vec3<T>(w.x, w.y, -w.z) : w;
        }
    };

    [[nodiscard]] view_side side_of(const vec3<T>& v) const noexcept {
        view_side s;
        if (!(v.z != T(0)) || !std::isfinite(v.z)) return s;
        s.valid = true;
        s.inside = v.z < T(0);
        s.v = s.inside ? vec3<T>(v.x, v.y, -v.z) : v;
        s.eta = s.inside ? T(1) / eta_ : eta_;
        return s;
    }

    /// f (radiance mode) and pdf of a pair in the mirrored frame.
    struct lobe {
        T f = 0;
        T pdf = 0;
    };

    /// eqs. 20-21 and the densities above, for l (mirrored frame) and v = side.v (z > 0).
    [[nodiscard]] lobe evaluate(const vec3<T>& l, const view_side& side) const noexcept {
        const vec3<T>& v = side.v;
        const T cos_v = v.z;
        const T cos_l = l.z;
        if (!(cos_l != T(0)) || !std::isfinite(cos_l)) return {};
        const bool reflected = cos_l > T(0);
        const T eta_prime = reflected ? T(1) : side.eta;
        // The generalized half vector, turned to the outside (Walter et al. eq. 16).
        const std::optional<vec3<T>> half = generalized_half_vector(l, v, eta_prime);
        if (!half) return {};
        const vec3<T>& m = *half;
        const T v_dot_m = glm::dot(v, m);
        const T l_dot_m = glm::dot(l, m);
        // Microfacets facing away from v, or from l on its side, scatter nothing (the side
        // tests chi+((w·m)/(w·n)) of Walter et al. eq. 7, as in G1(w, m)).
        if (!detail::same_side(v_dot_m, v.z) || !detail::same_side(l_dot_m, cos_l)) return {};
        const T D = distribution_.D(m);
        // Lambda(v) and G1(v) (below), from one square root where the distribution has both.
        T lambda_v, g1_v;
        if constexpr (requires { distribution_.Lambda_and_G1(v); }) {
            const auto masking_v = distribution_.Lambda_and_G1(v);
            lambda_v = masking_v.lambda;
            g1_v = masking_v.g1;
        } else {
            lambda_v = distribution_.Lambda(v);
            g1_v = distribution_.G1(v);
        }
        // Lambda is two-sided: l below the surface has the Lambda of its mirror image.
        const T G = T(1) / (T(1) + (distribution_.Lambda(l) + lambda_v));
        // F of a refraction is the same seen from either side; it is taken from the rarer
        // side (eta > 1 across the interface), where F_dielectric has no total internal
        // reflection to come near, so that f(l, v) and f(v, l) use the same cosine and
        // stay adjoint to rounding: from v's side (v·m > 0, index ratio side.eta) or from l's
        // (l·m < 0 for a refraction: the two-sided F_dielectric inverts side.eta).
        const T F = F_dielectric(reflected || side.eta >= T(1) ? v_dot_m : l_dot_m, side.eta);
        // |n·l| and n·v floored at machine epsilon in the denominators (the cos_floor of
        // microfacet_reflection), so that f and pdf stay finite for grazing directions whose
        // cosines are tiny or subnormal (their product would round to 0).
        constexpr T cos_floor = std::numeric_limits<T>::epsilon();
        const T floored_cos_v = glm::max(cos_v, cos_floor);
        const T floored_cos_l = glm::max(glm::abs(cos_l), cos_floor);
        const T D_visible = g1_v * v_dot_m * D / floored_cos_v;
        if (reflected) {
            return {F * G * D / (T(4) * floored_cos_l * floored_cos_v), F * D_visible / (T(4) * v_dot_m)};
        }
        const T transmittance = T(1) - F;
        const T denominator = sqr(eta_prime * l_dot_m + v_dot_m);
        const T abs_l_dot_m = -l_dot_m;
        const T f = abs_l_dot_m * v_dot_m * transmittance * G * D / (floored_cos_l * floored_cos_v * denominator);
        // dl/dm of the refraction, |l·m| / (l·m + v·m / eta')^2 = eta'^2 |l·m| / denominator.
        const T pdf = transmittance * D_visible * sqr(eta_prime) * abs_l_dot_m / denominator;
        return {f, pdf};
    }

    Distribution distribution_;
    T eta_;
};

} // namespace shade
