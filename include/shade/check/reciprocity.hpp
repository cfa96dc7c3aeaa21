#pragma once
// Helmholtz reciprocity check: a physically based BRDF is symmetric, f(l, v) = f(v, l).

#include <algorithm>
#include <cmath>
#include <concepts>
#include <string>

#include <shade/brdf/brdf.hpp>
#include <shade/check/directions.hpp>
#include <shade/check/positivity.hpp>
#include <shade/check/result.hpp>

namespace shade::check {

/// The default relative tolerance of the reciprocity check for scalar T: a few hundred
/// ulps of rounding in a BRDF evaluation (1e-3 for float, 1e-9 for double).
template <std::floating_point T>
[[nodiscard]] constexpr double default_reciprocity_tolerance() noexcept {
    return sizeof(T) <= 4 ? 1e-3 : 1e-9;
}

/// Checks f(l, v) = f(v, l) on `options.pairs` upper-hemisphere pairs at `at`.
///
/// The measure is the relative difference |f(l,v) - f(v,l)| / max(|f(l,v)|, |f(v,l)|), the
/// largest over the three channels; pairs where both values are below
/// options.absolute_floor count as equal. result::worst is the largest relative difference,
/// compared with options.relative_tolerance (default: default_reciprocity_tolerance<T>()).
/// A non-finite value counts as a violation of measure +inf.
template <brdf B>
result<scalar_of<B>> reciprocity(const B& model, const surface_point<scalar_of<B>>& at,
                                 const pair_options& options = {}) {
    using T = scalar_of<B>;
    result<T> r;
    r.property = "reciprocity";
    r.model = options.model;
    r.at = at;
    r.tolerance = options.relative_tolerance >= 0 ? options.relative_tolerance
                                                  : default_reciprocity_tolerance<T>();
    bool have_worst = false;
    for (const auto& [l, v] : hemisphere_pairs(at, options.pairs, options.seed)) {
        const rgb<T> f_lv = model.f(l, v, at);
        const rgb<T> f_vl = model.f(v, l, at);
        ++r.tried;
        double measure = 0;
        for (int c = 0; c < 3; ++c) {
            const double a = double(f_lv[c]);
            const double b = double(f_vl[c]);
            if (!std::isfinite(a) || !std::isfinite(b)) {
                measure = std::numeric_limits<double>::infinity();
                break;
            }
            const double scale = std::max(std::abs(a), std::abs(b));
            if (scale < options.absolute_floor) continue;
            measure = std::max(measure, std::abs(a - b) / scale);
        }
        if (measure > r.tolerance) ++r.failures;
        if (!have_worst || measure > r.worst) {
            have_worst = true;
            r.worst = measure;
            r.l = l;
            r.v = v;
            r.value = f_lv;
            r.other = f_vl;
        }
    }
    r.passed = r.failures == 0;
    const std::string tried = std::to_string(r.tried) + " direction pairs";
    if (r.passed) {
        r.message = "reciprocity holds for " + r.model + ": f(l, v) = f(v, l) within relative " +
                    detail::number(r.tolerance) + " for all " + tried + " (worst " +
                    detail::number(r.worst) + ").";
    } else {
        r.message = "reciprocity FAILS for " + r.model + ": " + std::to_string(r.failures) +
                    " of " + tried + " differ by more than relative " +
                    detail::number(r.tolerance) + "; worst: f(l, v) = " +
                    shade::detail::to_text(r.value) + " but f(v, l) = " +
                    shade::detail::to_text(r.other) + " (relative difference " +
                    detail::number(r.worst) + ") for " + detail::where(r.l, r.v, at) +
                    ". Look for a factor that depends on l or v alone (e.g. a division by n.l).";
    }
    return r;
}

} // namespace shade::check
