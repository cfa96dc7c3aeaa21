#pragma once
// shade::layer: a coat over a base, combined by the coat's directional albedo (albedo
// scaling). Not in the umbrella header: include it directly.
//
//   using coat_type = shade::cook_torrance<shade::ggx<float>, shade::dielectric_fresnel<float>,
//                                          shade::smith_height_correlated<float>>;
//   const shade::layer varnished(coat_type(shade::ggx<float>(0.1f), shade::dielectric_fresnel<float>(1.5f)),
//                                shade::lambert<float>({0.8f, 0.1f, 0.1f}));

#include <array>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <optional>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <shade/brdf/brdf.hpp>
#include <shade/brdf/detail/directions.hpp>
#include <shade/bsdf/bsdf.hpp>
#include <shade/bsdf/detail/lobe_pair.hpp>
#include <shade/core/error.hpp>
#include <shade/core/math.hpp>
#include <shade/core/random.hpp>
#include <shade/core/scalar.hpp>
#include <shade/core/surface_point.hpp>
#include <shade/core/types.hpp>

namespace shade {

/// How shade::layer weighs its base by the coat's directional albedo E_c (see layer).
enum class layering {
    reciprocal,     ///< (1 - w E_c(n·l)) (1 - w E_c(n·v)) / (1 - w E_c,avg): symmetric in l and v
    albedo_scaling  ///< 1 - w E_c(n·v): OpenPBR's form; albedo seen from v <= 1 for any base, not reciprocal
};

namespace detail {

/// C reports its own directional albedo: `c.albedo(mu)`, the fraction of the energy
/// arriving at cosine mu in (0, 1] that it reflects, and `c.average_albedo()`, its
/// cosine-weighted average 2 ∫ albedo(mu) mu dmu.
template <class C>
concept has_directional_albedo = requires(const C& c, scalar_of<C> mu) {
    { c.albedo(mu) } -> std::same_as<scalar_of<C>>;
    { c.average_albedo() } -> std::same_as<scalar_of<C>>;
};

} // namespace detail

/// C is a lobe choice of shade::layer: `c.coat_probability(e)` returns the probability in
/// [0, 1] of drawing from the coat for a view where the coat (weighted) reflects the share
/// e = w E_c(n·v) in [0, 1] of the light; 1 only when the base's coefficient is 0 there.
template <class C, class T>
concept layer_choice = std::floating_point<T> && requires(const C& c, T e) {
    { c.coat_probability(e) } -> std::same_as<T>;
};

/// shade::layer's default lobe choice: the coat with probability clamp(e, 0.1, 0.9),
/// e = w E_c(n·v) the coat's share of the energy over a white base, kept within
/// [0.1, 0.9] so that each lobe is drawn often enough for its peaks.
struct clamped_coat_albedo {
    /// clamp(e, 0.1, 0.9).
    template <std::floating_point T>
    [[nodiscard]] constexpr T coat_probability(T e) const noexcept {
        return glm::clamp(e, T(0.1), T(0.9));
    }
};

/// A lobe choice of shade::layer that knows a bound b of the base's albedo (the largest
/// channel of a Lambertian base's rho, for example): the coat with probability
///
///     p_c = e / (e + b (1 - e))   kept within [0.1, 0.9],   1 when b = 0
///
/// e = w E_c(n·v): the coat's share of the reflected energy when the base reflects b of
/// what the coat lets through, so that each lobe is drawn in proportion to (a bound of) the
/// energy it reflects (the one-sample model of Veach 1997, "Robust Monte Carlo Methods for
/// Light Transport Simulation", sec. 9.2.4, with the lobes' albedos as weights), kept within
/// [0.1, 0.9] as clamped_coat_albedo is. b = 0 promises a black base: the coat is then
/// always drawn, and the layer is exactly the coat (times w).
template <std::floating_point T>
class base_albedo_choice {
public:
    /// b, finite and >= 0. Throws shade::invalid_parameter naming "base_albedo" otherwise.
    explicit base_albedo_choice(T base_albedo) : b_(require_non_negative("base_albedo", base_albedo)) {}

    [[nodiscard]] constexpr T base_albedo() const noexcept { return b_; } ///< b

