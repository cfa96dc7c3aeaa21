#pragma once
// Energy conservation: the directional albedo a(v) = ∫ f(l, v) (n·l) dl over the upper
// hemisphere is the fraction of light arriving from v that is reflected anywhere (by
// reciprocity, equally the fraction reflected toward v under uniform illumination). A
// surface that does not create energy has a(v) <= 1 for every v. The white-furnace test
// plots a(v) against the viewing angle. The albedo is estimated from samples, so the check
// reports pass, fail or inconclusive from the estimate's standard error.

#include <algorithm>
#include <cmath>
#include <concepts>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include <shade/brdf/brdf.hpp>
#include <shade/bsdf/bsdf.hpp>
#include <shade/check/detail/model_ref.hpp>
#include <shade/check/result.hpp>
#include <shade/core/error.hpp>
#include <shade/core/frame.hpp>
#include <shade/core/math.hpp>
#include <shade/core/random.hpp>
#include <shade/core/sampling.hpp>

namespace shade::check {

/// How the albedo is estimated.
enum class albedo_estimator {
    automatic,   ///< the model's own sampler when it has one (sampled_brdf), else the mixture
    own_sampler, ///< the model's own sampler (sampled_albedo); only for a sampled_brdf
    mixture,     ///< the defensive mixture of directional_albedo, for any BRDF
};

/// The fewest samples per view for which energy_conservation gives a verdict other than
/// inconclusive. Its standard error comes from strata paired up (see directional_albedo):
/// with m samples it has m/2 degrees of freedom, and below 128 of them the error estimate
/// is itself too uncertain for a k-sigma rule (the Student t quantile for 4 sigma's normal
/// tail probability is 4.5 at 128 degrees of freedom, 7.2 at 16, 38 at 2).
inline constexpr std::size_t min_albedo_samples = 256;

/// Settings of the albedo estimator and the energy-conservation check.
struct albedo_options {
    /// Strata per axis of the unit square: each albedo estimate uses strata² jittered
    /// samples (default 256² = 65536); fewer than min_albedo_samples give no verdict.
    std::size_t strata = 256;
    /// Share of the samples drawn around the mirror direction of v (see
    /// directional_albedo), in [0, 0.95]; the rest are cosine-weighted. 0 gives pure
    /// cosine sampling.
    double lobe_fraction = 2.0 / 3.0;
    /// Viewing angles theta_v, evenly spaced from 0 to max_theta_degrees inclusive.
    std::size_t view_angles = 16;
    /// Largest viewing angle from the normal, in degrees (< 90: at 90 the view is on the
    /// horizon, where every model returns 0).
    double max_theta_degrees = 89;
    /// Viewing azimuths phi_v, evenly spaced over [0, pi): several, so anisotropic models
    /// are seen along and across their tangent.
    std::size_t azimuths = 4;
    std::uint64_t seed = 1;   ///< seed of the jitter; same seed, same estimate
    /// The bound is 1 + tolerance: a margin for the estimators' own small biases (none is
    /// known for the mixture or a correct sampler; a float model's rounding is far below).
    double tolerance = 0.01;
    /// k of the k-sigma rule: a view passes when albedo + k SE <= 1 + tolerance and fails
    /// when albedo - k SE > 1 + tolerance, in every channel (decide_at_most).
    double sigmas = 4;
    albedo_estimator estimator = albedo_estimator::automatic; ///< see albedo_estimator
    std::string model = "BRDF"; ///< name used in the message
};

/// One point of a white-furnace curve: the directional albedo seen from one view.
template <std::floating_point T>
struct albedo_sample {
    T theta_v = 0;                 ///< viewing angle from the normal, radians
    T phi_v = 0;                   ///< viewing azimuth from the tangent, radians
    vec3<T> v{0, 0, 1};            ///< the view direction in world space
    glm::dvec3 albedo{0};          ///< estimated a(v) per channel
    glm::dvec3 standard_error{0};  ///< its estimated standard error (collapsed strata)
    /// The standard deviation of a single sample's contribution (for a sampler, of its
    /// weight, nullopt counting as 0), per channel: how noisy one sample is in a renderer.
    glm::dvec3 sample_deviation{0};
    std::size_t samples = 0;       ///< samples the estimate used
    bool own_sampler = false;      ///< true when the model's own sampler drew them
};

namespace detail {

/// A direction around the unit axis r with density (e+1)/(2 pi) cos^e(angle to r), from
/// u in [0,1)^2 (the Phong lobe, sampled as in Lafortune & Willems 1994).
template <std::floating_point T>
vec3<T> sample_power_lobe(const vec3<T>& r, double e, const vec2<T>& u) {
    const T cos_a = T(std::pow(double(u.x), 1.0 / (e + 1.0)));
    const T sin_a = safe_sqrt(T(1) - cos_a * cos_a);
    const T phi = T(2) * pi<T> * u.y;
    const frame<T> f = frame<T>::from_normal(r);
    return glm::normalize(f.to_world(vec3<T>(sin_a * std::cos(phi), sin_a * std::sin(phi), cos_a)));
}

/// The albedo_sample of the mean of contribution(u, random) over strata² points u, one
/// jittered in each stratum of the unit square (u stays in [0, 1) even where (i + xi) /
/// strata rounds up in float); `random` is for any further random numbers the
/// contribution needs.
///
/// Collapsed-strata variance estimate (Cochran 1977, "Sampling Techniques", 3rd ed.,
/// sec. 5A.12): with one sample per stratum, neighbouring strata are paired and
/// Var ~ sum over pairs of (x_a - x_b)^2 / m^2. It overstates the error slightly, never
/// understates it for smooth integrands, and unlike the i.i.d. formula it reflects the
/// gain from stratification. sample_deviation is the i.i.d. standard deviation of one
/// contribution.
template <std::floating_point T, class Contribution>
albedo_sample<T> stratified_estimate(const vec3<T>& v, std::size_t strata, std::uint64_t seed, bool own_sampler,
                                     Contribution&& contribution) {
    rng random(seed);
    glm::dvec3 sum(0);
    glm::dvec3 sum_sq(0);
    glm::dvec3 pair_sq(0);
    glm::dvec3 previous(0);
    const T inv = T(1) / T(strata);
    const T below_one = T(1) - std::numeric_limits<T>::epsilon() / 2;
    for (std::size_t i = 0; i < strata; ++i) {
        for (std::size_t j = 0; j < strata; ++j) {
            const T ux = std::min((T(i) + random.uniform<T>()) * inv, below_one);
            const T uy = std::min((T(j) + random.uniform<T>()) * inv, below_one);
            const glm::dvec3 x = contribution(vec2<T>(ux, uy), random);
            sum += x;
            sum_sq += x * x;
            if (j % 2 == 1) pair_sq += (x - previous) * (x - previous);
            previous = x;
        }
    }
    const double m = double(strata * strata);
    albedo_sample<T> s;
    s.v = v;
    s.albedo = sum / m;
    s.standard_error = glm::sqrt(pair_sq) / m;
    s.sample_deviation = glm::sqrt(glm::max(sum_sq / m - s.albedo * s.albedo, glm::dvec3(0)) * (m / std::max(m - 1, 1.0)));
    s.samples = strata * strata;
    s.own_sampler = own_sampler;
    return s;
}

/// The density of sample_power_lobe at w (per steradian).
template <std::floating_point T>
double power_lobe_pdf(const vec3<T>& r, double e, const vec3<T>& w) {
    const double c = double(glm::dot(r, w));
    return c > 0 ? (e + 1.0) / (2.0 * pi<double>) * std::pow(c, e) : 0.0;
}

/// The body of directional_albedo (see there), on the type-erased model.
template <std::floating_point T>
albedo_sample<T> run_directional_albedo(const model_ref<T>& model, const vec3<T>& v, const surface_point<T>& at,
                                        std::size_t strata, std::uint64_t seed, double lobe_fraction) {
    if (strata < 2)
        throw invalid_parameter("strata", "must be >= 2 (strata^2 samples per view)",
                                shade::detail::to_text(double(strata)));
    // Below 1, so the cosine part stays in the mixture (it is what makes the estimate unbiased).
    const double q = require_in_range("lobe_fraction", lobe_fraction, 0.0, 0.95);
    const vec3<T> n = at.n();
    const vec3<T> mirror = glm::normalize(T(2) * glm::dot(n, v) * n - v);
    constexpr double e_wide = 8;
    constexpr double e_narrow = 128;
    return detail::stratified_estimate<T>(v, strata, seed, false, [&](vec2<T> u, rng&) {
        vec3<T> l;
        // Pick the technique with u.x and stretch the chosen part of it back to [0, 1).
        if (double(u.x) < 1.0 - q) {
            u.x = T(std::min(double(u.x) / (1.0 - q), 1.0 - 1e-7));
            l = glm::normalize(at.shading.to_world(square_to_cosine_hemisphere(u)));
        } else {
            const double x = (double(u.x) - (1.0 - q)) / q; // in [0, 1)
            const bool wide = x < 0.5;
            u.x = T(std::min(wide ? 2 * x : 2 * x - 1, 1.0 - 1e-7));
            l = detail::sample_power_lobe(mirror, wide ? e_wide : e_narrow, u);
        }
        const double n_dot_l = double(glm::dot(n, l));
        if (!(n_dot_l > 0)) return glm::dvec3(0); // at or below the horizon: contributes nothing
        const double pdf = (1.0 - q) * n_dot_l / pi<double> + 0.5 * q * detail::power_lobe_pdf(mirror, e_wide, l) +
                           0.5 * q * detail::power_lobe_pdf(mirror, e_narrow, l);
        return glm::dvec3(model.f(l, v, at)) * (n_dot_l / pdf);
    });
}

} // namespace detail

/// Estimates a(v) = ∫ f(l, v) max(n·l, 0) dl for the world-space view v at `at`.
///
/// Estimator: a one-sample mixture (defensive importance sampling, Hesterberg 1995,
/// "Weighted Average Importance Sampling and Defensive Mixture Distributions",
/// Technometrics 37(2)): l is drawn with density
///   p(l) = (1 - q) (n·l)/pi + (q/2) P_8(l) + (q/2) P_128(l),   q = lobe_fraction,
/// where P_e is a Phong lobe of exponent e around the mirror direction of v. The cosine
/// part keeps p > 0 wherever f (n·l) > 0, so the estimate f (n·l) / p is unbiased for any
/// BRDF; the lobes put samples where specular models peak, which pure cosine sampling
/// misses at grazing views (there it is off by tens of percent with 128² samples). The
/// technique is chosen by the first coordinate of strata² jittered strata (concentric map
/// for the cosine part), so the samples stay stratified. With lobe_fraction = 0 every
/// sample of a Lambertian BRDF contributes exactly pi f. Sums are kept in double; the
/// standard error is the collapsed-strata estimate of detail::stratified_estimate.
template <brdf B>
albedo_sample<scalar_of<B>> directional_albedo(const B& model, const vec3<scalar_of<B>>& v,
                                               const surface_point<scalar_of<B>>& at,
                                               std::size_t strata = 256,
                                               std::uint64_t seed = 1,
                                               double lobe_fraction = 2.0 / 3.0) {
    return detail::run_directional_albedo(detail::model_ref<scalar_of<B>>(model), v, at, strata, seed, lobe_fraction);
}

namespace detail {

/// The body of sampled_albedo (see there), on the type-erased model.
template <std::floating_point T>
albedo_sample<T> run_sampled_albedo(const model_ref<T>& model, const vec3<T>& v, const surface_point<T>& at,
                                    std::size_t strata, std::uint64_t seed) {
    if (strata < 2)
        throw invalid_parameter("strata", "must be >= 2 (strata^2 samples per view)",
                                shade::detail::to_text(double(strata)));
    return detail::stratified_estimate<T>(v, strata, seed, true, [&](const vec2<T>& u, rng& random) {
        const auto s = model.sample(v, random.uniform<T>(), u, at);
        return s ? glm::dvec3(s->weight) : glm::dvec3(0);
    });
}

} // namespace detail

/// Estimates a(v) = ∫ f(l, v) max(n·l, 0) dl with the model's own sampler: the mean of
/// sample(v, uc, u, at).weight over strata² draws (nullopt counts as 0), u jittered in
/// strata² strata of the unit square and uc uniform. Unbiased when sample and pdf are
/// consistent and pdf covers f, which the checks of shade/check/sampling.hpp verify. For a
/// visible-normal microfacet sampler the weight is F G2/G1 <= F, so sharp lobes need no
/// more samples than rough ones. The standard error is the collapsed-strata estimate of
/// detail::stratified_estimate, as for directional_albedo.
///
/// For a BSDF with its own sampler (shade::bsdf_sampler) v may be on either side and the
/// estimate is ∫ f(l, v) |n·l| dl over the whole sphere in radiance mode (the mean
/// radiance-mode weight, delta lobes included through their weight): a transmission's
/// weight carries (eta_v / eta_l)^2, so from inside glass the estimate may exceed 1 for a
/// model that creates no energy. The energy a surface sends to each side is
/// shade::check::bsdf_albedo (shade/check/bsdf_energy.hpp, importance mode).
template <sampled_bsdf B>
albedo_sample<scalar_of<B>> sampled_albedo(const B& model, const vec3<scalar_of<B>>& v,
                                           const surface_point<scalar_of<B>>& at, std::size_t strata = 256,
                                           std::uint64_t seed = 1) {
    return detail::run_sampled_albedo(detail::model_ref<scalar_of<B>>(model), v, at, strata, seed);
}

namespace detail {

/// The body of white_furnace (see there), on the type-erased model.
template <std::floating_point T>
std::vector<albedo_sample<T>> run_white_furnace(const model_ref<T>& model, const surface_point<T>& at,
                                                const albedo_options& options) {
    require_in_range("max_theta_degrees", options.max_theta_degrees, 0.0, 90.0);
    if (options.estimator == albedo_estimator::own_sampler && !model.sampled())
        throw invalid_parameter("estimator", "can be own_sampler only for a sampled_brdf", "own_sampler");
    std::vector<albedo_sample<T>> curve;
    const std::size_t angles = std::max<std::size_t>(options.view_angles, 1);
    const std::size_t azimuths = std::max<std::size_t>(options.azimuths, 1);
    const double max_theta = options.max_theta_degrees * pi<double> / 180.0;
    for (std::size_t a = 0; a < azimuths; ++a) {
        const T phi = T(pi<double> * double(a) / double(azimuths));
        for (std::size_t k = 0; k < angles; ++k) {
            const T theta = angles == 1 ? T(0) : T(max_theta * double(k) / double(angles - 1));
            const vec3<T> v = glm::normalize(at.shading.to_world(spherical_direction(theta, phi)));
            const std::uint64_t seed = options.seed + 7919u * (a * angles + k);
            albedo_sample<T> s;
            if (model.sampled() && options.estimator != albedo_estimator::mixture)
                s = run_sampled_albedo(model, v, at, options.strata, seed);
            else
                s = run_directional_albedo(model, v, at, options.strata, seed, options.lobe_fraction);
            s.theta_v = theta;
            s.phi_v = phi;
            curve.push_back(s);
        }
    }
    return curve;
}

} // namespace detail

/// The white-furnace curve: a(v) for every viewing angle and azimuth of `options`, in
/// order of azimuth, then angle, estimated as options.estimator says.
template <brdf B>
std::vector<albedo_sample<scalar_of<B>>> white_furnace(const B& model,
                                                       const surface_point<scalar_of<B>>& at,
                                                       const albedo_options& options = {}) {
    return detail::run_white_furnace(detail::model_ref<scalar_of<B>>(model), at, options);
}

/// The verdict on a(v) <= 1 + options.tolerance for one point of a white-furnace curve:
/// decide_at_most per channel with options.sigmas (fail if any channel fails, pass if all
/// pass); inconclusive below min_albedo_samples samples unless the estimate is not finite.
template <std::floating_point T>
verdict albedo_verdict(const albedo_sample<T>& s, const albedo_options& options) {
    if (s.samples < min_albedo_samples)
        return std::isfinite(s.albedo.x) && std::isfinite(s.albedo.y) && std::isfinite(s.albedo.z)
                   ? verdict::inconclusive
                   : verdict::fail;
    verdict worst = verdict::pass;
    for (int c = 0; c < 3; ++c) {
        const verdict v = decide_at_most(s.albedo[c], s.standard_error[c], 1.0 + options.tolerance, options.sigmas);
        if (v == verdict::fail) return verdict::fail;
        if (v == verdict::inconclusive) worst = verdict::inconclusive;
    }
    return worst;
}

namespace detail {

/// The body of energy_conservation (see there), on the type-erased model.
template <std::floating_point T>
result<T> run_energy_conservation(const model_ref<T>& model, const surface_point<T>& at,
                                  const albedo_options& options) {
    result<T> r;
    r.property = "energy conservation";
    r.model = options.model;
    r.at = at;
    r.tolerance = require_non_negative("tolerance", options.tolerance);
    if (!(options.sigmas > 0)) throw invalid_parameter("sigmas", "must be > 0", shade::detail::to_text(options.sigmas));
    std::size_t undecided = 0;
    verdict deciding = verdict::pass;
    bool have_worst = false;
    bool own_sampler = false;
    const auto rank = [](verdict v) { return v == verdict::fail ? 2 : v == verdict::inconclusive ? 1 : 0; };
    for (const auto& s : run_white_furnace(model, at, options)) {
        ++r.tried;
        own_sampler = s.own_sampler;
        const verdict v = albedo_verdict(s, options);
        if (v == verdict::fail) ++r.failures;
        if (v == verdict::inconclusive) ++undecided;
        const double top = std::max(s.albedo.x, std::max(s.albedo.y, s.albedo.z));
        const double measure = std::isfinite(top) ? top : std::numeric_limits<double>::infinity();
        if (!have_worst || rank(v) > rank(deciding) || (rank(v) == rank(deciding) && measure > r.worst)) {
            have_worst = true;
            deciding = v;
            r.worst = measure;
            r.v = s.v;
            r.l = s.v;
            r.value = rgb<T>(s.albedo);
            r.error = std::max(s.standard_error.x, std::max(s.standard_error.y, s.standard_error.z));
        }
    }
    r.decide(deciding);
    const std::string n = std::to_string(options.strata * options.strata);
    const std::string theta = detail::number(
        std::acos(std::clamp(double(glm::dot(r.v, at.n())), -1.0, 1.0)) * 180.0 / pi<double>);
    const std::string estimate = "albedo " + detail::number(r.worst) + " +- " + detail::number(r.error, 2) +
                                 " (standard error; " + n + " samples per view from " +
                                 (own_sampler ? "its own sampler" : "the cosine/lobe mixture") +
                                 ") at theta_v = " + theta + " deg, v = " + shade::detail::to_text(r.v);
    const std::string rule = " against 1 + " + detail::number(r.tolerance) + " with " +
                             detail::number(options.sigmas) + " standard errors of margin";
    if (r.outcome == verdict::pass) {
        r.message = "energy conservation holds for " + r.model + " over " + std::to_string(r.tried) +
                    " views: largest " + estimate + "," + rule + ".";
    } else if (r.outcome == verdict::fail) {
        r.message = "energy conservation FAILS for " + r.model + ": " + std::to_string(r.failures) + " of " +
                    std::to_string(r.tried) + " views reflect more than they receive; " + estimate + "," + rule +
                    ". Check the normalisation constant of the lobe.";
    } else {
        r.message = "energy conservation is INCONCLUSIVE for " + r.model + ": " + std::to_string(undecided) +
                    " of " + std::to_string(r.tried) + " views cannot be decided; " + estimate + "," + rule +
                    (options.strata * options.strata < min_albedo_samples
                         ? ". Fewer than " + std::to_string(min_albedo_samples) +
                               " samples per view give no verdict: raise strata to at least 16."
                         : ". Raise strata for a smaller standard error.");
    }
    return r;
}

} // namespace detail

/// Checks a(v) <= 1 + options.tolerance for every view of the white-furnace curve, with
/// the three-way verdict of albedo_verdict per view: the check fails when some view fails,
/// passes when every view passes, and is inconclusive otherwise (more samples decide it).
/// result::worst is the albedo (largest channel) of the deciding view: the failing view
/// with the largest albedo, else the inconclusive one, else the largest albedo of all;
/// result::error is its standard error, result::value that albedo, result::v its view
/// (result::l is unused and equals v). result::failures counts failing views.
template <brdf B>
result<scalar_of<B>> energy_conservation(const B& model, const surface_point<scalar_of<B>>& at,
                                         const albedo_options& options = {}) {
    return detail::run_energy_conservation(detail::model_ref<scalar_of<B>>(model), at, options);
}

} // namespace shade::check
