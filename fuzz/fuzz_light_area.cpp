// libFuzzer target: shade::area_light (the parallelogram emitter) in the physical mode:
// sample_incident, pdf_incident, incident_radiance, the classic sample, and any_light's
// forwarding (the checks of light_target.hpp).
//
// Input: byte 0 bit 0 double/float; corner, edge_u, edge_v (vectors); the emission
// (intensity, ambient, diffuse, specular); a sides byte (0 one-sided, 1 two-sided, 2
// invalid); then the situation of light_target.hpp (p, u, w).
//
// Well conditioned for the sample/pdf agreement: every number moderate, edges at least
// 1e-2 long and 1e-2 (sine) from parallel, u at least 1e-3 inside [0, 1]^2, p at least
// 1e-2 from the light's plane, and the sampled direction at least 1e-2 (cosine) from
// grazing the light.

#include <cmath>
#include <cstddef>
#include <cstdint>

#include <glm/geometric.hpp>

#include <shade/light/area.hpp>

#include "light_target.hpp"

namespace {

using namespace shade;

template <std::floating_point T>
void run(fuzz::input& in) {
    auto r = fuzz::light_reader<T>(in);
    const vec3<T> corner = r.vector();
    const vec3<T> edge_u = r.vector();
    const vec3<T> edge_v = r.vector();
    const emission<T> e = fuzz::decode_emission(r);
    const sidedness sides = fuzz::decode_sides(in);
    const auto s = fuzz::decode_light_situation(r);
    const auto light = fuzz::build<area_light<T>>(corner, edge_u, edge_v, e, sides);
    if (!light) return;
    const T len_u = glm::length(edge_u), len_v = glm::length(edge_v);
    const T sine = glm::length(glm::cross(edge_u, edge_v)) / (len_u * len_v);
    const auto inside = [](T x) { return x >= T(1e-3) && x <= T(1) - T(1e-3); };
    const bool shape_ok = r.moderate && len_u >= T(1e-2) && len_v >= T(1e-2) && sine >= T(1e-2) &&
                          inside(s.u.x) && inside(s.u.y) &&
                          std::abs(glm::dot(light->normal(), s.p - corner)) >= T(1e-2);
    fuzz::check_light(*light, s, [&](const incident_sample<T>& x) {
        return shape_ok && std::abs(glm::dot(light->normal(), x.l)) >= T(1e-2);
    });
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return shade::fuzz::dispatch(data, size, &run<float>, &run<double>);
}