    /// p_c for the coat's share e in [0, 1] (class comment).
    [[nodiscard]] constexpr T coat_probability(T e) const noexcept {
        if (!(b_ > T(0))) return T(1);
        const T p = e / (e + b_ * (T(1) - e));
        return glm::clamp(p, T(0.1), T(0.9));
    }

private:
    T b_;
};

/// A coat over a base: two shade::sampled_bsdf of the same scalar type, combined by the
/// albedo-scaling approximation of layering, with a coat weight (presence) w in [0, 1].
/// An opaque reflector: l and v above the surface.
///
/// OpenPBR's albedo scaling (Andersson, Edmondson, Guertault et al. 2024, "OpenPBR Surface
/// Specification" v1.1, sec. "Layering", eq. non-reciprocal-albedo-scaling, and with the
/// coat weight, eq. coat_layering_formula_with_albedo_scaling; the Autodesk Standard
/// Surface layering, Georgiev et al. 2019) is layering::albedo_scaling:
///
///     f = w f_c(l, v) + (1 - w E_c(n·v)) f_b(l, v)
///
/// whose albedo seen from v, ∫ f(l, v) (n·l) dl = w E_c(n·v) + (1 - w E_c(n·v)) E_b(v) (what
/// a white furnace renders, radiance mode), is at most 1 for every base with E_b <= 1, and
/// 1 over a white base. It is not reciprocal (the base's factor depends on v only), so the
/// energy it sends back from light arriving along v (importance mode, shade/bsdf/bsdf.hpp),
/// w E_c(n·v) + ∫ (1 - w E_c(n·l)) f_b(v, l) (n·l) dl, is not bounded the same way: over a
/// white Lambertian base it is 1 + w (E_c(n·v) - E_c,avg), above 1 at grazing incidence.
/// layering::reciprocal (the default) uses one factor per direction, the product form of
/// Kelemen, Szirmay-Kalos 2001, "A Microfacet Based Coupled Specular-Matte BRDF Model with
/// Importance Sampling", Eurographics short presentation, with the normalisation of Kulla,
/// Conty 2017, "Revisiting Physically Based Shading at Imageworks", SIGGRAPH course:
///
///     f = w f_c(l, v) + (1 - w E_c(n·l)) (1 - w E_c(n·v)) / (1 - w E_c,avg) f_b(l, v)
///
/// symmetric in l and v, so reciprocal when f_c and f_b are, and the same albedo in both
/// transport modes. Over a Lambertian base of albedo rho its albedo is
/// w E_c(n·v) + (1 - w E_c(n·v)) rho (the base factor integrates against the cosine to
/// (1 - w E_c(n·v))(1 - w E_c,avg)): exactly 1 over a white one. Over
/// a base that reflects mostly toward directions where E_c < E_c,avg (a mirror seen
/// head-on under a glossy dielectric coat) it can exceed that, by at most the factor
/// (1 - w min E_c) / (1 - w E_c,avg) on the base's part; use albedo_scaling where that
/// matters. Neither form models the bounces between coat and base or the base's lobe
/// refracted by the coat (OpenPBR, same section).
///
/// E_c(mu), the fraction of the energy arriving at cosine mu that the coat reflects
/// (dimensionless), comes from the coat: its `albedo(mu)` and `average_albedo()` when it
/// has both (detail::has_directional_albedo), otherwise an estimate made at construction:
/// the mean weight of the coat's reflected samples (shade::sample_bsdf, largest channel)
/// over 32 x 32 strata of u, uc stratified in 32^2 strata of its own dealt to them in a
/// fixed random order (Latin hypercube sampling, McKay, Beckman, Conover 1979, "A
/// Comparison of Three Methods for Selecting Values of Input Variables in the Analysis of
/// Output from a Computer Code", Technometrics 21(2)), at each of 32
/// view cosines mu_k = ((k + 1/2) / 32)^2, about 33000 coat samples in all, read by linear
/// interpolation in sqrt(mu) (flat beyond the end nodes), and E_c,avg = Σ E_k mu_k^(3/2) /
/// Σ mu_k^(3/2), the midpoint rule of 2 ∫ E mu dmu in x = sqrt(mu), normalised so a
/// constant E is exact. The estimate assumes an isotropic coat (views at azimuth 0 of the
/// shading frame); values above 1 are clamped to 1. A delta coat (shade::smooth_conductor)
/// is estimated exactly at the nodes.
///
/// Sampling: the coat with probability p_c = choice.coat_probability(w E_c(n·v)) (0 when
/// w = 0), by default clamped_coat_albedo's clamp(w E_c(n·v), 0.1, 0.9), the coat's share
/// of the energy over a white base; base_albedo_choice uses a bound of the base's albedo
/// as well. Otherwise the base. pdf is the mixture density p_c pdf_c + (1 - p_c) pdf_b;
/// delta samples as shade::mix has them (detail::sample_lobe_pair).
///
/// shade::coupled_plastic is this layer: layer<ggx_dielectric_coating<T>, lambert<T>,
/// base_albedo_choice<T>> with w = 1 and layering::reciprocal, its coat reporting its
/// tabulated albedo and its choice knowing max(k_d).
template <sampled_bsdf Coat, sampled_bsdf Base, class Choice = clamped_coat_albedo>
    requires std::same_as<scalar_of<Coat>, scalar_of<Base>> && layer_choice<Choice, scalar_of<Coat>>
class layer {
    using T = scalar_of<Coat>;
    static constexpr std::size_t nodes = 32;  // view cosines of the estimated E_c
    static constexpr std::size_t strata = 32; // strata per axis of u per node

public:
    using scalar_type = T;

