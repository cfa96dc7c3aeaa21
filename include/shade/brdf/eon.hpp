#pragma once
// shade::eon: the energy-preserving Oren-Nayar rough diffuse BRDF (EON) of OpenPBR Surface,
// and shade::fujii_oren_nayar, its single-scattering part (FON) on its own:
//
//   eon<T>                          FON + multiple-scattering compensation, exact FON albedo
//   eon<T, eon_albedo::approximate> the same with the paper's polynomial fit of the FON albedo
//   fujii_oren_nayar<T>             FON alone (loses energy as roughness grows)
//
// Sampling (shade::sampled_brdf): the paper's mixture of a clipped linearly transformed
// cosine and the uniform hemisphere (shade/brdf/detail/eon_sampling.hpp).
//
// Not included by shade/shade.hpp: include this header directly.

#include <cmath>
#include <concepts>
#include <optional>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <shade/brdf/brdf.hpp>
#include <shade/brdf/detail/directions.hpp>
#include <shade/brdf/detail/eon_sampling.hpp>
#include <shade/brdf/detail/sampling.hpp>
#include <shade/core/error.hpp>
#include <shade/core/math.hpp>
#include <shade/core/sampling.hpp>
#include <shade/core/surface_point.hpp>
#include <shade/core/types.hpp>

