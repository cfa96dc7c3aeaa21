#pragma once
// shade::f82_tint: the "F82-tint" Fresnel term of metals, Schlick's curve with a dip toward
// grazing set by the colour at cos = 1/7 (about 82 degrees). It is the metal Fresnel of
// OpenPBR Surface and of the Adobe Standard Material; any microfacet model that takes a
// Fresnel term (shade::cook_torrance, with or without the Kulla-Conty compensation) takes
// it:
//
//   cook_torrance<ggx<T>, f82_tint<T>, smith_height_correlated<T>, cook_torrance_form::walter,
//                 kulla_conty>
//
// Not part of shade/shade.hpp: include this header where it is used.

#include <concepts>

#include <glm/common.hpp>

#include <shade/brdf/brdf.hpp>
#include <shade/brdf/fresnel.hpp>
#include <shade/core/error.hpp>
#include <shade/core/types.hpp>

namespace shade {

/// The cosine at which f82_tint's edge colour is prescribed, mu_bar = 1/7 (Kutz, Hasan,
/// Edmondson 2021): it is where mu (1 - mu)^6 peaks, so the correction term below is
/// largest there.
template <std::floating_point T>
inline constexpr T f82_mu_bar = T(1) / T(7);

/// The F82-tint Fresnel reflectance, per channel.
///
/// Hoffman 2019, "Fresnel Equations Considered Harmful", Eurographics Workshop on Material
/// Appearance Modeling (Schlick's curve corrected by a term in mu (1 - mu)^6 fitted to the
/// reflectance near 82 degrees); Kutz, Hasan, Edmondson 2021, "Novel aspects of the Adobe
/// Standard Material", Adobe white paper (the edge colour as a tint of Schlick's curve);
/// in the notation of the OpenPBR Surface 1.1 specification (Andersson, Kutz, Portsmouth
/// et al., Academy Software Foundation, section "Metal"):
///
///     F_Schlick(mu) = F_0 + (1 - F_0) (1 - mu)^5
///     b             = (F_Schlick(mu_bar) - t F_Schlick(mu_bar)) / (mu_bar (1 - mu_bar)^6)
///     F_82(mu)      = F_Schlick(mu) - b mu (1 - mu)^6
///     F_metal(mu)   = w F_82(mu)
///
/// with mu_bar = 1/7, F_0 the reflectance at normal incidence (OpenPBR: base_weight *
/// base_color), t the tint of the edge (OpenPBR: specular_color; F_82(mu_bar) = t
/// F_Schlick(mu_bar)) and w an overall weight (OpenPBR: specular_weight). t = 1 gives
/// Schlick's curve; F(1) = w F_0 and F(0) = w. Returns the reflectance (dimensionless) per
/// channel, clamped to [0, w]: for a small F_0 with a small t the correction can exceed
/// Schlick's curve between mu_bar and 1 (F_0 = 0, t = 0 gives b = 49/6 and F_82(1/2) = 1/32 -
/// 49/768 = -25/768); such inputs have no physical metal behind them, and the clamp keeps the term a
/// reflectance. Two-sided as F_schlick: F(-c) = F(c), |cos_theta| clamped to 1.
template <std::floating_point T>
[[nodiscard]] constexpr rgb<T> F_f82_tint(const rgb<T>& f0, const rgb<T>& tint, T weight, T cos_theta) noexcept {
    constexpr T mu_bar = f82_mu_bar<T>;
    // mu_bar (1 - mu_bar)^6 = (1/7) (6/7)^6.
    constexpr T m_bar = T(1) - mu_bar;
    constexpr T m_bar3 = m_bar * m_bar * m_bar;
    constexpr T peak = mu_bar * m_bar3 * m_bar3;
    const rgb<T> b = F_schlick(f0, mu_bar) * (rgb<T>(1) - tint) / peak;
    const T c = glm::clamp(cos_theta < T(0) ? -cos_theta : cos_theta, T(0), T(1));
    const T m = T(1) - c;
    const T m3 = m * m * m;
    const rgb<T> f82 = F_schlick(f0, c) - b * (c * m3 * m3);
    return weight * glm::clamp(f82, rgb<T>(0), rgb<T>(1));
}

/// Fresnel term type: the F82-tint reflectance of a metal (see F_f82_tint), for
/// shade::cook_torrance and the Kulla-Conty compensation (whose F_avg it gets by
/// quadrature; for F_82 >= 0 everywhere that is, exactly, w (F_0 + (1 - F_0) / 21 - b / 126),
/// since 2 integral mu (1 - mu)^5 dmu = 1/21 and 2 integral mu^2 (1 - mu)^6 dmu = 2 B(3, 7)
/// = 1/126).
template <std::floating_point T>
class f82_tint {
public:
    using scalar_type = T;

    /// f0: reflectance at normal incidence; tint: the edge colour as a fraction of
    /// Schlick's curve at mu_bar; weight: overall factor. Throws shade::invalid_parameter
    /// naming "f0" or "tint" unless every channel is in [0, 1], or "weight" unless it is
    /// in [0, 1].
    f82_tint(const rgb<T>& f0, const rgb<T>& tint, T weight = T(1))
        : f0_(require_in_range("f0", f0, T(0), T(1))), tint_(require_in_range("tint", tint, T(0), T(1))),
          weight_(require_in_range("weight", weight, T(0), T(1))) {}

    /// Unchecked: the caller guarantees f0, tint and weight in [0, 1].
    constexpr f82_tint(unchecked_t, const rgb<T>& f0, const rgb<T>& tint, T weight = T(1)) noexcept
        : f0_(f0), tint_(tint), weight_(weight) {}

    [[nodiscard]] constexpr const rgb<T>& f0() const noexcept { return f0_; }     ///< reflectance at normal incidence
    [[nodiscard]] constexpr const rgb<T>& tint() const noexcept { return tint_; } ///< edge tint at mu_bar
    [[nodiscard]] constexpr T weight() const noexcept { return weight_; }        ///< overall factor

    /// F(cos_theta) per channel, dimensionless, in [0, weight].
    [[nodiscard]] constexpr rgb<T> F(T cos_theta) const noexcept {
        return F_f82_tint(f0_, tint_, weight_, cos_theta);
    }

private:
    rgb<T> f0_;
    rgb<T> tint_;
    T weight_;
};

} // namespace shade
