#pragma once
// Helmholtz reciprocity check: a physically based BRDF is symmetric, f(l, v) = f(v, l).

#include <algorithm>
#include <cmath>
#include <concepts>
#include <limits>
#include <string>
#include <vector>

#include <shade/brdf/brdf.hpp>
#include <shade/check/detail/model_ref.hpp>
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

namespace detail {

/// Two directions, the model's values both ways and the factor each value is multiplied by
/// before they are compared (1 for BRDFs; eta_l^2 and eta_v^2 for the adjoint form).
template <std::floating_point T>
struct reciprocity_pair {
    vec3<T> l, v;
    rgb<T> f_lv, f_vl;
    double scale_lv = 1, scale_vl = 1;
};

/// Judges the pairs into r (tried, failures, worst with its directions and values, and the
/// verdict; r.tolerance set by the caller). Per pair the measure is the largest relative
/// difference over the channels of a = f_lv scale_lv and b = f_vl scale_vl,
/// |a - b| / max(|a|, |b|, s), infinite when either is not finite; channels where both are
/// below absolute_floor are skipped, and s is 1e-3 times the 90th percentile of the pairs'
/// largest value, so that values near zero beside large ones are compared absolutely.
template <std::floating_point T>
void judge_reciprocity_pairs(result<T>& r, const std::vector<reciprocity_pair<T>>& values, double absolute_floor) {
    std::vector<double> sizes;
    sizes.reserve(values.size());
    for (const auto& e : values) {
        double size = 0;
        for (int c = 0; c < 3; ++c)
            for (const double x : {double(e.f_lv[c]) * e.scale_lv, double(e.f_vl[c]) * e.scale_vl})
                if (std::isfinite(x)) size = std::max(size, std::abs(x));
        sizes.push_back(size);
    }
    double typical = 0;
    if (!sizes.empty()) {
        const auto k = sizes.begin() + std::ptrdiff_t(sizes.size() * 9 / 10);
        std::nth_element(sizes.begin(), k, sizes.end());
        typical = *k;
    }
    const double scale = 1e-3 * typical;
    bool have_worst = false;
    for (const auto& e : values) {
        ++r.tried;
        double measure = 0;
        for (int c = 0; c < 3; ++c) {
            const double a = double(e.f_lv[c]) * e.scale_lv;
            const double b = double(e.f_vl[c]) * e.scale_vl;
            if (!std::isfinite(a) || !std::isfinite(b)) {
                measure = std::numeric_limits<double>::infinity();
                break;
            }
            const double size = std::max(std::abs(a), std::abs(b));
            if (size < absolute_floor) continue;
            measure = std::max(measure, std::abs(a - b) / std::max(size, scale));
        }
        if (measure > r.tolerance) ++r.failures;
        if (!have_worst || measure > r.worst) {
            have_worst = true;
            r.worst = measure;
            r.l = e.l;
            r.v = e.v;
            r.value = e.f_lv;
            r.other = e.f_vl;
        }
    }
    r.decide(r.failures == 0 ? verdict::pass : verdict::fail);
}

/// The body of reciprocity (see there), on the type-erased model.
template <std::floating_point T>
result<T> run_reciprocity(const model_ref<T>& model, const surface_point<T>& at, const pair_options& options) {
    result<T> r;
    r.property = "reciprocity";
    r.model = options.model;
    r.at = at;
    r.tolerance = options.relative_tolerance >= 0 ? options.relative_tolerance
                                                  : default_reciprocity_tolerance<T>();
    std::vector<reciprocity_pair<T>> values;
    for (const auto& [l, v] : hemisphere_pairs(at, options.pairs, options.seed))
        values.push_back({l, v, model.f(l, v, at), model.f(v, l, at)});
    judge_reciprocity_pairs(r, values, options.absolute_floor);
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

} // namespace detail

/// Checks f(l, v) = f(v, l) on `options.pairs` upper-hemisphere pairs at `at`.
///
/// The measure is the relative difference |f(l,v) - f(v,l)| / max(|f(l,v)|, |f(v,l)|, s),
/// the largest over the three channels, where s = 1e-3 times the 90th percentile of |f|
/// over all pairs (a typical value of the model, unaffected by a few singular peaks):
/// values a thousand times below it are compared on that scale.
/// Without that scale, rounding alone fails a reciprocal float model where a lobe is
/// evaluated far in its tail (e.g. r.v ~ 1e-5 computed with an absolute error of one ulp
/// of 1, a relative error of ~1e-3), while real violations (a factor depending on l or v
/// alone) are large where the BRDF is large. Pairs where both values are below
/// options.absolute_floor count as equal. result::worst is the largest measure, compared
/// with options.relative_tolerance (default: default_reciprocity_tolerance<T>()). A
/// non-finite value counts as a violation of measure +inf.
template <brdf B>
result<scalar_of<B>> reciprocity(const B& model, const surface_point<scalar_of<B>>& at,
                                 const pair_options& options = {}) {
    return detail::run_reciprocity(detail::model_ref<scalar_of<B>>(model), at, options);
}

} // namespace shade::check
