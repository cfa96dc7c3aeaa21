#pragma once
// Multiple importance sampling weights (Veach and Guibas 1995, "Optimally Combining
// Sampling Techniques for Monte Carlo Rendering", SIGGRAPH; Veach 1997, "Robust Monte Carlo
// Methods for Light Transport Simulation", PhD thesis, Stanford, ch. 9).
//
// A sample x drawn by technique f (n_f samples, density p_f) when technique g (n_g samples,
// density p_g) could also have drawn it counts with weight w_f(x); the weights of all
// techniques sum to 1 wherever any density is positive, so the combined estimator
//     sum over techniques t, samples j of  w_t(x_tj) f(x_tj) / (n_t p_t(x_tj))
// stays unbiased. Densities must be measured in the same measure (both in 1/sr, say) and
// include every discrete choice made on the way (e.g. the probability of picking the
// light). A density of +infinity stands for a delta (specular) technique, which no other
// technique can draw: its weight is 1 and the others' 0.
//
// Every weight here is in [0, 1], never NaN, for densities in [0, +inf] and sample counts
// >= 1, and is computed from the ratio of the densities, so that squaring a density far
// above 1e154 (double) or 1e19 (float) cannot overflow.

#include <cmath>
#include <concepts>

namespace shade {

/// The balance heuristic (Veach 1997, eq. 9.10): w_f = n_f p_f / (n_f p_f + n_g p_g). The
/// weight of a sample of technique f (n_f samples, density pdf_f) against technique g.
/// 0 when pdf_f is 0; 1 when pdf_f is +infinity and pdf_g finite. Preconditions: pdfs in
/// [0, +inf], counts >= 1.
template <std::floating_point T>
[[nodiscard]] inline T balance_heuristic(T n_f, T pdf_f, T n_g, T pdf_g) noexcept {
    const T a = n_f * pdf_f;
    const T b = n_g * pdf_g;
    if (!(a > 0)) return T(0);
    if (std::isinf(a)) return std::isinf(b) ? T(0.5) : T(1);
    // a / (a + b) as 1 / (1 + b/a): no overflow of a + b.
    return T(1) / (T(1) + b / a);
}

/// The power heuristic with exponent beta = 2 (Veach 1997, eq. 9.13):
/// w_f = (n_f p_f)^2 / ((n_f p_f)^2 + (n_g p_g)^2). Close to the best of the weights Veach
/// compares when one technique is much better than the other (low-variance regions keep
/// their weight near 1). 0 when pdf_f is 0; 1 when pdf_f is +infinity and pdf_g finite.
/// Preconditions: pdfs in [0, +inf], counts >= 1.
template <std::floating_point T>
[[nodiscard]] inline T power_heuristic(T n_f, T pdf_f, T n_g, T pdf_g) noexcept {
    const T a = n_f * pdf_f;
    const T b = n_g * pdf_g;
    if (!(a > 0)) return T(0);
    if (std::isinf(a)) return std::isinf(b) ? T(0.5) : T(1);
    // a^2 / (a^2 + b^2) as 1 / (1 + (b/a)^2): the ratio is squared, never a density.
    const T r = b / a;
    return T(1) / (T(1) + r * r);
}

/// The power heuristic with one sample of each technique: power_heuristic(1, pdf_f, 1, pdf_g),
/// the common case of a path tracer's next-event estimation against BSDF sampling.
template <std::floating_point T>
[[nodiscard]] inline T power_heuristic(T pdf_f, T pdf_g) noexcept {
    return power_heuristic(T(1), pdf_f, T(1), pdf_g);
}

/// The balance heuristic with one sample of each technique.
template <std::floating_point T>
[[nodiscard]] inline T balance_heuristic(T pdf_f, T pdf_g) noexcept {
    return balance_heuristic(T(1), pdf_f, T(1), pdf_g);
}

} // namespace shade
