#pragma once
// The reciprocity of a BSDF in radiance mode over the whole sphere (Veach 1997, "Robust
// Monte Carlo Methods for Light Transport Simulation", PhD thesis, Stanford, eq. 5.14):
// f(l, v) / eta_v^2 = f(v, l) / eta_l^2, eta_l and eta_v the indices of refraction on the
// sides of l and v. For a BRDF, or a BSDF with the same medium on both sides (a thin
// pane), it is Helmholtz reciprocity f(l, v) = f(v, l). Not in the umbrella header:
// include it directly.
//
//   auto r = shade::check::adjoint_reciprocity(glass, at, glass.eta(), {.model = "my glass"});
//   if (!r) std::cerr << r << '\n';

#include <cmath>
#include <concepts>
#include <cstddef>
#include <string>
#include <vector>

#include <shade/bsdf/bsdf.hpp>
#include <shade/check/directions.hpp>
#include <shade/check/positivity.hpp>
#include <shade/check/reciprocity.hpp>
#include <shade/check/result.hpp>
#include <shade/core/error.hpp>

namespace shade::check {

/// The default relative tolerance of adjoint_reciprocity for scalar T: 1e-3 for float (as
/// reciprocity's) and 1e-7 for double. The pairs include grazing directions (cos = 1e-4 in
/// float, 1e-7 in double, see hemisphere_pairs), whose cosines in a tilted frame carry a
/// relative rounding error of about epsilon / cos (6e-4 in float, 1e-9 in double); a
/// refraction's microfacet normal is computed from (l, v) and from (v, l) by different
/// roundings, and D and G amplify that error near grazing, to a few times 1e-9 in double.
/// The violations the check is for are far larger: a missing, inverted or misplaced eta^2
/// is a relative error of at least 1 - 1/eta^2, 0.1 already for eta = 1.05.
template <std::floating_point T>
[[nodiscard]] constexpr double default_adjoint_reciprocity_tolerance() noexcept {
    return sizeof(T) <= 4 ? 1e-3 : 1e-7;
}

/// Checks Veach's eq. 5.14 for `model` in radiance mode, f(l, v) eta_l^2 = f(v, l) eta_v^2
/// (the same equation multiplied by eta_l^2 eta_v^2), on options.pairs pairs of
/// sphere_pairs at `at`, with eta 1 on the side at.n() points to and eta_inside on the
/// other: the model's relative index for an interface (shade::smooth_dielectric,
/// shade::rough_dielectric: their eta()), 1 for a BRDF and for a surface with the same
/// medium on both sides (shade::thin_dielectric). shade guarantees it for every model
/// (docs/conventions.md, "Transmission"); delta lobes add nothing to f, so they pass
/// trivially.
///
/// The measure is that of reciprocity, on the two sides of the equation: the relative
/// difference |a - b| / max(|a|, |b|, s), a = f(l, v) eta_l^2, b = f(v, l) eta_v^2, the
/// largest over the channels, s = 1e-3 times the 90th percentile of max(|a|, |b|) over
/// all pairs; pairs where both are below options.absolute_floor count as equal, and a
/// non-finite value as a violation of measure +inf; the measure is compared with
/// options.relative_tolerance (default: default_adjoint_reciprocity_tolerance<T>()).
/// result::value is f(l, v) and
/// result::other f(v, l) at the worst pair. Throws shade::invalid_parameter naming
/// "eta_inside" unless it lies in [1e-4, 1e4].
template <bsdf B>
result<scalar_of<B>> adjoint_reciprocity(const B& model, const surface_point<scalar_of<B>>& at, double eta_inside,
                                         const pair_options& options = {}) {
    using T = scalar_of<B>;
    require_in_range("eta_inside", eta_inside, 1e-4, 1e4);
    result<T> r;
    r.property = "adjoint reciprocity";
    r.model = options.model;
    r.at = at;
    r.tolerance =
        options.relative_tolerance >= 0 ? options.relative_tolerance : default_adjoint_reciprocity_tolerance<T>();
    const vec3<T> n = at.n();
    const auto eta2 = [&](const vec3<T>& w) { return glm::dot(w, n) < T(0) ? eta_inside * eta_inside : 1.0; };
    // Compared: f(l, v) eta_l^2 against f(v, l) eta_v^2.
    std::vector<detail::reciprocity_pair<T>> values;
    for (const auto& [l, v] : sphere_pairs(at, options.pairs, options.seed))
        values.push_back({l, v, model.f(l, v, at), model.f(v, l, at), eta2(l), eta2(v)});
    detail::judge_reciprocity_pairs(r, values, options.absolute_floor);
    const std::string tried = std::to_string(r.tried) + " direction pairs over the sphere";
    const std::string eta = "eta_inside = " + detail::number(eta_inside);
    if (r.passed) {
        r.message = "adjoint reciprocity holds for " + r.model + " (" + eta +
                    "): f(l, v) eta_l^2 = f(v, l) eta_v^2 within relative " + detail::number(r.tolerance) +
                    " for all " + tried + " (worst " + detail::number(r.worst) + ").";
    } else {
        r.message = "adjoint reciprocity FAILS for " + r.model + " (" + eta + "): " + std::to_string(r.failures) +
                    " of " + tried + " differ by more than relative " + detail::number(r.tolerance) +
                    "; worst: f(l, v) = " + shade::detail::to_text(r.value) + " but f(v, l) = " +
                    shade::detail::to_text(r.other) + " (relative difference " + detail::number(r.worst) +
                    ") for " + detail::where(r.l, r.v, at) +
                    ". In radiance mode a refraction carries (eta_v / eta_l)^2; look for it missing, inverted or "
                    "applied to reflection.";
    }
    return r;
}

} // namespace shade::check