    /// coat over base with coat weight w, the base's factor `form` and the lobe choice
    /// `choice`. Throws shade::invalid_parameter naming "coat_weight" unless it lies in
    /// [0, 1]; and whatever the coat's sample throws while E_c is estimated.
    layer(const Coat& coat, const Base& base, T coat_weight = T(1), layering form = layering::reciprocal,
          const Choice& choice = Choice())
        : coat_(coat), base_(base), w_(require_in_range("coat_weight", coat_weight, T(0), T(1))), form_(form),
          choice_(choice) {
        if constexpr (detail::has_directional_albedo<Coat>) {
            average_ = coat_.average_albedo();
        } else {
            estimate_albedo();
        }
        // 1 - w E_c,avg is 0 only for a coat that reflects everything from every view; its
        // base then receives nothing (every 1 - w E_c factor is 0), and 0 replaces the
        // division by 0.
        const T loss = T(1) - w_ * average_;
        inverse_average_loss_ = loss > T(0) ? T(1) / loss : T(0);
    }

    [[nodiscard]] constexpr const Coat& coat() const noexcept { return coat_; } ///< the top lobe
    [[nodiscard]] constexpr const Base& base() const noexcept { return base_; } ///< the bottom lobe
    [[nodiscard]] constexpr T coat_weight() const noexcept { return w_; }       ///< w, in [0, 1]
    [[nodiscard]] constexpr layering form() const noexcept { return form_; }    ///< the base's factor
    [[nodiscard]] constexpr const Choice& choice() const noexcept { return choice_; } ///< the lobe choice

    /// E_c(mu), the coat's directional albedo at view cosine mu (dimensionless, in [0, 1];
    /// see the class comment for where it comes from).
    [[nodiscard]] T coat_albedo(T mu) const {
        if constexpr (detail::has_directional_albedo<Coat>) {
            return coat_.albedo(mu);
        } else {
            const T t = std::sqrt(glm::clamp(mu, T(0), T(1))) * T(nodes) - T(0.5);
            if (!(t > T(0))) return table_[0];
            if (!(t < T(nodes - 1))) return table_[nodes - 1];
            const auto k = static_cast<std::size_t>(t);
            const T s = t - T(k);
            return table_[k] + s * (table_[k + 1] - table_[k]);
        }
    }

    /// E_c,avg = 2 ∫ E_c(mu) mu dmu, the coat's cosine-weighted average albedo.
    [[nodiscard]] constexpr T coat_average_albedo() const noexcept { return average_; }

    /// The base's factor for cosines n_dot_l, n_dot_v > 0 (dimensionless, in radiance
    /// mode): (1 - w E_c(n·l)) (1 - w E_c(n·v)) / (1 - w E_c,avg) or 1 - w E_c(n·v).
    [[nodiscard]] T base_factor(T n_dot_l, T n_dot_v) const {
        const T loss_v = T(1) - w_ * coat_albedo(n_dot_v);
        if (form_ == layering::albedo_scaling) return loss_v;
        const T loss_l = T(1) - w_ * coat_albedo(n_dot_l);
        return loss_l * loss_v * inverse_average_loss_;
    }

