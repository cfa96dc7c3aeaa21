#pragma once
// shade::mix: a weighted sum of two BSDFs, with one lobe choice and the mixture density.
// Not in the umbrella header: include it directly.
//
//   const shade::mix painted(metal, shade::rgb<float>(0.3f), paint, shade::rgb<float>(0.7f));
//   const auto s = shade::sample_bsdf(painted, v, uc, u, at, shade::transport_mode::radiance);

#include <concepts>
#include <optional>

#include <shade/brdf/brdf.hpp>
#include <shade/brdf/detail/directions.hpp>
#include <shade/bsdf/bsdf.hpp>
#include <shade/bsdf/detail/lobe_pair.hpp>
#include <shade/core/error.hpp>
#include <shade/core/scalar.hpp>
#include <shade/core/surface_point.hpp>
#include <shade/core/types.hpp>

namespace shade {

/// The mixture of two BSDFs A and B (any shade::sampled_bsdf of the same scalar type, BRDFs
/// included; a mix is one too, so mixes nest) with constant per-channel weights:
///
///     f(l, v) = w_a f_a(l, v) + w_b f_b(l, v)        (1/sr, either side, per channel)
///
/// the linear blend of OpenPBR's mix operation (Andersson, Edmondson, Guertault et al. 2024,
/// "OpenPBR Surface Specification" v1.1, sec. "Mixing": f_mix = (1 - w_1) f_0 + w_1 f_1,
/// here with two free weights). Reciprocal when A and B are; its albedo is
/// w_a E_a + w_b E_b, at most 1 when w_a + w_b <= 1 and both conserve energy (weights above
/// 1 are accepted: a mix is also a way to scale a lobe).
///
/// Sampling: lobe a with the constant probability p_a = max(w_a) / (max(w_a) + max(w_b))
/// (max over the channels; p_a = 1 when both weights are 0), lobe b otherwise, uc rescaled
/// to choose within the lobe; pdf is the mixture density p_a pdf_a + (1 - p_a) pdf_b, the
/// same in both transport modes, so multiple importance sampling sees the whole model. A
/// delta sample of a lobe keeps its direction and flags with pdf the lobe's probability
/// times p and weight w times its throughput over that (pbrt-v4's convention,
/// shade/bsdf/bsdf.hpp); see detail::sample_lobe_pair. The weights choose the lobe, not the
/// lobes' albedos: a lobe that reflects little but has a large weight is drawn often.
template <sampled_bsdf A, sampled_bsdf B>
    requires std::same_as<scalar_of<A>, scalar_of<B>>
class mix {
    using T = scalar_of<A>;

public:
    using scalar_type = T;

    /// w_a a + w_b b. Throws shade::invalid_parameter naming "w_a" or "w_b" unless every
    /// channel is finite and >= 0.
    mix(const A& a, const rgb<T>& w_a, const B& b, const rgb<T>& w_b)
        : a_(a), b_(b), w_a_(require_non_negative("w_a", w_a)), w_b_(require_non_negative("w_b", w_b)) {
        const T m_a = detail::max_channel(w_a_);
        const T m_b = detail::max_channel(w_b_);
        p_a_ = m_a + m_b > T(0) ? m_a / (m_a + m_b) : T(1);
    }

    [[nodiscard]] constexpr const A& a() const noexcept { return a_; }          ///< the first lobe
    [[nodiscard]] constexpr const B& b() const noexcept { return b_; }          ///< the second lobe
    [[nodiscard]] constexpr const rgb<T>& w_a() const noexcept { return w_a_; } ///< weight of a
    [[nodiscard]] constexpr const rgb<T>& w_b() const noexcept { return w_b_; } ///< weight of b
    /// p_a, the probability that sample() draws from a (dimensionless, in [0, 1]).
    [[nodiscard]] constexpr T probability_a() const noexcept { return p_a_; }

    /// BSDF value in 1/sr without the cosine, radiance mode: w_a f_a + w_b f_b (a lobe of
    /// weight 0 is not evaluated).
    [[nodiscard]] rgb<T> f(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const {
        if (p_a_ == T(1)) return w_a_ * a_.f(l, v, at);
        if (p_a_ == T(0)) return w_b_ * b_.f(l, v, at);
        return w_a_ * a_.f(l, v, at) + w_b_ * b_.f(l, v, at);
    }

    /// The density (1/sr) with which sample() draws l: p_a pdf_a + (1 - p_a) pdf_b (a lobe
    /// never chosen is not evaluated). Delta lobes add nothing.
    [[nodiscard]] T pdf(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const {
        if (p_a_ == T(1)) return a_.pdf(l, v, at);
        if (p_a_ == T(0)) return b_.pdf(l, v, at);
        return p_a_ * a_.pdf(l, v, at) + (T(1) - p_a_) * b_.pdf(l, v, at);
    }

    /// Draws l for the view v (either side) in the given mode: lobe a when uc < p_a, else
    /// b (class comment). nullopt when the chosen lobe draws nothing.
    [[nodiscard]] std::optional<bsdf_sample<T>> sample(const vec3<T>& v, T uc, const vec2<T>& u,
                                                       const surface_point<T>& at,
                                                       transport_mode mode = transport_mode::radiance) const {
        return detail::sample_lobe_pair(*this, a_, b_, p_a_, v, uc, u, at, mode,
                                        [this](bool chose_a, const vec3<T>&) { return chose_a ? w_a_ : w_b_; });
    }

private:
    A a_;
    B b_;
    rgb<T> w_a_;
    rgb<T> w_b_;
    T p_a_ = 1;
};

} // namespace shade