namespace shade {

namespace detail {

/// c1 = 1/2 - 2/(3 pi): the FON coefficient A = 1 / (1 + c1 r) (Fujii, "A tiny improvement
/// of Oren-Nayar reflectance model", mimosa-pudica.net; Portsmouth, Kutz, Hill 2025,
/// constant1_FON), and also G(0)/pi, so that the FON albedo is 1 at grazing.
template <std::floating_point T>
inline constexpr T fon_c1 = T(0.5) - T(2) / (T(3) * pi<T>);

/// c2 = 2/3 - 28/(15 pi): the average FON albedo is A (1 + c2 r) (Portsmouth, Kutz, Hill
/// 2025, constant2_FON).
template <std::floating_point T>
inline constexpr T fon_c2 = T(2) / T(3) - T(28) / (T(15) * pi<T>);

/// The FON coefficient A = 1 / (1 + c1 r); B = r A.
template <std::floating_point T>
[[nodiscard]] constexpr T fon_a(T r) noexcept {
    return T(1) / (T(1) + fon_c1<T> * r);
}

/// The angular factor s/t of the FON BRDF for n·l = n_dot_l > 0, n·v = n_dot_v > 0:
/// s = l·v - (n·l)(n·v) (= sin(theta_l) sin(theta_v) cos(phi_l - phi_v)), divided by
/// t = max(n·l, n·v) when s > 0 and by t = 1 otherwise (Fujii; OpenPBR Surface 1.1, footnote
/// to eq. FON_brdf). t is floored at machine epsilon (detail::cos_floor): s/t grows like
/// 1/t when both directions approach grazing at the same azimuth, and would overflow.
template <std::floating_point T>
[[nodiscard]] inline T fon_s_over_t(const vec3<T>& l, const vec3<T>& v, T n_dot_l, T n_dot_v) noexcept {
    const T s = glm::dot(l, v) - n_dot_l * n_dot_v;
    return s > T(0) ? s / floored_cos(glm::max(n_dot_l, n_dot_v)) : s;
}

/// The FON BRDF for white rho: A (1 + r s/t) / pi (1/sr). Clamped at 0: s >= -1 and r <= 1
/// make it >= 0 exactly, but s rounds below -1 for opposite grazing directions.
template <std::floating_point T>
[[nodiscard]] inline T fon_white(T a, T r, T s_over_t) noexcept {
    return glm::max(a * (T(1) + r * s_over_t), T(0)) * inv_pi<T>;
}

/// G(mu) / pi of the exact FON albedo E(mu) = A (1 + r G(mu) / pi), with sin = sqrt(1 - mu^2):
///   G(mu) = sin (acos(mu) - sin mu) + (2/3) ((sin / mu) (1 - sin^3) - sin)
/// (Portsmouth, Kutz, Hill 2025, listing function E_FON_exact). (sin/mu)(1 - sin^3) is
/// formed as sin mu (1 + sin + sin^2) / (1 + sin) (1 - sin^3 = (1 - sin)(1 + sin + sin^2),
/// 1 - sin = mu^2 / (1 + sin)): finite at mu = 0 and free of the cancellation of 1 - sin^3
/// near grazing. mu is clamped to [0, 1].
template <std::floating_point T>
[[nodiscard]] inline T fon_g_over_pi_exact(T mu) noexcept {
    mu = glm::clamp(mu, T(0), T(1));
    const T sin_theta = safe_sqrt((T(1) - mu) * (T(1) + mu));
    const T g = sin_theta * (std::acos(mu) - sin_theta * mu) +
                (T(2) / T(3)) * (sin_theta * mu * (T(1) + sin_theta + sin_theta * sin_theta) / (T(1) + sin_theta) - sin_theta);
    return g * inv_pi<T>;
}

/// The paper's quartic fit of G(mu)/pi in 1 - mu (Portsmouth, Kutz, Hill 2025, listing
/// function E_FON_approx): 0.0571085289 m + 0.491881867 m^2 - 0.332181442 m^3 +
/// 0.0714429953 m^4 with m = 1 - mu, within 6.1e-4 of the exact G/pi on [0, 1].
template <std::floating_point T>
[[nodiscard]] inline T fon_g_over_pi_approximate(T mu) noexcept {
    const T m = T(1) - glm::clamp(mu, T(0), T(1));
    return m * (T(0.0571085289) + m * (T(0.491881867) + m * (T(-0.332181442) + m * T(0.0714429953))));
}

} // namespace detail

/// The forms of the FON directional albedo E(mu) that shade::eon builds its compensation
/// from, used as its Albedo parameter. Each is a stateless type whose `deficit<T>(mu)`
/// returns (1 - E(mu)) / (r A) = c1 - G(mu)/pi, clamped at 0: since E = A (1 + r G/pi) and
/// 1/A = 1 + c1 r, 1 - E = r A (c1 - G/pi). Written this way the compensation has no
/// 0/0 at r = 0 and no cancellation of 1 - E where E is close to 1.
namespace eon_albedo {

/// The closed form of the FON albedo (default): OpenPBR Surface 1.1 says the albedo "can
/// be determined analytically", and MaterialX's OpenPBR implementation
/// (mx_oren_nayar_fujii_diffuse_dir_albedo) uses this form. With it the compensated
/// lobe's albedo is exactly 1 for white rho at every roughness and view.
struct exact {
    template <std::floating_point T>
    [[nodiscard]] static T deficit(T mu) noexcept {
        return glm::max(detail::fon_c1<T> - detail::fon_g_over_pi_exact(mu), T(0));
    }
};

/// The paper's polynomial fit of G/pi (no acos). The fit exceeds c1 (by up to 4.6e-4) for
/// mu < 0.0014, so E > 1 there; the deficit is then clamped to 0, where the paper's listing
/// clamps 1 - E to 1e-7 (a difference of at most 1.4e-7 rho_ms / pi in f).
struct approximate {
    template <std::floating_point T>
    [[nodiscard]] static T deficit(T mu) noexcept {
        return glm::max(detail::fon_c1<T> - detail::fon_g_over_pi_approximate(mu), T(0));
    }
};

} // namespace eon_albedo

/// X is one of the shade::eon_albedo types (or a user type with the same member).
template <class X, class T>
concept eon_albedo_form = std::floating_point<T> && requires(T mu) {
    { X::template deficit<T>(mu) } -> std::same_as<T>;
};

namespace detail {

/// What shade::eon and shade::fujii_oren_nayar share: the parameters, their validation, and
/// the sampler (Portsmouth, Kutz, Hill 2025, sec. "Importance sampling"; see
/// shade/brdf/detail/eon_sampling.hpp).
template <std::floating_point T>
class fon_base {
public:
    fon_base(const rgb<T>& rho, T roughness)
        : fon_base(unchecked, require_in_range("rho", rho, T(0), T(1)),
                   require_in_range("roughness", roughness, T(0), T(1))) {}