    /// BSDF value in 1/sr without the cosine, radiance mode: w f_c + base_factor f_b if
    /// n·l > 0 and n·v > 0, else 0. A coat of weight 0 is not evaluated.
    [[nodiscard]] rgb<T> f(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const {
        const T n_dot_l = glm::dot(at.n(), l);
        const T n_dot_v = glm::dot(at.n(), v);
        if (!(n_dot_l > T(0)) || !(n_dot_v > T(0))) return rgb<T>(0);
        const rgb<T> base = base_factor(n_dot_l, n_dot_v) * base_.f(l, v, at);
        return w_ == T(0) ? base : w_ * coat_.f(l, v, at) + base;
    }

    /// The density (1/sr) with which sample() draws l: p_c pdf_c + (1 - p_c) pdf_b, 0
    /// unless n·l > 0 and n·v > 0. Delta lobes add nothing.
    [[nodiscard]] T pdf(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const {
        const T n_dot_l = glm::dot(at.n(), l);
        const T n_dot_v = glm::dot(at.n(), v);
        if (!(n_dot_l > T(0)) || !(n_dot_v > T(0))) return T(0);
        const T p_c = coat_probability(n_dot_v);
        if (p_c == T(0)) return base_.pdf(l, v, at);
        return p_c * coat_.pdf(l, v, at) + (T(1) - p_c) * base_.pdf(l, v, at);
    }

    /// Draws l for the view v in the given mode: the coat when uc < p_c, else the base
    /// (class comment). nullopt unless v is above the surface, when the chosen lobe draws
    /// nothing, and when the drawn l is not above the surface.
    [[nodiscard]] std::optional<bsdf_sample<T>> sample(const vec3<T>& v, T uc, const vec2<T>& u,
                                                       const surface_point<T>& at,
                                                       transport_mode mode = transport_mode::radiance) const {
        const T n_dot_v = glm::dot(at.n(), v);
        if (!(n_dot_v > T(0))) return std::nullopt;
        const auto coefficient = [&](bool chose_coat, const vec3<T>& l) {
            if (chose_coat) return rgb<T>(w_);
            const T n_dot_l = glm::dot(at.n(), l);
            return rgb<T>(mode == transport_mode::radiance ? base_factor(n_dot_l, n_dot_v)
                                                           : base_factor(n_dot_v, n_dot_l));
        };
        std::optional<bsdf_sample<T>> s = detail::sample_lobe_pair(*this, coat_, base_, coat_probability(n_dot_v), v,
                                                                   uc, u, at, mode, coefficient);
        if (s && !(glm::dot(at.n(), s->l) > T(0))) return std::nullopt;
        return s;
    }

    /// p_c, the probability that sample() draws from the coat for a view of cosine
    /// n_dot_v > 0: choice().coat_probability(w E_c(n·v)), 0 when w = 0.
    [[nodiscard]] T coat_probability(T n_dot_v) const {
        if (w_ == T(0)) return T(0);
        return choice_.coat_probability(w_ * coat_albedo(n_dot_v));
    }

private:
    // Fills table_ and average_ from the coat's sampler (class comment).
    void estimate_albedo() {
        const surface_point<T> at = surface_point<T>::at(vec3<T>(0), vec3<T>(0, 0, 1));
        rng random(1);
        double weighted = 0;
        double weights = 0;
        for (std::size_t k = 0; k < nodes; ++k) {
            const double x = (double(k) + 0.5) / double(nodes);
            const double mu = x * x;
            const vec3<T> v = glm::normalize(at.shading.to_world(vec3<T>(T(std::sqrt(1 - mu * mu)), T(0), T(mu))));
            // uc: the centres of strata * strata strata of [0, 1), dealt to the strata of u in
            // a random order (Fisher-Yates shuffle), so that uc is stratified on its own and
            // independent of u.
            std::array<std::uint32_t, strata * strata> order{};
            for (std::uint32_t i = 0; i < order.size(); ++i) order[i] = i;
            for (std::uint32_t i = std::uint32_t(order.size()) - 1; i > 0; --i) {
                const std::uint32_t j = random.next_u32() % (i + 1);
                const std::uint32_t swapped = order[i];
                order[i] = order[j];
                order[j] = swapped;
            }
            double sum = 0;
            for (std::size_t i = 0; i < strata * strata; ++i) {
                const vec2<T> u(T((double(i % strata) + 0.5) / double(strata)),
                                T((double(i / strata) + 0.5) / double(strata)));
                const T uc = T((double(order[i]) + 0.5) / double(strata * strata));
                const auto s = sample_bsdf(coat_, v, uc, u, at, transport_mode::radiance);
                if (s && is_reflection(s->flags)) sum += double(detail::max_channel(s->weight));
            }
            const double mean = sum / double(strata * strata);
            const double e = mean < 1 ? mean : 1.0;
            table_[k] = T(e);
            weighted += e * x * x * x;
            weights += x * x * x;
        }
        average_ = T(weighted / weights);
    }

    Coat coat_;
    Base base_;
    T w_;
    layering form_;
    [[no_unique_address]] Choice choice_;
    std::array<T, nodes> table_{};   // E_c at mu_k (estimated coats only)
    T average_ = 0;                  // E_c,avg
    T inverse_average_loss_ = 1;     // 1 / (1 - w E_c,avg), or 0 (constructor)
};

} // namespace shade
