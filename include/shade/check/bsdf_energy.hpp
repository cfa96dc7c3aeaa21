#pragma once
// Energy conservation of a BSDF over the whole sphere: the fraction of the energy arriving
// along v that a surface reflects and the fraction it transmits, estimated separately with
// the model's own sampler in importance mode, for v on either side of the surface. Not in
// the umbrella header: include it directly.
//
//   const auto a = shade::check::bsdf_albedo(glass, v, at);   // a.reflected, a.transmitted
//   auto r = shade::check::bsdf_energy_conservation(glass, at, {.model = "my glass"});
//   if (!r) std::cerr << r << '\n';

#include <algorithm>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include <shade/bsdf/bsdf.hpp>
#include <shade/check/energy.hpp>
#include <shade/check/result.hpp>
#include <shade/core/error.hpp>
#include <shade/core/math.hpp>
#include <shade/core/sampling.hpp>

namespace shade::check {

/// The albedo of a BSDF for one view v, split by where the energy goes (importance mode,
/// see shade/bsdf/bsdf.hpp): `reflected` the fraction of the energy arriving along v that
/// leaves on v's side, `transmitted` the fraction that leaves on the other side, `total`
/// their sum, each per channel with its standard error. For a model that conserves energy
/// total <= 1; a lossless interface (shade::smooth_dielectric) has total = 1 exactly.
template <std::floating_point T>
struct bsdf_albedo_sample {
    vec3<T> v{0, 0, 1};               ///< the view direction in world space, either side
    T theta_v = 0;                    ///< angle between v and at.n(), radians: > pi/2 when v is inside
    T phi_v = 0;                      ///< azimuth of v from the tangent, radians
    bool inside = false;              ///< true when v is on the side opposite at.n()
    glm::dvec3 reflected{0};          ///< reflected albedo per channel
    glm::dvec3 reflected_error{0};    ///< its standard error
    glm::dvec3 transmitted{0};        ///< transmitted albedo per channel
    glm::dvec3 transmitted_error{0};  ///< its standard error
    glm::dvec3 total{0};              ///< reflected + transmitted, from the same samples
    glm::dvec3 total_error{0};        ///< its standard error
    std::size_t samples = 0;          ///< samples per estimate
};

/// Estimates the reflected and transmitted albedo of `model` for the view v (world space,
/// unit, either side of the surface) at `at`: the mean importance-mode weight of
/// shade::sample_bsdf(model, v, uc, u, at, transport_mode::importance) over strata² draws
/// (u jittered in the strata of the unit square, uc uniform; nullopt counts as 0), the
/// samples whose flags say reflection counted in `reflected`, those that say transmission
/// in `transmitted`. In importance mode a refraction carries no (eta_v / eta_l)^2, so the
/// weight is a fraction of energy (Veach 1997, "Robust Monte Carlo Methods for Light
/// Transport Simulation", sec. 5.2): the sums are what the surface sends to each side.
/// Unbiased when sample and pdf are consistent (shade/check/sampling.hpp). The three
/// estimates use the same draws; standard errors are the collapsed-strata estimate of
/// detail::stratified_estimate (Cochran 1977, "Sampling Techniques", sec. 5A.12). Throws
/// shade::invalid_parameter naming "strata" when strata < 2.
template <sampled_bsdf B>
bsdf_albedo_sample<scalar_of<B>> bsdf_albedo(const B& model, const vec3<scalar_of<B>>& v,
                                             const surface_point<scalar_of<B>>& at, std::size_t strata = 256,
                                             std::uint64_t seed = 1) {
    using T = scalar_of<B>;
    if (strata < 2)
        throw invalid_parameter("strata", "must be >= 2 (strata^2 samples per view)",
                                shade::detail::to_text(double(strata)));
    // The part of the weight that goes to `side` (reflection, transmission or both).
    const auto estimate = [&](bsdf_flags side) {
        return detail::stratified_estimate<T>(v, strata, seed, true, [&](const vec2<T>& u, rng& random) {
            const auto s = sample_bsdf(model, v, random.uniform<T>(), u, at, transport_mode::importance);
            if (!s || (s->flags & side) == bsdf_flags::none) return glm::dvec3(0);
            return glm::dvec3(s->weight);
        });
    };
    const albedo_sample<T> reflected = estimate(bsdf_flags::reflection);
    const albedo_sample<T> transmitted = estimate(bsdf_flags::transmission);
    const albedo_sample<T> total = estimate(bsdf_flags::reflection | bsdf_flags::transmission);
    bsdf_albedo_sample<T> out;
    out.v = v;
    const T cos_v = glm::dot(v, at.n());
    out.theta_v = std::acos(std::clamp(cos_v, T(-1), T(1)));
    out.inside = cos_v < T(0);
    out.reflected = reflected.albedo;
    out.reflected_error = reflected.standard_error;
    out.transmitted = transmitted.albedo;
    out.transmitted_error = transmitted.standard_error;
    out.total = total.albedo;
    out.total_error = total.standard_error;
    out.samples = total.samples;
    return out;
}

/// The white-furnace curve of a BSDF over the whole sphere: bsdf_albedo for every view of
/// `options` (options.view_angles angles from 0 to options.max_theta_degrees from the
/// normal, times options.azimuths azimuths over [0, pi)) seen from outside, then the same
/// views mirrored to the inside (theta_v = pi - theta), options.strata² samples each. The
/// options' estimator and lobe_fraction are not used (the model's own sampler always is).
/// Throws shade::invalid_parameter naming "max_theta_degrees" unless it lies in [0, 90].
template <sampled_bsdf B>
std::vector<bsdf_albedo_sample<scalar_of<B>>> bsdf_white_furnace(const B& model, const surface_point<scalar_of<B>>& at,
                                                                 const albedo_options& options = {}) {
    using T = scalar_of<B>;
    require_in_range("max_theta_degrees", options.max_theta_degrees, 0.0, 90.0);
    std::vector<bsdf_albedo_sample<T>> curve;
    const std::size_t angles = std::max<std::size_t>(options.view_angles, 1);
    const std::size_t azimuths = std::max<std::size_t>(options.azimuths, 1);
    const double max_theta = options.max_theta_degrees * pi<double> / 180.0;
    for (const bool inside : {false, true}) {
        for (std::size_t a = 0; a < azimuths; ++a) {
            const T phi = T(pi<double> * double(a) / double(azimuths));
            for (std::size_t k = 0; k < angles; ++k) {
                const T theta = angles == 1 ? T(0) : T(max_theta * double(k) / double(angles - 1));
                vec3<T> local = spherical_direction(theta, phi);
                if (inside) local.z = -local.z;
                const vec3<T> v = glm::normalize(at.shading.to_world(local));
                const std::uint64_t seed = options.seed + 7919u * ((inside ? azimuths : 0) * angles + a * angles + k);
                bsdf_albedo_sample<T> s = bsdf_albedo(model, v, at, options.strata, seed);
                s.phi_v = phi;
                curve.push_back(s);
            }
        }
    }
    return curve;
}

/// Checks that no view of bsdf_white_furnace (both sides of the surface) sends out more
/// energy than it receives: total albedo <= 1 + options.tolerance, decided per view and
/// channel as albedo_verdict decides a BRDF's albedo (k = options.sigmas standard errors
/// of margin; inconclusive below min_albedo_samples samples). The check fails when some
/// view fails, passes when every view passes, and is inconclusive otherwise.
/// result::worst is the total albedo (largest channel) of the deciding view (as for
/// energy_conservation), result::error its standard error, result::value that total,
/// result::v (and result::l) the view; the message gives its reflected and transmitted
/// parts. Throws shade::invalid_parameter naming "tolerance", "sigmas" or
/// "max_theta_degrees" for a negative tolerance, sigmas <= 0 or an angle outside [0, 90].
template <sampled_bsdf B>
result<scalar_of<B>> bsdf_energy_conservation(const B& model, const surface_point<scalar_of<B>>& at,
                                              const albedo_options& options = {}) {
    using T = scalar_of<B>;
    result<T> r;
    r.property = "energy conservation (BSDF)";
    r.model = options.model;
    r.at = at;
    r.tolerance = require_non_negative("tolerance", options.tolerance);
    if (!(options.sigmas > 0)) throw invalid_parameter("sigmas", "must be > 0", shade::detail::to_text(options.sigmas));
    std::size_t undecided = 0;
    verdict deciding = verdict::pass;
    bool have_worst = false;
    bsdf_albedo_sample<T> worst{};
    const auto rank = [](verdict v) { return v == verdict::fail ? 2 : v == verdict::inconclusive ? 1 : 0; };
    for (const auto& s : bsdf_white_furnace(model, at, options)) {
        ++r.tried;
        albedo_sample<T> as;
        as.albedo = s.total;
        as.standard_error = s.total_error;
        as.samples = s.samples;
        const verdict v = albedo_verdict(as, options);
        if (v == verdict::fail) ++r.failures;
        if (v == verdict::inconclusive) ++undecided;
        const double top = std::max(s.total.x, std::max(s.total.y, s.total.z));
        const double measure = std::isfinite(top) ? top : std::numeric_limits<double>::infinity();
        if (!have_worst || rank(v) > rank(deciding) || (rank(v) == rank(deciding) && measure > r.worst)) {
            have_worst = true;
            deciding = v;
            worst = s;
            r.worst = measure;
            r.v = s.v;
            r.l = s.v;
            r.value = rgb<T>(s.total);
            r.error = std::max(s.total_error.x, std::max(s.total_error.y, s.total_error.z));
        }
    }
    r.decide(deciding);
    const auto top = [](const glm::dvec3& x) { return std::max(x.x, std::max(x.y, x.z)); };
    const std::string estimate =
        "total albedo " + detail::number(r.worst) + " +- " + detail::number(r.error, 2) + " (reflected " +
        detail::number(top(worst.reflected)) + ", transmitted " + detail::number(top(worst.transmitted)) +
        "; standard error, " + std::to_string(options.strata * options.strata) +
        " importance-mode samples per view from its own sampler) at theta_v = " +
        detail::number(double(worst.theta_v) * 180.0 / pi<double>) + " deg (" +
        (worst.inside ? "inside" : "outside") + "), v = " + shade::detail::to_text(r.v);
    const std::string rule = " against 1 + " + detail::number(r.tolerance) + " with " +
                             detail::number(options.sigmas) + " standard errors of margin";
    if (r.outcome == verdict::pass) {
        r.message = "energy conservation holds for " + r.model + " over " + std::to_string(r.tried) +
                    " views on both sides: largest " + estimate + "," + rule + ".";
    } else if (r.outcome == verdict::fail) {
        r.message = "energy conservation FAILS for " + r.model + ": " + std::to_string(r.failures) + " of " +
                    std::to_string(r.tried) + " views send out more than they receive; " + estimate + "," + rule +
                    ". Check the Fresnel split between the lobes and the importance-mode weights.";
    } else {
        r.message = "energy conservation is INCONCLUSIVE for " + r.model + ": " + std::to_string(undecided) +
                    " of " + std::to_string(r.tried) + " views cannot be decided; " + estimate + "," + rule +
                    ". Raise strata for a smaller standard error.";
    }
    return r;
}

} // namespace shade::check