    fon_base(unchecked_t, const rgb<T>& rho, T roughness) noexcept
        : rho_(rho), roughness_(roughness), a_(fon_a(roughness)), r_pow_(std::pow(roughness, T(0.1))) {}

    /// The single-scattering albedo of the facets (per channel, in [0, 1]).
    [[nodiscard]] constexpr const rgb<T>& rho() const noexcept { return rho_; }
    /// The roughness r in [0, 1] (OpenPBR's base_diffuse_roughness; not an angle).
    [[nodiscard]] constexpr T roughness() const noexcept { return roughness_; }
    /// The FON coefficient A = 1 / (1 + (1/2 - 2/(3 pi)) r); B = r A.
    [[nodiscard]] constexpr T a() const noexcept { return a_; }

    /// What pdf() and draw() compute from the view v alone, computed once by prepare() for
    /// a caller that draws and evaluates several directions for one view (a mixture of
    /// lobes): the lobe frame's azimuth, the LTC fit and P_u at v.
    struct prepared_view {
        view_azimuth<T> turn{}; ///< the azimuth of v (the lobe frame)
        eon_ltc<T> m{};         ///< detail::eon_ltc::fit at n·v
        T p_uniform = 0;        ///< P_u at n·v
        bool valid = false;     ///< n·v > 0
    };

    /// The prepared_view of v at `at` (the same `at` must be passed with it below).
    [[nodiscard]] prepared_view prepare(const vec3<T>& v, const surface_point<T>& at) const noexcept {
        if (!(glm::dot(at.n(), v) > T(0))) return {};
        return prepare_local(at.shading.to_local(v));
    }

    /// prepare(v, at) for v given in the shading frame (v_local = at.shading.to_local(v)).
    [[nodiscard]] prepared_view prepare_local(const vec3<T>& v_local) const noexcept {
        prepared_view p;
        if (!(v_local.z > T(0))) return p;
        p.turn = view_azimuth<T>::of(v_local);
        p.m = eon_ltc<T>::fit(v_local.z, roughness_);
        p.p_uniform = eon_uniform_probability(v_local.z, r_pow_);
        p.valid = true;
        return p;
    }

