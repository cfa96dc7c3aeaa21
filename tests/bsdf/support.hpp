#pragma once
// Shared helpers of the BSDF tests: views on either side of a surface, the checks every
// sample must pass, and the sampled fractions of a delta model's lobes.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/bsdf/bsdf.hpp>
#include <shade/core/math.hpp>
#include <shade/core/surface_point.hpp>

#include "brdf/support.hpp"

namespace bsdf_test {

using shade::rgb;
using shade::vec2;
using shade::vec3;

/// The unit direction at polar angle theta_deg (degrees, from at.n(); above 90 is inside)
/// and azimuth 0.4 rad from the tangent.
template <class T>
vec3<T> view_deg(const shade::surface_point<T>& at, double theta_deg) {
    const double theta = theta_deg * shade::pi<double> / 180;
    return brdf_test::direction(at, T(theta), T(0.4));
}

/// Checks what every bsdf_sample must satisfy: unit l, finite f and weight >= 0, pdf in
/// (0, inf), weight = f |n·l| / pdf (to rel, where |n·l| is above the floor of f), exactly
/// one of reflection and transmission, l on v's side for a reflection and on the other for
/// a transmission.
template <class T>
void check_sample(const shade::bsdf_sample<T>& s, const vec3<T>& v, const shade::surface_point<T>& at, T rel) {
    CHECK(std::abs(glm::length(s.l) - T(1)) <= T(8) * std::numeric_limits<T>::epsilon());
    CHECK(brdf_test::finite_non_negative(s.f));
    CHECK(brdf_test::finite_non_negative(s.weight));
    CHECK(s.pdf > T(0));
    CHECK(std::isfinite(s.pdf));
    CHECK(std::isfinite(s.eta));
    CHECK(s.eta > T(0));
    CHECK(shade::is_reflection(s.flags) != shade::is_transmission(s.flags));
    const T n_dot_l = glm::dot(at.n(), s.l);
    const T n_dot_v = glm::dot(at.n(), v);
    if (shade::is_reflection(s.flags)) CHECK(n_dot_l * n_dot_v >= T(0));
    if (shade::is_transmission(s.flags)) CHECK(n_dot_l * n_dot_v <= T(0));
    // |n·l| here (world space) and the model's (often local) cosine differ by a few ulps,
    // which matters relative to a grazing |n·l|: allowed for as an absolute error.
    if (std::abs(n_dot_l) > std::numeric_limits<T>::epsilon()) {
        for (int i = 0; i < 3; ++i) {
            const T expected = s.f[i] * std::abs(n_dot_l) / s.pdf;
            const T allowed = rel * std::max(s.weight[i], expected) +
                              T(16) * std::numeric_limits<T>::epsilon() * s.f[i] / s.pdf;
            CHECK(std::abs(s.weight[i] - expected) <= allowed);
        }
    }
}

/// What a model's sample() gives over n stratified values of uc, (i + 1/2) / n: the
/// fraction of reflections and the mean weight (the expected throughput) of reflections
/// and of transmissions, channel 0.
template <class T>
struct lobe_fractions {
    T reflected = 0;         ///< fraction of samples that reflect
    T reflected_weight = 0;  ///< mean of weight over all samples, reflections only
    T transmitted_weight = 0; ///< mean of weight over all samples, transmissions only
    std::size_t missing = 0; ///< samples that returned nullopt
};

/// Runs `model.sample(v, uc, u, at, mode)` for n stratified uc and checks each sample.
template <class B, class T = shade::scalar_of<B>>
lobe_fractions<T> sample_lobes(const B& model, const vec3<T>& v, const shade::surface_point<T>& at,
                               shade::transport_mode mode, int n = 20000) {
    lobe_fractions<T> r;
    double reflected = 0, w_r = 0, w_t = 0;
    for (int i = 0; i < n; ++i) {
        const T uc = T((i + 0.5) / n);
        const std::optional<shade::bsdf_sample<T>> s = model.sample(v, uc, vec2<T>(T(0.5), T(0.5)), at, mode);
        if (!s) {
            ++r.missing;
            continue;
        }
        if (i % 97 == 0) check_sample(*s, v, at, sizeof(T) <= 4 ? T(1e-5) : T(1e-12));
        CHECK(shade::is_specular(s->flags));
        if (shade::is_reflection(s->flags)) {
            reflected += 1;
            w_r += double(s->weight.x);
        } else {
            w_t += double(s->weight.x);
        }
    }
    r.reflected = T(reflected / n);
    r.reflected_weight = T(w_r / n);
    r.transmitted_weight = T(w_t / n);
    return r;
}

} // namespace bsdf_test
