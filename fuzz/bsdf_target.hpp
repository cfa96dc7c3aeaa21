#pragma once
// What the BSDF fuzz targets check (shade/bsdf/bsdf.hpp's contract), in the situations of
// brdf_target.hpp (unit l and v on either side of the surface, or raw vectors).
// For a model built by its validating constructor (parameters it rejects must throw exactly
// shade::invalid_parameter), in situations 0-6:
//   * f(l, v, at) is finite and >= 0 in every channel; pdf(l, v, at) finite and >= 0;
//   * sample(v, uc, u, at, mode) in both transport modes: a returned sample has a finite
//     unit l; exactly one of the flags reflection and transmission; l on v's side for a
//     reflection (n.l n.v > 0) and on the other for a transmission (< 0), unless either
//     cosine is within 8 epsilon of 0 (the model decides in its local frame); eta finite,
//     > 0, and exactly 1 for a reflection; for a delta sample (flags specular) a pdf that
//     is a probability in (0, 1], f finite and >= 0, and a finite weight >= 0 (+inf allowed
//     where throughput / pdf exceeds the largest T); for any other sample a finite
//     pdf > 0, f finite and >= 0, and weight = f |n.l| / pdf (relative 1e-4 per channel,
//     plus f / pdf times 32 epsilon for the rounding of a grazing n.l; +inf allowed where
//     that exact value exceeds the largest T).
// In situation 7 everything is evaluated (ASan/UBSan watch it) and nothing is promised.

#include <algorithm>
#include <cmath>
#include <concepts>
#include <limits>
#include <optional>

#include <glm/geometric.hpp>

#include <shade/bsdf/bsdf.hpp>

#include "brdf_target.hpp"
#include "expect.hpp"

namespace shade::fuzz {

/// Samples b in situation s in one transport mode and checks the sample (see the top).
template <sampled_bsdf B>
void check_bsdf_sample(const B& b, const brdf_situation<scalar_of<B>>& s, transport_mode mode) {
    using T = scalar_of<B>;
    const std::optional<bsdf_sample<T>> x = sample_bsdf(b, s.v, s.uc, s.u, s.at, mode);
    if (!s.unit || !x) return;
    const T n_dot_l = glm::dot(s.at.n(), x->l);
    const T n_dot_v = glm::dot(s.at.n(), s.v);
    const bool reflection = is_reflection(x->flags);
    const bool transmission = is_transmission(x->flags);
    const bool l_ok = is_finite(x->l) && is_unit_length(x->l);
    const bool flags_ok = reflection != transmission;
    // The model decides the side in its local frame; the world-space cosines here may differ
    // by a few ulps of 1, so a direction within 8 epsilon of the surface counts as either.
    const T near = 8 * std::numeric_limits<T>::epsilon();
    const bool on_surface = std::abs(n_dot_l) <= near || std::abs(n_dot_v) <= near;
    const bool side_ok = on_surface || (reflection ? n_dot_l * n_dot_v > T(0) : n_dot_l * n_dot_v < T(0));
    const bool eta_ok = std::isfinite(x->eta) && x->eta > T(0) && (!reflection || x->eta == T(1));
    bool pdf_ok = false;
    bool values_ok = false;
    if (is_specular(x->flags)) {
        pdf_ok = std::isfinite(x->pdf) && x->pdf > T(0) && x->pdf <= T(1);
        // The weight is throughput / pdf, and f = throughput / max(|n.l|, epsilon): +inf is
        // allowed where that exact quotient exceeds the largest T (a lobe chosen with a
        // subnormal probability whose throughput is not small).
        values_ok = finite_non_negative(x->f) && pdf_ok;
        for (int i = 0; i < 3 && values_ok; ++i) {
            const long double throughput =
                static_cast<long double>(x->f[i]) *
                std::max(static_cast<long double>(std::abs(n_dot_l)),
                         static_cast<long double>(std::numeric_limits<T>::epsilon()));
            values_ok = throughput / x->pdf > static_cast<long double>(std::numeric_limits<T>::max())
                            ? x->weight[i] >= T(0)
                            : std::isfinite(x->weight[i]) && x->weight[i] >= T(0);
        }
    } else {
        pdf_ok = std::isfinite(x->pdf) && x->pdf > T(0);
        values_ok = finite_non_negative(x->f) && pdf_ok;
        bool overflows = false;
        for (int i = 0; i < 3 && values_ok; ++i)
            values_ok = weight_agrees(x->f[i], x->pdf, std::abs(n_dot_l), x->weight[i], overflows);
    }
    if (!l_ok || !flags_ok || !side_ok || !eta_ok || !pdf_ok || !values_ok) {
        show(s);
        show("mode (0 radiance, 1 importance)", T(mode == transport_mode::importance ? 1 : 0));
        show("uc", s.uc);
        show("u.x", s.u.x);
        show("u.y", s.u.y);
        show("flags", T(static_cast<unsigned>(x->flags)));
        show("sampled l", x->l);
        show("sampled f", x->f);
        show("sampled pdf", x->pdf);
        show("sampled weight", x->weight);
        show("sampled eta", x->eta);
    }
    expect(l_ok, "BSDF sample: l is not a finite unit vector");
    expect(flags_ok, "BSDF sample: not exactly one of reflection and transmission");
    expect(side_ok, "BSDF sample: l on the wrong side of the surface for its flags");
    expect(eta_ok, "BSDF sample: eta not finite and > 0, or not 1 for a reflection");
    expect(pdf_ok, "BSDF sample: pdf not finite and > 0 (a probability in (0, 1] for a delta lobe)");
    expect(values_ok, "BSDF sample: f or weight NaN, infinite or negative, or weight not f |n.l| / pdf");
}

/// Evaluates and samples b in situation s and checks the BSDF contract (see the top).
template <sampled_bsdf B>
void check_bsdf(const B& b, const brdf_situation<scalar_of<B>>& s) {
    using T = scalar_of<B>;
    const rgb<T> f = b.f(s.l, s.v, s.at);
    const T pdf = b.pdf(s.l, s.v, s.at);
    check_bsdf_sample(b, s, transport_mode::radiance);
    check_bsdf_sample(b, s, transport_mode::importance);
    if (!s.unit) return;
    const bool f_ok = finite_non_negative(f);
    const bool pdf_ok = std::isfinite(pdf) && pdf >= T(0);
    if (!f_ok || !pdf_ok) {
        show(s);
        show("f", f);
        show("pdf", pdf);
    }
    expect(f_ok, "BSDF value is NaN, infinite or negative for unit directions");
    expect(pdf_ok, "BSDF pdf is NaN, infinite or negative for unit directions");
}

} // namespace shade::fuzz