    /// The density (1/sr) with which sample() draws l: P_u / (2 pi) + (1 - P_u) D_cltc(l),
    /// with P_u = detail::eon_uniform_probability and D_cltc = detail::cltc_pdf in the lobe
    /// frame of v; 0 unless n·l > 0 and n·v > 0.
    [[nodiscard]] T pdf(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const noexcept {
        if (!(glm::dot(at.n(), l) > T(0))) return T(0);
        return pdf(l, prepare(v, at), at);
    }

    /// pdf(l, v, at) for the prepared view of v.
    [[nodiscard]] T pdf(const vec3<T>& l, const prepared_view& view, const surface_point<T>& at) const noexcept {
        if (!view.valid || !(glm::dot(at.n(), l) > T(0))) return T(0);
        return pdf_local(at.shading.to_local(l), view);
    }

    /// pdf(l, view, at) for l given in the shading frame (l_local = at.shading.to_local(l)).
    [[nodiscard]] T pdf_local(const vec3<T>& l_local, const prepared_view& view) const noexcept {
        if (!view.valid || !(l_local.z > T(0))) return T(0);
        const vec3<T> w = view.turn.to_lobe(l_local);
        return mixture_pdf(view.p_uniform, cltc_pdf(view.m, w), inv_pi<T> * T(0.5));
    }

    /// Draws l: from the uniform hemisphere when uc < P_u, else from the clipped LTC lobe,
    /// each with u; f_at(l) gives the BRDF value. nullopt when v is not above the surface
    /// or l falls on or below the horizon (by rounding at its rim).
    template <class F>
    [[nodiscard]] std::optional<brdf_sample<T>> sample_with(const vec3<T>& v, T uc, const vec2<T>& u,
                                                            const surface_point<T>& at, F&& f_at) const {
        if (!(glm::dot(at.n(), v) > T(0))) return std::nullopt;
        const vec3<T> v_local = at.shading.to_local(v);
        const view_azimuth<T> turn = view_azimuth<T>::of(v_local);
        const eon_ltc<T> m = eon_ltc<T>::fit(v_local.z, roughness_);
        const T p_uniform = eon_uniform_probability(v_local.z, r_pow_);
        const std::optional<vec3<T>> l = draw_with(turn, m, p_uniform, uc, u, at);
        if (!l) return std::nullopt;
        const T n_dot_l = glm::dot(at.n(), *l);
        const T pdf = mixture_pdf(p_uniform, cltc_pdf(m, turn.to_lobe(at.shading.to_local(*l))), inv_pi<T> * T(0.5));
        return make_brdf_sample(*l, f_at(*l), pdf, n_dot_l);
    }

    /// The direction l that sample_with(v, uc, u, at, f_at) draws, without its f and pdf
    /// (for a mixture that evaluates the whole model at l itself); nullopt exactly when
    /// sample_with's is.
    [[nodiscard]] std::optional<vec3<T>> draw(const vec3<T>& v, T uc, const vec2<T>& u,
                                              const surface_point<T>& at) const noexcept {
        return draw(prepare(v, at), uc, u, at);
    }

    /// draw(v, uc, u, at) for the prepared view of v.
    [[nodiscard]] std::optional<vec3<T>> draw(const prepared_view& view, T uc, const vec2<T>& u,
                                              const surface_point<T>& at) const noexcept {
        if (!view.valid) return std::nullopt;
        return draw_with(view.turn, view.m, view.p_uniform, uc, u, at);
    }

protected:
    // sample_with's direction for the view's lobe frame turn, LTC fit m and uniform
    // probability p_uniform; nullopt on or below the horizon.
    [[nodiscard]] std::optional<vec3<T>> draw_with(const view_azimuth<T>& turn, const eon_ltc<T>& m, T p_uniform, T uc,
                                                   const vec2<T>& u, const surface_point<T>& at) const noexcept {
        vec3<T> w;
        if (uc < p_uniform) {
            w = square_to_uniform_hemisphere(u);
        } else {
            const vec3<T> mw = cltc_sample(m, u);
            const T len = glm::length(mw);
            if (!(len > T(0))) return std::nullopt;
            w = mw / len;
        }
        if (!(w.z > T(0))) return std::nullopt;
        const vec3<T> l = at.shading.to_world(turn.from_lobe(w));
        if (!(glm::dot(at.n(), l) > T(0))) return std::nullopt;
        return l;
    }

    rgb<T> rho_;
    T roughness_;
    T a_;     // A = 1 / (1 + c1 r)
    T r_pow_; // r^0.1, the roughness factor of the uniform lobe's probability
};

} // namespace detail

/// The Fujii form of the qualitative Oren-Nayar model (FON), single scattering only.
///
/// Fujii, "A tiny improvement of Oren-Nayar reflectance model" (mimosa-pudica.net); as
/// written in Portsmouth, Kutz, Hill 2025, "EON: A Practical Energy-Preserving Rough
/// Diffuse BRDF", JCGT 14(1) (listing function f_EON, its f_ss), and in OpenPBR Surface 1.1,
/// eq. FON_brdf:
///
///     f = (rho / pi) (A + B s/t),   A = 1 / (1 + (1/2 - 2/(3 pi)) r),   B = r A
///     s = l·v - (n·l)(n·v),   t = max(n·l, n·v) if s > 0, else 1
///
/// rho is the facet albedo per channel in [0, 1], r the roughness in [0, 1] (r = 0 is
/// Lambert, f = rho/pi). Returns 0 unless n·l > 0 and n·v > 0; t is floored at machine
/// epsilon (detail::fon_s_over_t).
///
/// Reciprocal: yes. Energy: its directional albedo is rho E(mu) with
/// E(mu) = A (1 + r G(mu)/pi) <= 1 (directional_albedo); for white rho it is 1 at grazing
/// and A = 0.777 at normal incidence when r = 1 (the energy that multiple scattering
/// between the facets would return is lost; shade::eon puts it back).
///
/// Sampling (shade::sampled_brdf): the EON sampler (see shade::eon).
template <std::floating_point T>
class fujii_oren_nayar : public detail::fon_base<T> {
public:
    using scalar_type = T;

