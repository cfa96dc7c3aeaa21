#pragma once
// shade::zeltner_sheen: the sheen of a layer of fibres standing on the surface (cloth,
// dust, peach fuzz), as a linearly transformed cosine. It is the fuzz lobe of OpenPBR
// Surface 1.1 and the "zeltner" mode of MaterialX's sheen_bsdf. The fitted functions
// it reads (the directional albedo E and the LTC matrix) are public too, because a layer
// under the sheen needs E: OpenPBR puts the base under the fuzz as
//
//   f_surface = w f_fuzz + (1 - w E(mu_v, alpha)) f_base          (w = fuzz_weight)
//
// zeltner_sheen is that lobe as specified (not reciprocal); zeltner_sheen_reciprocal is a
// reciprocal lobe with the same albedo and a simpler shape.
//
// Not part of shade/shade.hpp: include this header where it is used.

#include <cmath>
#include <concepts>
#include <limits>
#include <optional>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <shade/brdf/brdf.hpp>
#include <shade/core/error.hpp>
#include <shade/core/math.hpp>
#include <shade/core/sampling.hpp>
#include <shade/core/surface_point.hpp>
#include <shade/core/types.hpp>

namespace shade {

/// The smallest alpha the sheen fits are used at. Zeltner, Burley, Chiang tabulated their
/// fit on alpha = max(0.01, k/31), and production code (MaterialX's sheen_bsdf, the
/// MaterialX PBR specification's appendix) clamps roughness to [0.01, 1] the same way; at
/// alpha = 0 the fitted LTC matrix is singular (a_inv = 0).
template <std::floating_point T>
inline constexpr T zeltner_sheen_min_alpha = T(0.01);

/// The inverse LTC matrix of the sheen lobe, M^-1 = [[a_inv, 0, b_inv], [0, a_inv, 0],
/// [0, 0, 1]], in the frame whose x axis is the view's tangent direction (see
/// shade::zeltner_sheen).
template <std::floating_point T>
struct zeltner_sheen_ltc {
    T a_inv; ///< the diagonal entries (1,1) and (2,2) of M^-1, > 0 for alpha > 0
    T b_inv; ///< the entry (1,3) of M^-1, <= 0 (the lobe leans away from the view)
};

namespace detail {

/// 1 / sqrt(2 pi).
template <std::floating_point T>
inline constexpr T inv_sqrt_two_pi = T(0.398942280401432677939946059934381868L);

/// The parameters of the Gaussian fit of the sheen albedo at alpha (clamped to
/// [zeltner_sheen_min_alpha, 1]): E = exp(-(mu - m)^2 / (2 s^2)) / (s sqrt(2 pi)) + o
/// (see zeltner_sheen_albedo). s > 0; o < 0 for alpha in (0.0413, 0.1324), down to
/// -2.11e-5.
template <std::floating_point T>
struct sheen_albedo_fit {
    T s; ///< standard deviation of the Gaussian
    T m; ///< its mean
    T o; ///< the offset added to it

    [[nodiscard]] static sheen_albedo_fit at(T alpha) noexcept {
        const T y = glm::clamp(alpha, zeltner_sheen_min_alpha<T>, T(1));
        return {y * (T(0.0206607) + T(1.58491) * y) / (T(0.0379424) + y * (T(1.32227) + y)),
                y * (T(-0.193854) + y * (T(-1.14885) + y * (T(1.7932) - T(0.95943) * y * y))) / (T(0.046391) + y),
                y * (T(0.000654023) + (T(-0.0207818) + T(0.119681) * y) * y) / (T(1.26264) + y * (T(-1.92021) + y))};
    }

