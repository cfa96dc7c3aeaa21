#pragma once
// Positivity check: a BRDF value is a density of reflected radiance, so every channel of
// f(l, v) must be finite and >= 0.

#include <cmath>
#include <concepts>
#include <cstdint>
#include <string>

#include <shade/brdf/brdf.hpp>
#include <shade/check/detail/model_ref.hpp>
#include <shade/check/directions.hpp>
#include <shade/check/result.hpp>

namespace shade::check {

/// Settings of the pointwise checks (positivity, reciprocity).
struct pair_options {
    std::size_t pairs = 20000;           ///< direction pairs to evaluate (hard cases first)
    std::uint64_t seed = 1;              ///< seed of the random pairs; same seed, same pairs
    double relative_tolerance = -1;      ///< reciprocity only; < 0 picks the scalar's default
    double absolute_floor = 1e-30;       ///< reciprocity only: pairs where both values are
                                         ///< below this are equal (avoids 0-vs-denormal noise)
    std::string model = "BRDF";          ///< name used in the message
};

namespace detail {

/// The body of positivity (see there), on the type-erased model.
template <std::floating_point T>
result<T> run_positivity(const model_ref<T>& model, const surface_point<T>& at, const pair_options& options) {
    result<T> r;
    r.property = "positivity";
    r.model = options.model;
    r.at = at;
    bool have_worst = false;
    for (const auto& [l, v] : hemisphere_pairs(at, options.pairs, options.seed)) {
        const rgb<T> f = model.f(l, v, at);
        ++r.tried;
        const bool finite = std::isfinite(f.x) && std::isfinite(f.y) && std::isfinite(f.z);
        const double lowest = finite ? double(std::min(f.x, std::min(f.y, f.z))) : 0.0;
        const double badness = finite ? (lowest < 0 ? -lowest : 0.0)
                                      : std::numeric_limits<double>::infinity();
        if (badness > 0) ++r.failures;
        if (!have_worst || badness > r.worst) {
            have_worst = true;
            r.worst = badness;
            r.l = l;
            r.v = v;
            r.value = f;
        }
    }
    r.decide(r.failures == 0 ? verdict::pass : verdict::fail);
    const std::string tried = std::to_string(r.tried) + " direction pairs";
    if (r.passed) {
        r.message = "positivity holds for " + r.model + ": f(l, v) was finite and >= 0 for all " +
                    tried + " at p = " + shade::detail::to_text(at.p) + ".";
    } else {
        r.message = "positivity FAILS for " + r.model + ": " + std::to_string(r.failures) +
                    " of " + tried + " gave a negative or non-finite value; worst f(l, v) = " +
                    shade::detail::to_text(r.value) + " for " + detail::where(r.l, r.v, at) +
                    ". A BRDF must be finite and >= 0: look for a subtraction or division that "
                    "goes wrong in that configuration.";
    }
    return r;
}

} // namespace detail

/// Checks that f(l, v) is finite and >= 0 in every channel for `options.pairs` direction
/// pairs on the upper hemisphere at `at` (see hemisphere_pairs for which pairs).
///
/// result::worst is the most negative channel value found (0 when none is negative), or
/// +inf if a non-finite value was found; the failing pair is reported.
template <brdf B>
result<scalar_of<B>> positivity(const B& model, const surface_point<scalar_of<B>>& at,
                                const pair_options& options = {}) {
    return detail::run_positivity(detail::model_ref<scalar_of<B>>(model), at, options);
}

} // namespace shade::check