    /// Throws shade::invalid_parameter naming "rho" unless every channel lies in [0, 1], or
    /// "roughness" unless it lies in [0, 1].
    fujii_oren_nayar(const rgb<T>& rho, T roughness) : detail::fon_base<T>(rho, roughness) {}

    /// Unchecked: the caller guarantees rho in [0, 1] per channel and roughness in [0, 1].
    fujii_oren_nayar(unchecked_t, const rgb<T>& rho, T roughness) noexcept
        : detail::fon_base<T>(unchecked, rho, roughness) {}

    /// BRDF value in 1/sr without the cosine (see the class comment); 0 unless n·l > 0 and
    /// n·v > 0.
    [[nodiscard]] rgb<T> f(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const noexcept {
        detail::assert_unit_directions(l, v, at);
        const T n_dot_l = glm::dot(at.n(), l);
        const T n_dot_v = glm::dot(at.n(), v);
        if (!(n_dot_l > T(0)) || !(n_dot_v > T(0))) return rgb<T>(0);
        return this->rho_ * detail::fon_white(this->a_, this->roughness_, detail::fon_s_over_t(l, v, n_dot_l, n_dot_v));
    }

    /// The directional albedo (cosine-weighted integral of f over l) for n·v = n_dot_v:
    /// rho A (1 + r G(mu)/pi) from the closed form of G (Portsmouth, Kutz, Hill 2025,
    /// E_FON_exact), mu = n_dot_v clamped to [0, 1].
    [[nodiscard]] rgb<T> directional_albedo(T n_dot_v) const noexcept {
        return this->rho_ * (T(1) - this->roughness_ * this->a_ * eon_albedo::exact::deficit(n_dot_v));
    }

    /// Draws l with the EON sampler (see shade::eon::sample).
    [[nodiscard]] std::optional<brdf_sample<T>> sample(const vec3<T>& v, T uc, const vec2<T>& u,
                                                       const surface_point<T>& at) const noexcept {
        return this->sample_with(v, uc, u, at, [&](const vec3<T>& l) { return f(l, v, at); });
    }
};

/// The energy-preserving Oren-Nayar BRDF (EON): the FON lobe (shade::fujii_oren_nayar)
/// plus an analytic multiple-scattering lobe.
///
/// Portsmouth, Kutz, Hill 2025, "EON: A Practical Energy-Preserving Rough Diffuse BRDF",
/// JCGT 14(1), listing functions f_EON and E_EON; OpenPBR Surface 1.1, eqs. EON_brdf and
/// EON_comp:
///
///     f    = f_FON + f_ms
///     f_ms = (rho_ms / pi) (1 - E(n·l)) (1 - E(n·v)) / (1 - E_avg)
///     rho_ms = rho^2 E_avg / (1 - rho (1 - E_avg))
///     E(mu) = A (1 + r G(mu)/pi),   E_avg = A (1 + (2/3 - 28/(15 pi)) r)
///
/// with E the FON albedo for white rho (Albedo chooses its exact closed form, the default,
/// or the paper's fit: shade::eon_albedo) and E_avg its cosine-weighted average over the
/// hemisphere (closed form in both). Computed as f_ms = k_ms d(n·l) d(n·v) with
/// d = (1 - E)/(r A) (eon_albedo::exact::deficit) and k_ms = rho_ms r A / (pi (c1 - c2)),
/// since 1 - E_avg = r A (c1 - c2): exactly 0 at r = 0, where EON is Lambert (f = rho/pi).
/// Returns 0 unless n·l > 0 and n·v > 0.
///
/// Reciprocal: yes. Energy: with the exact albedo the directional albedo is
/// rho E + rho_ms (1 - E) (directional_albedo), exactly 1 at every view for white rho and
/// below 1 otherwise (rho_ms <= rho for rho <= 1).
///
/// Sampling (shade::sampled_brdf), Portsmouth, Kutz, Hill 2025, sec. "Importance
/// sampling": with probability P_u (uc < P_u) the uniform hemisphere, else a clipped
/// linearly transformed cosine whose matrix is a fit in (n·v, r); pdf() is the exact
/// density of that mixture (shade/brdf/detail/eon_sampling.hpp). At r = 0 it is the cosine
/// lobe.
template <std::floating_point T, class Albedo = eon_albedo::exact>
    requires eon_albedo_form<Albedo, T>
class eon : public detail::fon_base<T> {
public:
    using scalar_type = T;
    using albedo_type = Albedo;