    /// The Gaussian alone at mu (clamped to [0, 1]).
    [[nodiscard]] T gaussian(T mu) const noexcept {
        const T t = (glm::clamp(mu, T(0), T(1)) - m) / s;
        return std::exp(T(-0.5) * t * t) * inv_sqrt_two_pi<T> / s;
    }
};

} // namespace detail

/// The directional albedo E(mu, alpha) of the sheen layer (dimensionless, in [0, 1]):
/// the fraction of light arriving at cosine mu that the fibre layer reflects.
///
/// Zeltner, Burley, Chiang 2022, "Practical Multiple-Scattering Sheen Using Linearly
/// Transformed Cosines", SIGGRAPH Talks (R_i of their eq. 1, tabulated on a 32 x 32 grid
/// from a random walk through the fibre volume); the closed-form fit of that table given in
/// the MaterialX PBR Specification (ASWF), appendix "Zeltner Sheen Model", section
/// "Directional Albedo", and in MaterialX's mx_microfacet_sheen.glsl
/// (mx_zeltner_sheen_dir_albedo), a Gaussian in x = mu with rational s, m, o in y = alpha:
///
///     s = y (0.0206607 + 1.58491 y) / (0.0379424 + y (1.32227 + y))
///     m = y (-0.193854 + y (-1.14885 + y (1.7932 - 0.95943 y^2))) / (0.046391 + y)
///     o = y (0.000654023 + (-0.0207818 + 0.119681 y) y) / (1.26264 + y (-1.92021 + y))
///     E = exp(-(x - m)^2 / (2 s^2)) / (s sqrt(2 pi)) + o
///
/// The constants are the fit's data. mu is clamped to [0, 1] and alpha to
/// [zeltner_sheen_min_alpha, 1]; E is clamped to [0, 1] because the fit dips to -2.1e-5
/// near normal incidence at small alpha (its largest value is 0.745, at mu = 0, alpha = 1).
template <std::floating_point T>
[[nodiscard]] inline T zeltner_sheen_albedo(T mu, T alpha) noexcept {
    const auto fit = detail::sheen_albedo_fit<T>::at(alpha);
    return glm::clamp(fit.gaussian(mu) + fit.o, T(0), T(1));
}

/// The inverse LTC matrix entries of the sheen lobe for a view at cosine mu and alpha.
///
/// Zeltner, Burley, Chiang 2022 (as for zeltner_sheen_albedo): M_i^-1 of their eq. 1 with
/// two free entries, tabulated by a fit to the fibre volume's BRDF; the rational fits of
/// that table given in the MaterialX PBR Specification, appendix "Zeltner Sheen Model",
/// section "Fitted Coefficients", and in MaterialX's mx_zeltner_sheen_ltc_aInv and
/// mx_zeltner_sheen_ltc_bInv, with x = mu, y = alpha:
///
///     a_inv = (2.58126 x + 0.813703 y) y / (1 + 0.310327 x^2 + 2.60994 x y)
///     b_inv = sqrt(1 - x) (y - 1) y^3 / (0.0000254053 + 1.71228 x - 1.71506 x y + 1.34174 y^2)
///
/// mu is clamped to [0, 1] and alpha to [zeltner_sheen_min_alpha, 1]; there a_inv > 0
/// (at least 8.1e-5, at mu = 0, alpha = 0.01), b_inv <= 0 (0 at mu = 1, where the lobe is
/// symmetric about n, and at alpha = 1), and both denominators exceed 1e-4.
template <std::floating_point T>
[[nodiscard]] inline zeltner_sheen_ltc<T> zeltner_sheen_ltc_of(T mu, T alpha) noexcept {
    const T x = glm::clamp(mu, T(0), T(1));
    const T y = glm::clamp(alpha, zeltner_sheen_min_alpha<T>, T(1));
    const T a_inv = (T(2.58126) * x + T(0.813703) * y) * y / (T(1) + T(0.310327) * x * x + T(2.60994) * x * y);
    const T b_inv = std::sqrt(T(1) - x) * (y - T(1)) * y * y * y /
                    (T(0.0000254053) + T(1.71228) * x - T(1.71506) * x * y + T(1.34174) * y * y);
    return {a_inv, b_inv};
}

/// The fuzz (sheen) lobe of OpenPBR Surface: a layer of fibres on the surface, seen as one
/// linearly transformed cosine per view.
///
/// Zeltner, Burley, Chiang 2022, "Practical Multiple-Scattering Sheen Using Linearly
/// Transformed Cosines", SIGGRAPH Talks, eq. 1; OpenPBR Surface 1.1 specification
/// (Andersson, Kutz, Portsmouth et al., ASWF), section "Fuzz"; the LTC density of Heitz,
/// Dupuy, Hill, Neubelt 2016, "Real-Time Polygonal-Light Shading with Linearly Transformed
/// Cosines", ACM TOG 35(4), sec. 3 (D(w) = D_o(w_o) |M^-1| / |M^-1 w|^3, w_o = M^-1 w / |M^-1 w|):
///
///     (n·l) f(l, v) = F E(mu_v, alpha) D(l | mu_v, alpha)
///     D(l) = (w_o·n / pi) a_inv^2 / |M^-1 l|^3 = (n·l) a_inv^2 / (pi |M^-1 l|^4)
///     f(l, v) = F E(mu_v, alpha) a_inv^2 / (pi |M^-1 l|^4)               (1/sr)
///
/// with F the colour (OpenPBR fuzz_color), mu_v = n·v, E = zeltner_sheen_albedo, M^-1 from
/// zeltner_sheen_ltc_of, and l written in the frame (x, y, n) whose x axis is the unit
/// tangent part of v, x = (v - (n·v) n) / |v - (n·v) n| (at v = n, where b_inv = 0 and the
/// lobe is symmetric about n, the shading tangent). The cosine cancels: f needs no
/// division by n·l. D is a density over the upper hemisphere (M^-1 keeps the z
/// component, so it maps the hemisphere to itself), and so the directional albedo of f
/// is exactly F E(mu_v, alpha) for every view: the layer below gets 1 - E of the light.
///
/// The volume behind the fit (Zeltner et al.; OpenPBR "Fuzz"): a slab of unit thickness
/// and unit density, purely scattering, index-matched, filled with SGGX microflakes of
/// the fibre-like form S = diag(1, 1, sigma^2) about n (Heitz, Dupuy, Crassin, Dachsbacher
/// 2015, "The SGGX Microflake Distribution", ACM TOG 34(4)), sigma = alpha^2; light that
/// crosses it leaves at the bottom.
///
/// Roughness: OpenPBR's fuzz_roughness, alpha = roughness in [0, 1]. alpha is raised to
/// zeltner_sheen_min_alpha = 0.01 as production code does, so roughness 0 and 0.01 are the
/// same lobe (it reflects almost nothing: E <= 1.3e-4). Small roughness is a sheen at
/// grazing views only; roughness 1 is dusty, E from 0.34 (mu = 1) to 0.74 (grazing).
///
/// Reciprocal: NO. The lobe's shape and its albedo both belong to v (E(mu_v) and the LTC
/// frame of v), as the paper says; f(l, v) and f(v, l) differ, most at small roughness.
/// Energy conserving: yes for F <= 1 (albedo F E <= 0.745 F).
///
/// Sampling (shade::sampled_brdf): exactly proportional to f (n·l), the clamped cosine
/// drawn from u and mapped by M (Heitz et al. 2016, sec. 3); every sample's weight is
/// F E(mu_v, alpha) (in each channel where f is a normal number); uc is not used.
template <std::floating_point T>
class zeltner_sheen {
public:
    using scalar_type = T;

