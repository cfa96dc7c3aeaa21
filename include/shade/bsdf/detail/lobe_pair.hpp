#pragma once
// Internal piece of the combinators shade::mix and shade::layer: drawing a direction from a
// BSDF made of two lobes, f = c_a f_a + c_b f_b, by choosing one lobe and letting it draw.

#include <cmath>
#include <concepts>
#include <limits>
#include <optional>

#include <glm/geometric.hpp>

#include <shade/brdf/brdf.hpp>
#include <shade/bsdf/bsdf.hpp>
#include <shade/core/surface_point.hpp>
#include <shade/core/types.hpp>

namespace shade::detail {

/// uc in [0, 1) rescaled to [0, 1) within the part of [0, 1) that chose a lobe: uc / p_a
/// for lobe a (uc < p_a), (uc - p_a) / (1 - p_a) for lobe b. Rounding can bring the ratio
/// to 1, which the lobes' samplers do not accept; it is kept just below.
template <std::floating_point T>
[[nodiscard]] constexpr T remap_lobe_choice(T uc, T p_a, bool chose_a) noexcept {
    constexpr T below_one = T(1) - std::numeric_limits<T>::epsilon() / T(2);
    const T r = chose_a ? uc / p_a : (uc - p_a) / (T(1) - p_a);
    return r < below_one ? r : below_one;
}

/// One draw of the two-lobe model `model` (f = c_a f_a + c_b f_b; model.f and model.pdf
/// are the combination's): lobe a when uc < p_a, else lobe b, which draws l with
/// shade::sample_bsdf. `coefficient(chose_a, l)` returns the factor c on the chosen lobe
/// at l, in the given mode (used for a delta sample only).
///
/// The sample follows pbrt-v4's mixture (Pharr, Jakob, Humphreys 2023, "Physically Based
/// Rendering", 4th ed., sec. 9.1.2 and 9.3 for delta lobes; the "one sample, sum of the
/// densities" rule of Veach 1997, "Robust Monte Carlo Methods for Light Transport
/// Simulation", sec. 9.2.4):
///   * a sample with a density: f the full model.f at l (in the mode), pdf the mixture
///     density p_a pdf_a + (1 - p_a) pdf_b (model.pdf), weight f |n·l| / pdf;
///   * a delta sample of the chosen lobe (its pdf a probability P, its weight t / P for
///     throughput t): throughput c t, probability p P, so f = c s.f, pdf = p s.pdf and
///     weight = c s.weight / p; the other lobe adds nothing at a delta direction.
/// When the chosen lobe is the only one that can be chosen (p = 1), the model is that lobe
/// times c (the caller promises the other lobe's coefficient is 0), and the lobe's sample
/// is returned with f and weight scaled by c, unchanged otherwise.
/// nullopt when the lobe draws nothing, or (a density sample) when the mixture density is
/// not > 0 or not finite.
template <class Model, class A, class B, class Coefficient, std::floating_point T = scalar_of<Model>>
[[nodiscard]] std::optional<bsdf_sample<T>> sample_lobe_pair(const Model& model, const A& a, const B& b, T p_a,
                                                             const vec3<T>& v, T uc, const vec2<T>& u,
                                                             const surface_point<T>& at, transport_mode mode,
                                                             const Coefficient& coefficient) {
    const bool chose_a = uc < p_a;
    const T p = chose_a ? p_a : T(1) - p_a;
    const T uc_lobe = remap_lobe_choice(uc, p_a, chose_a);
    const std::optional<bsdf_sample<T>> s =
        chose_a ? sample_bsdf(a, v, uc_lobe, u, at, mode) : sample_bsdf(b, v, uc_lobe, u, at, mode);
    if (!s) return std::nullopt;
    if (is_specular(s->flags) || p == T(1)) {
        const rgb<T> c = coefficient(chose_a, s->l);
        bsdf_sample<T> out = *s;
        out.f = c * s->f;
        out.pdf = p * s->pdf;
        out.weight = p == T(1) ? c * s->weight : c * s->weight / p;
        return out;
    }
    const std::optional<brdf_sample<T>> m = make_brdf_sample(s->l, bsdf_f(model, s->l, v, at, mode),
                                                             model.pdf(s->l, v, at),
                                                             std::abs(glm::dot(at.n(), s->l)));
    if (!m) return std::nullopt;
    return bsdf_sample<T>{m->l, m->f, m->pdf, m->weight, s->flags, s->eta};
}

} // namespace shade::detail
