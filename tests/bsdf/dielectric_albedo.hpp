#pragma once
// The total albedo R + T (importance mode) of shade::rough_dielectric seen from a view at
// cosine mu, estimated with the model's own sampler as examples/dielectric_albedo_tables
// does: u stratified, the lobe choice uc integrated out exactly (the reflection weighted by
// F and the refraction by 1 - F at the visible normal drawn from u).

#include <cmath>
#include <cstddef>
#include <cstdint>

#include <glm/geometric.hpp>

#include <shade/brdf/fresnel.hpp>
#include <shade/bsdf/rough_dielectric.hpp>
#include <shade/check/energy.hpp>

namespace bsdf_test {

/// R + T of `model` for the unit view v in the local frame (v.z > 0: v outside; n = +z,
/// t = +x), from strata^2 stratified u; albedo and standard error in channel x.
template <class Distribution>
shade::check::albedo_sample<double> single_scattering_albedo(const shade::rough_dielectric<Distribution>& model,
                                                             const shade::vec3<double>& v, std::size_t strata,
                                                             std::uint64_t seed) {
    using T = double;
    shade::surface_point<T> at;
    at.shading = shade::frame<T>::from_normal_tangent({0, 0, 1}, {1, 0, 0});
    const auto weight = [&](const shade::vec2<T>& u, T uc) {
        const auto s = model.sample(v, uc, u, at, shade::transport_mode::importance);
        return s ? s->weight.x : 0.0;
    };
    return shade::check::detail::stratified_estimate<T>(v, strata, seed, true, [&](const shade::vec2<T>& u, shade::rng&) {
        const shade::vec3<T> m = model.distribution().sample_visible_normal(v, u);
        const double F = shade::F_dielectric(glm::dot(v, m), model.eta());
        const double reflected = F > 0 ? F * weight(u, 0) : 0.0;
        const double refracted = F < 1 ? (1 - F) * weight(u, std::nextafter(1.0, 0.0)) : 0.0;
        return glm::dvec3(reflected + refracted);
    });
}

/// R + T of `model` for a view in the local frame at cosine mu > 0 (v outside, azimuth 0).
template <class Distribution>
shade::check::albedo_sample<double> single_scattering_albedo(const shade::rough_dielectric<Distribution>& model,
                                                             double mu, std::size_t strata, std::uint64_t seed) {
    return single_scattering_albedo(model, shade::vec3<double>(std::sqrt((1 - mu) * (1 + mu)), 0, mu), strata, seed);
}

/// R alone (the reflected part) of `model` for the unit local view v (either side: v.z < 0
/// is a view inside), from strata^2 stratified u: each reflection of the model's sampler
/// weighted by the F with which sample() chooses it at the visible normal drawn from u (the
/// refraction dropped); albedo and standard error in channel x.
template <class Distribution>
shade::check::albedo_sample<double> single_scattering_reflection(const shade::rough_dielectric<Distribution>& model,
                                                                 const shade::vec3<double>& v, std::size_t strata,
                                                                 std::uint64_t seed) {
    using T = double;
    shade::surface_point<T> at;
    at.shading = shade::frame<T>::from_normal_tangent({0, 0, 1}, {1, 0, 0});
    // The sampler works in the frame of v's side: the visible normal is drawn for the view
    // mirrored to +z, and F is that of v's side (eta_s = eta outside, 1 / eta inside).
    const bool inside = v.z < 0;
    const shade::vec3<T> v_up(v.x, v.y, std::abs(v.z));
    const double eta_s = inside ? 1 / model.eta() : model.eta();
    return shade::check::detail::stratified_estimate<T>(v_up, strata, seed, true, [&](const shade::vec2<T>& u, shade::rng&) {
        const shade::vec3<T> m = model.distribution().sample_visible_normal(v_up, u);
        const double F = shade::F_dielectric(glm::dot(v_up, m), eta_s);
        if (!(F > 0)) return glm::dvec3(0);
        const auto s = model.sample(v, 0, u, at, shade::transport_mode::importance);
        return glm::dvec3(s ? F * s->weight.x : 0.0);
    });
}

} // namespace bsdf_test