    /// A sheen of colour `color` (OpenPBR fuzz_color) and roughness `roughness`
    /// (fuzz_roughness). Throws shade::invalid_parameter naming "color" unless every
    /// channel lies in [0, 1], or "roughness" unless it lies in [0, 1].
    zeltner_sheen(const rgb<T>& color, T roughness)
        : color_(require_in_range("color", color, T(0), T(1))),
          roughness_(require_in_range("roughness", roughness, T(0), T(1))),
          alpha_(glm::max(roughness, zeltner_sheen_min_alpha<T>)) {}

    /// Unchecked: the caller guarantees color in [0, 1]^3 and roughness in [0, 1].
    zeltner_sheen(unchecked_t, const rgb<T>& color, T roughness) noexcept
        : color_(color), roughness_(roughness), alpha_(glm::max(roughness, zeltner_sheen_min_alpha<T>)) {}

    [[nodiscard]] constexpr const rgb<T>& color() const noexcept { return color_; } ///< F, the tint of the reflection
    [[nodiscard]] constexpr T roughness() const noexcept { return roughness_; } ///< as given, in [0, 1]
    /// The alpha the fits are read at: max(roughness, zeltner_sheen_min_alpha).
    [[nodiscard]] constexpr T alpha() const noexcept { return alpha_; }

