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
#include <shade/core/math.hpp>
#include <shade/core/random.hpp>
#include <shade/core/sampling.hpp>

namespace shade::check {

/// Settings of the albedo estimator and the energy-conservation check.
struct albedo_options {
    /// Strata per axis of the unit square: each albedo estimate uses strata² jittered,
    /// cosine-weighted samples (default 256² = 65536).
    std::size_t strata = 256;
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

/// Estimates a(v) = ∫ f(l, v) max(n·l, 0) dl for the world-space view v at `at`.
///
/// Estimator: l is drawn cosine-weighted (pdf = n·l / pi) from strata² jittered strata of
/// the unit square mapped with the concentric map, so each sample contributes
/// f(l, v) (n·l) / pdf = pi f(l, v). Stratification makes the error fall roughly as
/// 1/strata² for smooth lobes instead of 1/strata. Sums are kept in double for any T.
template <brdf B>
albedo_sample<scalar_of<B>> directional_albedo(const B& model, const vec3<scalar_of<B>>& v,
                                               const surface_point<scalar_of<B>>& at,
                                               std::size_t strata = 256,
                                               std::uint64_t seed = 1) {
    using T = scalar_of<B>;
    if (strata < 2)
        throw invalid_parameter("strata", "must be >= 2 (strata^2 samples per view)",
                                shade::detail::to_text(double(strata)));
    rng random(seed);
    glm::dvec3 sum(0);
    glm::dvec3 pair_sq(0);
    glm::dvec3 previous(0);
    const T inv = T(1) / T(strata);
    for (std::size_t i = 0; i < strata; ++i) {
        for (std::size_t j = 0; j < strata; ++j) {
            const vec2<T> u((T(i) + random.uniform<T>()) * inv, (T(j) + random.uniform<T>()) * inv);
            const vec3<T> l_local = square_to_cosine_hemisphere(u);
            glm::dvec3 x(0);
            if (l_local.z > T(0)) { // on the horizon n·l = 0 contributes nothing
                const vec3<T> l = glm::normalize(at.shading.to_world(l_local));
                x = glm::dvec3(model.f(l, v, at)) * pi<double>;
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
                                        options.seed + 7919u * (a * angles + k));
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
