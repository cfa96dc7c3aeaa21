#pragma once
// Energy conservation: the directional albedo a(v) = ∫ f(l, v) (n·l) dl over the upper
// hemisphere is the fraction of light arriving from v that is reflected anywhere (by
// reciprocity, equally the fraction reflected toward v under uniform illumination). A
// surface that does not create energy has a(v) <= 1 for every v. The white-furnace test
// plots a(v) against the viewing angle.

#include <algorithm>
#include <cmath>
#include <concepts>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include <shade/brdf/brdf.hpp>
#include <shade/check/result.hpp>
#include <shade/core/error.hpp>
#include <shade/core/frame.hpp>
#include <shade/core/math.hpp>
#include <shade/core/random.hpp>
#include <shade/core/sampling.hpp>

namespace shade::check {

/// Settings of the albedo estimator and the energy-conservation check.
struct albedo_options {
    /// Strata per axis of the unit square: each albedo estimate uses strata² jittered
    /// samples (default 256² = 65536).
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
    double tolerance = 0.01;  ///< pass when every albedo channel is <= 1 + tolerance
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

/// The density of sample_power_lobe at w (per steradian).
template <std::floating_point T>
double power_lobe_pdf(const vec3<T>& r, double e, const vec3<T>& w) {
    const double c = double(glm::dot(r, w));
    return c > 0 ? (e + 1.0) / (2.0 * pi<double>) * std::pow(c, e) : 0.0;
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
/// sample of a Lambertian BRDF contributes exactly pi f. Sums are kept in double.
template <brdf B>
albedo_sample<scalar_of<B>> directional_albedo(const B& model, const vec3<scalar_of<B>>& v,
                                               const surface_point<scalar_of<B>>& at,
                                               std::size_t strata = 256,
                                               std::uint64_t seed = 1,
                                               double lobe_fraction = 2.0 / 3.0) {
    using T = scalar_of<B>;
    if (strata < 2)
        throw invalid_parameter("strata", "must be >= 2 (strata^2 samples per view)",
                                shade::detail::to_text(double(strata)));
    // Below 1, so the cosine part stays in the mixture (it is what makes the estimate unbiased).
    const double q = require_in_range("lobe_fraction", lobe_fraction, 0.0, 0.95);
    const vec3<T> n = at.n();
    const vec3<T> mirror = glm::normalize(T(2) * glm::dot(n, v) * n - v);
    constexpr double e_wide = 8;
    constexpr double e_narrow = 128;
    rng random(seed);
    glm::dvec3 sum(0);
    glm::dvec3 pair_sq(0);
    glm::dvec3 previous(0);
    const T inv = T(1) / T(strata);
    for (std::size_t i = 0; i < strata; ++i) {
        for (std::size_t j = 0; j < strata; ++j) {
            vec2<T> u((T(i) + random.uniform<T>()) * inv, (T(j) + random.uniform<T>()) * inv);
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
            glm::dvec3 x(0);
            const double n_dot_l = double(glm::dot(n, l));
            if (n_dot_l > 0) { // at or below the horizon n·l = 0 contributes nothing
                const double pdf = (1.0 - q) * n_dot_l / pi<double> +
                                   0.5 * q * detail::power_lobe_pdf(mirror, e_wide, l) +
                                   0.5 * q * detail::power_lobe_pdf(mirror, e_narrow, l);
                x = glm::dvec3(model.f(l, v, at)) * (n_dot_l / pdf);
            }
            sum += x;
            if (j % 2 == 1) pair_sq += (x - previous) * (x - previous);
            previous = x;
        }
    }
    const double m = double(strata * strata);
    albedo_sample<T> s;
    s.v = v;
    s.albedo = sum / m;
    // Collapsed-strata variance estimate (Cochran 1977, "Sampling Techniques", 3rd ed.,
    // sec. 5A.12): with one sample per stratum, neighbouring strata are paired and
    // Var ~ sum over pairs of (x_a - x_b)^2 / m^2. It overstates the error slightly, never
    // understates it for smooth integrands, and unlike the i.i.d. formula it reflects the
    // gain from stratification.
    s.standard_error = glm::sqrt(pair_sq) / m;
    return s;
}

/// The white-furnace curve: a(v) for every viewing angle and azimuth of `options`, in
/// order of azimuth, then angle.
template <brdf B>
std::vector<albedo_sample<scalar_of<B>>> white_furnace(const B& model,
                                                       const surface_point<scalar_of<B>>& at,
                                                       const albedo_options& options = {}) {
    using T = scalar_of<B>;
    require_in_range("max_theta_degrees", options.max_theta_degrees, 0.0, 90.0);
    std::vector<albedo_sample<T>> curve;
    const std::size_t angles = std::max<std::size_t>(options.view_angles, 1);
    const std::size_t azimuths = std::max<std::size_t>(options.azimuths, 1);
    const double max_theta = options.max_theta_degrees * pi<double> / 180.0;
    for (std::size_t a = 0; a < azimuths; ++a) {
        const T phi = T(pi<double> * double(a) / double(azimuths));
        for (std::size_t k = 0; k < angles; ++k) {
            const T theta = angles == 1 ? T(0) : T(max_theta * double(k) / double(angles - 1));
            const vec3<T> v = glm::normalize(at.shading.to_world(spherical_direction(theta, phi)));
            auto s = directional_albedo(model, v, at, options.strata,
                                        options.seed + 7919u * (a * angles + k),
                                        options.lobe_fraction);
            s.theta_v = theta;
            s.phi_v = phi;
            curve.push_back(s);
        }
    }
    return curve;
}

/// Checks a(v) <= 1 + options.tolerance for every view of the white-furnace curve.
/// result::worst is the largest albedo found (any channel); result::value is that albedo
/// and result::v its view (result::l is unused and equals v).
template <brdf B>
result<scalar_of<B>> energy_conservation(const B& model, const surface_point<scalar_of<B>>& at,
                                         const albedo_options& options = {}) {
    using T = scalar_of<B>;
    result<T> r;
    r.property = "energy conservation";
    r.model = options.model;
    r.at = at;
    r.tolerance = require_non_negative("tolerance", options.tolerance);
    double worst_error = 0;
    bool have_worst = false;
    for (const auto& s : white_furnace(model, at, options)) {
        ++r.tried;
        const double top = std::max(s.albedo.x, std::max(s.albedo.y, s.albedo.z));
        const double measure = std::isfinite(top) ? top : std::numeric_limits<double>::infinity();
        if (!(measure <= 1.0 + r.tolerance)) ++r.failures;
        if (!have_worst || measure > r.worst) {
            have_worst = true;
            r.worst = measure;
            r.v = s.v;
            r.l = s.v;
            r.value = rgb<T>(s.albedo);
            worst_error = std::max(s.standard_error.x, std::max(s.standard_error.y, s.standard_error.z));
        }
    }
    r.passed = r.failures == 0;
    const std::string n = std::to_string(options.strata * options.strata);
    const std::string theta = detail::number(
        std::acos(std::clamp(double(glm::dot(r.v, at.n())), -1.0, 1.0)) * 180.0 / pi<double>);
    const std::string estimate = "max albedo " + detail::number(r.worst) + " (+- " +
                                 detail::number(worst_error) + ", " + n +
                                 " samples per view) at theta_v = " + theta +
                                 " deg, v = " + shade::detail::to_text(r.v);
    if (r.passed) {
        r.message = "energy conservation holds for " + r.model + ": " + estimate + " over " +
                    std::to_string(r.tried) + " views, within 1 + " +
                    detail::number(r.tolerance) + ".";
    } else {
        r.message = "energy conservation FAILS for " + r.model + ": " +
                    std::to_string(r.failures) + " of " + std::to_string(r.tried) +
                    " views reflect more than they receive; " + estimate +
                    " exceeds 1 + " + detail::number(r.tolerance) +
                    ". Check the normalisation constant of the lobe.";
    }
    return r;
}

} // namespace shade::check