    /// E(mu, alpha) (zeltner_sheen_albedo): the layer's directional albedo at the view
    /// cosine mu, without the colour. The albedo of f for a view at cosine mu is
    /// color() * albedo(mu); 1 - albedo(mu) is what OpenPBR passes to the layer below.
    [[nodiscard]] T albedo(T mu) const noexcept { return zeltner_sheen_albedo(mu, alpha_); }

    /// BRDF value in 1/sr without the cosine: F E(n·v) a_inv^2 / (pi |M^-1 l|^4) (see the
    /// class comment); 0 unless n·l > 0 and n·v > 0.
    [[nodiscard]] rgb<T> f(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const noexcept {
        detail::assert_unit_directions(l, v, at);
        const lobe_at lobe = lobe_for(l, v, at);
        if (!(lobe.density_over_cos > T(0))) return rgb<T>(0);
        return color_ * (lobe.albedo * lobe.density_over_cos);
    }

    /// The density (1/sr) with which sample() draws l: the LTC density D(l) =
    /// (n·l) a_inv^2 / (pi |M^-1 l|^4), which integrates to 1 over the upper hemisphere;
    /// 0 unless n·l > 0 and n·v > 0.
    [[nodiscard]] T pdf(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const noexcept {
        const lobe_at lobe = lobe_for(l, v, at);
        return lobe.density_over_cos > T(0) ? lobe.n_dot_l * lobe.density_over_cos : T(0);
    }

    /// Draws l with the density pdf() from u (uc is not used): a direction of the clamped
    /// cosine mapped by M = (M^-1)^-1, which sends w_o to (w_o.x - b_inv w_o.z, w_o.y,
    /// a_inv w_o.z) up to a positive factor. The weight is F E(n·v) exactly in each channel
    /// where f is a normal number (detail::make_brdf_sample). nullopt when v is not above
    /// the surface or l falls on the horizon.
    [[nodiscard]] std::optional<brdf_sample<T>> sample(const vec3<T>& v, T /*uc*/, const vec2<T>& u,
                                                       const surface_point<T>& at) const noexcept {
        const vec3<T>& n = at.n();
        const T n_dot_v = glm::dot(n, v);
        if (!(n_dot_v > T(0))) return std::nullopt;
        const T mu = glm::min(n_dot_v, T(1));
        const zeltner_sheen_ltc<T> m = zeltner_sheen_ltc_of(mu, alpha_);
        const vec3<T> w_o = square_to_cosine_hemisphere(u);
        const vec3<T> local(w_o.x - m.b_inv * w_o.z, w_o.y, m.a_inv * w_o.z);
        const vec3<T> x = view_tangent(v, n_dot_v, at);
        const vec3<T> l = glm::normalize(local.x * x + local.y * glm::cross(n, x) + local.z * n);
        const lobe_at lobe = lobe_for(l, v, at);
        if (!(lobe.density_over_cos > T(0))) return std::nullopt;
        const T pdf = lobe.n_dot_l * lobe.density_over_cos;
        if (!(pdf > T(0))) return std::nullopt;
        return detail::make_brdf_sample(l, color_ * (lobe.albedo * lobe.density_over_cos), pdf, lobe.n_dot_l,
                                        color_ * lobe.albedo);
    }

private:
    // What f and pdf share for one pair: n·l, E(n·v) and D(l) / (n·l) = a_inv^2 / (pi
    // |M^-1 l|^4), the last 0 unless n·l > 0 and n·v > 0.
    struct lobe_at {
        T n_dot_l;
        T albedo;
        T density_over_cos;
    };

    // The unit tangent part of v, the x axis of the LTC frame; the shading tangent when v
    // has none (v = n up to rounding), where the lobe is symmetric about n. The part is
    // projected twice: for v near n, v - (n·v) n carries rounding error along n as large
    // as epsilon, and a frame built on it would not be orthonormal; the second projection
    // removes it. When what is left is itself rounding (|x| below 64 epsilon, v within
    // about 1e-5 rad of n in float), its direction is noise and may even lie along n, so
    // the shading tangent is used (its direction does not matter there, since b_inv ~
    // sqrt(1 - mu) -> 0).
    [[nodiscard]] static vec3<T> view_tangent(const vec3<T>& v, T n_dot_v, const surface_point<T>& at) noexcept {
        const vec3<T>& n = at.n();
        const vec3<T> v_t = v - n_dot_v * n;
        const vec3<T> x = v_t - glm::dot(n, v_t) * n;
        const T len2 = glm::dot(x, x);
        constexpr T floor = T(64) * std::numeric_limits<T>::epsilon();
        return len2 > floor * floor ? x / std::sqrt(len2) : at.shading.t;
    }

    [[nodiscard]] lobe_at lobe_for(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const noexcept {
        const vec3<T>& n = at.n();
        const T n_dot_l = glm::dot(n, l);
        const T n_dot_v = glm::dot(n, v);
        if (!(n_dot_l > T(0)) || !(n_dot_v > T(0))) return {n_dot_l, T(0), T(0)};
        const T mu = glm::min(n_dot_v, T(1));
        const zeltner_sheen_ltc<T> m = zeltner_sheen_ltc_of(mu, alpha_);
        const vec3<T> x = view_tangent(v, n_dot_v, at);
        const vec3<T> y = glm::cross(n, x);
        // M^-1 l in the frame (x, y, n); its z component is n·l.
        const T lx = glm::dot(l, x);
        const T ly = glm::dot(l, y);
        const T ox = m.a_inv * lx + m.b_inv * n_dot_l;
        const T oy = m.a_inv * ly;
        const T len2 = ox * ox + oy * oy + n_dot_l * n_dot_l;
        const T density_over_cos = m.a_inv * m.a_inv / (pi<T> * len2 * len2);
        return {n_dot_l, zeltner_sheen_albedo(mu, alpha_), density_over_cos};
    }

    rgb<T> color_;
    T roughness_;
    T alpha_;
};


/// A reciprocal sheen: the product of the fuzz lobe's albedos at l and at v,
///
///     f(l, v) = F E'(n·l) E'(n·v) / (pi E'_avg),    E'_avg = 2 integral_0^1 E'(mu) mu dmu   (1/sr)
///
/// the separable form of Kulla, Conty 2017, "Revisiting Physically Based Shading at
/// Imageworks", SIGGRAPH course (their f_ms, built from 1 - E), here built from E itself.
/// E' is zeltner_sheen_albedo's Gaussian plus max(o, 0): it differs from E by at most
/// 2.11e-5 (where the fit's offset o is negative, alpha in (0.0413, 0.1324)) and is never
/// negative, so E'_avg has a closed form (see average_albedo). Symmetric in l and v, and
/// its directional albedo is F E'(n·v): the energy of zeltner_sheen, which leaves the
/// same 1 - E'(n·v) to the layer below.
///
/// What it gives up is the LTC lobe's shape: f depends on the two cosines only, not on
/// the azimuth between l and v. The relative L1 distance of its cosine-weighted lobe from
/// zeltner_sheen's, integral |f' - f| (n·l) / integral f (n·l), is about 0.04 at
/// roughness 1, 0.08 to 0.4 at 0.7, 0.1 to 0.6 at 0.5 and up to 1 at 0.1 (grazing views);
/// zeltner_sheen differs from its own swap f(v, l) by comparable amounts (docs/conventions.md).
///
/// Sampling (shade::sampled_brdf): exactly proportional to f (n·l), whatever v: the
/// azimuth uniform and n·l = mu drawn with density E'(mu) mu / (E'_avg / 2) on [0, 1] by
/// inverting its distribution function C(mu) / C(1) (closed form, see average_albedo) with
/// safeguarded Newton steps; pdf(l) = E'(n·l) (n·l) / (pi E'_avg) (1/sr) and every
/// sample's weight is F E'(n·v). uc is not used.
template <std::floating_point T>
class zeltner_sheen_reciprocal {
public:
    using scalar_type = T;

    /// As zeltner_sheen's constructor: throws shade::invalid_parameter naming "color"
    /// unless every channel lies in [0, 1], or "roughness" unless it lies in [0, 1].
    zeltner_sheen_reciprocal(const rgb<T>& color, T roughness)
        : color_(require_in_range("color", color, T(0), T(1))),
          roughness_(require_in_range("roughness", roughness, T(0), T(1))),
          alpha_(glm::max(roughness, zeltner_sheen_min_alpha<T>)), fit_(detail::sheen_albedo_fit<T>::at(alpha_)),
          tail_a_(std::erfc(-double(fit_.m) / double(fit_.s) * inv_sqrt2)),
          phi_a_(std::exp(-0.5 * sqr(double(fit_.m) / double(fit_.s))) * detail::inv_sqrt_two_pi<double>),
          cdf_one_(cosine_cdf(1).value), e_avg_(T(cdf_one_)) {}

    /// Unchecked: the caller guarantees color in [0, 1]^3 and roughness in [0, 1].
    zeltner_sheen_reciprocal(unchecked_t, const rgb<T>& color, T roughness) noexcept
        : color_(color), roughness_(roughness), alpha_(glm::max(roughness, zeltner_sheen_min_alpha<T>)),
          fit_(detail::sheen_albedo_fit<T>::at(alpha_)),
          tail_a_(std::erfc(-double(fit_.m) / double(fit_.s) * inv_sqrt2)),
          phi_a_(std::exp(-0.5 * sqr(double(fit_.m) / double(fit_.s))) * detail::inv_sqrt_two_pi<double>),
          cdf_one_(cosine_cdf(1).value), e_avg_(T(cdf_one_)) {}

    [[nodiscard]] constexpr const rgb<T>& color() const noexcept { return color_; } ///< F
    [[nodiscard]] constexpr T roughness() const noexcept { return roughness_; } ///< as given
    [[nodiscard]] constexpr T alpha() const noexcept { return alpha_; } ///< max(roughness, 0.01)

    /// E'(mu): the directional albedo of this lobe without the colour (color() * albedo(mu)
    /// is the albedo of f for a view at cosine mu), within 2.11e-5 of zeltner_sheen_albedo.
    /// Values below 1e-18 in float (1e-150 in double) are returned as 0: f multiplies two of
    /// them, and a subnormal product would carry too few digits for f, pdf and the sample
    /// weight to agree.
    [[nodiscard]] T albedo(T mu) const noexcept {
        const T e = fit_.gaussian(mu) + glm::max(fit_.o, T(0));
        return e >= flush_below ? e : T(0);
    }

    /// E'_avg = C(1), with C(mu) = 2 integral_0^mu E'(t) t dt in closed form: with
    /// z(t) = (t - m)/s, Phi and phi the standard normal distribution and density,
    /// C(mu) = 2 (m (Phi(z(mu)) - Phi(z(0))) + s (phi(z(0)) - phi(z(mu)))) + max(o, 0) mu^2
    /// (the Gaussian part is the integral of (m + s z) phi(z) dz). Evaluated in double.
    [[nodiscard]] constexpr T average_albedo() const noexcept { return e_avg_; }

    /// BRDF value in 1/sr without the cosine: F E'(n·l) E'(n·v) / (pi E'_avg); 0 unless
    /// n·l > 0 and n·v > 0.
    [[nodiscard]] rgb<T> f(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const noexcept {
        detail::assert_unit_directions(l, v, at);
        const T n_dot_l = glm::dot(at.n(), l);
        const T n_dot_v = glm::dot(at.n(), v);
        if (!(n_dot_l > T(0)) || !(n_dot_v > T(0))) return rgb<T>(0);
        return color_ * (albedo(n_dot_l) * albedo(n_dot_v) / (pi<T> * e_avg_));
    }

    /// The density (1/sr) with which sample() draws l: E'(n·l) (n·l) / (pi E'_avg), the
    /// same for every v above the surface; 0 unless n·l > 0 and n·v > 0.
    [[nodiscard]] T pdf(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const noexcept {
        const T n_dot_l = glm::dot(at.n(), l);
        if (!(n_dot_l > T(0)) || !(glm::dot(at.n(), v) > T(0))) return T(0);
        return albedo(n_dot_l) * n_dot_l / (pi<T> * e_avg_);
    }

    /// Draws l with the density pdf() from u (u.x for n·l, u.y for the azimuth; uc is not
    /// used). The weight is F E'(n·v) exactly in each channel where f is a normal number
    /// (detail::make_brdf_sample). nullopt when v is not above the surface or l falls on
    /// the horizon.
    [[nodiscard]] std::optional<brdf_sample<T>> sample(const vec3<T>& v, T /*uc*/, const vec2<T>& u,
                                                       const surface_point<T>& at) const noexcept {
        const T n_dot_v = glm::dot(at.n(), v);
        if (!(n_dot_v > T(0))) return std::nullopt;
        const double mu = invert_cosine_cdf(double(u.x) * cdf_one_);
        const double sin_theta = std::sqrt((1 - mu) * (1 + mu));
        const double phi = 2 * pi<double> * double(u.y);
        const vec3<T> l = glm::normalize(
            at.shading.to_world(vec3<T>(T(sin_theta * std::cos(phi)), T(sin_theta * std::sin(phi)), T(mu))));
        const T n_dot_l = glm::dot(at.n(), l);
        if (!(n_dot_l > T(0))) return std::nullopt;
        const T e_v = albedo(n_dot_v);
        const T density = albedo(n_dot_l) * n_dot_l / (pi<T> * e_avg_);
        if (!(density > T(0))) return std::nullopt;
        return detail::make_brdf_sample(l, color_ * (albedo(n_dot_l) * e_v / (pi<T> * e_avg_)), density, n_dot_l,
                                        color_ * e_v);
    }

private:
    // Above the square root of the smallest normal number with room for the division by
    // pi E'_avg (<= 1.41): 1e-18^2 / 1.41 > 1.2e-38 (float), 1e-150^2 / 1.41 > 2.3e-308.
    static constexpr T flush_below = sizeof(T) <= 4 ? T(1e-18) : T(1e-150);

    // C(mu) = 2 integral_0^mu E'(t) t dt (see average_albedo) and its derivative
    // 2 E'(mu) mu, in double. Phi(z) - Phi(a) is taken as (erfc(a / sqrt 2) - erfc(z /
    // sqrt 2)) / 2, the difference of two upper tails, which keeps its precision where both
    // are near 1 (m < 0 puts a = -m/s up to ~5); erfc(a / sqrt 2) and phi(a) are the
    // constructor's (tail_a_, phi_a_).
    struct cdf_at {
        double value;
        double slope;
    };
    [[nodiscard]] cdf_at cosine_cdf(double mu) const noexcept {
        const double s = double(fit_.s), m = double(fit_.m), o = std::fmax(double(fit_.o), 0.0);
        const double z = (mu - m) / s;
        const double mass = 0.5 * (tail_a_ - std::erfc(z * inv_sqrt2));
        const double phi_z = std::exp(-0.5 * z * z) * detail::inv_sqrt_two_pi<double>;
        return {2 * (m * mass + s * (phi_a_ - phi_z)) + o * mu * mu, 2 * (phi_z / s + o) * mu};
    }

    // The mu in [0, 1] with C(mu) = target (0 <= target <= C(1)): Newton steps on C, kept
    // inside a bisection bracket (a step leaving it, or a zero slope, bisects instead),
    // until a step moves mu by less than 1e-10 (far below float's resolution of mu; the
    // draws then follow the density to that accuracy) or after 60 steps.
    [[nodiscard]] double invert_cosine_cdf(double target) const noexcept {
        double lo = 0, hi = 1;
        double mu = std::sqrt(target / cdf_one_); // the root for constant E'
        if (!(mu > 0 && mu < 1)) mu = 0.5;
        for (int i = 0; i < 60; ++i) {
            const cdf_at c = cosine_cdf(mu);
            const double residual = c.value - target;
            if (residual > 0) hi = mu;
            else lo = mu;
            double next = c.slope > 0 ? mu - residual / c.slope : 0.5 * (lo + hi);
            if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
            if (std::fabs(next - mu) <= 1e-10) return next;
            mu = next;
        }
        return mu;
    }

    static constexpr double inv_sqrt2 = 0.707106781186547524400844362104849039;

    rgb<T> color_;
    T roughness_;
    T alpha_;
    detail::sheen_albedo_fit<T> fit_;
    double tail_a_;  // erfc(a / sqrt 2), a = -m/s
    double phi_a_;   // phi(a)
    double cdf_one_; // C(1) in double, what sample() inverts against
    T e_avg_;        // C(1) as T
};

} // namespace shade