    /// Throws shade::invalid_parameter naming "rho" unless every channel lies in [0, 1], or
    /// "roughness" unless it lies in [0, 1].
    eon(const rgb<T>& rho, T roughness) : detail::fon_base<T>(rho, roughness) { init(); }

    /// Unchecked: the caller guarantees rho in [0, 1] per channel and roughness in [0, 1].
    eon(unchecked_t, const rgb<T>& rho, T roughness) noexcept : detail::fon_base<T>(unchecked, rho, roughness) {
        init();
    }

    /// E_avg = A (1 + c2 r): the average FON albedo for white rho.
    [[nodiscard]] constexpr T average_fon_albedo() const noexcept { return e_avg_; }
    /// rho_ms = rho^2 E_avg / (1 - rho (1 - E_avg)), per channel.
    [[nodiscard]] constexpr const rgb<T>& rho_ms() const noexcept { return rho_ms_; }

    /// BRDF value in 1/sr without the cosine: f_FON + f_ms (see the class comment); 0 unless
    /// n·l > 0 and n·v > 0.
    [[nodiscard]] rgb<T> f(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const noexcept {
        detail::assert_unit_directions(l, v, at);
        const T n_dot_l = glm::dot(at.n(), l);
        const T n_dot_v = glm::dot(at.n(), v);
        if (!(n_dot_l > T(0)) || !(n_dot_v > T(0))) return rgb<T>(0);
        const T single = detail::fon_white(this->a_, this->roughness_, detail::fon_s_over_t(l, v, n_dot_l, n_dot_v));
        // k_ms = 0 (roughness 0, or black rho): no multiple-scattering term to add.
        if (!has_multiple_) return this->rho_ * single;
        const T deficits = Albedo::deficit(n_dot_l) * Albedo::deficit(n_dot_v);
        return this->rho_ * single + k_ms_ * deficits;
    }

    /// The directional albedo for n·v = n_dot_v by the paper's closed form (E_EON):
    /// rho E(mu) + rho_ms (1 - E(mu)), E from Albedo, mu = n_dot_v clamped to [0, 1]. With
    /// eon_albedo::exact it is the cosine-weighted integral of f over l; with the fit it
    /// differs from that integral by the fit's error (below 1e-3 for white rho).
    [[nodiscard]] rgb<T> directional_albedo(T n_dot_v) const noexcept {
        const T one_minus_e = this->roughness_ * this->a_ * Albedo::deficit(n_dot_v);
        return this->rho_ * (T(1) - one_minus_e) + rho_ms_ * one_minus_e;
    }

    /// Draws l with the EON sampler (see the class comment) from uc (the lobe choice) and u;
    /// nullopt when v is not above the surface or l falls on the horizon.
    [[nodiscard]] std::optional<brdf_sample<T>> sample(const vec3<T>& v, T uc, const vec2<T>& u,
                                                       const surface_point<T>& at) const noexcept {
        return this->sample_with(v, uc, u, at, [&](const vec3<T>& l) { return f(l, v, at); });
    }

private:
    void init() noexcept {
        const T r = this->roughness_;
        const T a = this->a_;
        e_avg_ = a * (T(1) + detail::fon_c2<T> * r);
        const rgb<T>& rho = this->rho_;
        // 1 - rho (1 - E_avg) >= E_avg >= 0.83 for rho <= 1: no division by zero.
        rho_ms_ = rho * rho * e_avg_ / (rgb<T>(1) - rho * (T(1) - e_avg_));
        k_ms_ = rho_ms_ * (r * a * inv_pi<T> / (detail::fon_c1<T> - detail::fon_c2<T>));
        has_multiple_ = k_ms_ != rgb<T>(0);
    }

    T e_avg_ = T(1);
    rgb<T> rho_ms_{0};
    rgb<T> k_ms_{0};
    bool has_multiple_ = false; // k_ms != 0
};

} // namespace shade
