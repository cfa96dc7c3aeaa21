// libFuzzer target: shade::disk_light in the physical mode: sample_incident,
// pdf_incident, incident_radiance, the classic sample, and any_light's forwarding (the
// checks of light_target.hpp).
//
// Input: byte 0 bit 0 double/float; center, normal (vectors), radius (scalar); the
// emission (intensity, ambient, diffuse, specular); a sides byte (0 one-sided, 1
// two-sided, 2 invalid); then the situation of light_target.hpp (p, u, w).
//
// Well conditioned for the sample/pdf agreement: every number moderate, radius at least
// 1e-2, u mapped by the concentric map to at most 0.998 of the radius (each of 2u - 1
// within 0.998), p at least 1e-2 from the disk's plane, and the sampled direction at
// least 1e-2 (cosine) from grazing the disk.

#include <cmath>
#include <cstddef>
#include <cstdint>

#include <glm/geometric.hpp>

#include <shade/light/disk.hpp>

#include "light_target.hpp"

namespace {

using namespace shade;

template <std::floating_point T>
void run(fuzz::input& in) {
    auto r = fuzz::light_reader<T>(in);
    const vec3<T> center = r.vector();
    const vec3<T> normal = r.vector();
    const T radius = r.scalar();
    const emission<T> e = fuzz::decode_emission(r);
    const sidedness sides = fuzz::decode_sides(in);
    const auto s = fuzz::decode_light_situation(r);
    const auto light = fuzz::build<disk_light<T>>(center, normal, radius, e, sides);
    if (!light) return;
    const auto inside = [](T x) { return std::abs(T(2) * x - T(1)) <= T(0.998); };
    const bool shape_ok = r.moderate && radius >= T(1e-2) && inside(s.u.x) && inside(s.u.y) &&
                          std::abs(glm::dot(light->normal(), s.p - center)) >= T(1e-2);
    fuzz::check_light(*light, s, [&](const incident_sample<T>& x) {
        return shape_ok && std::abs(glm::dot(light->normal(), x.l)) >= T(1e-2);
    });
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return shade::fuzz::dispatch(data, size, &run<float>, &run<double>);
}
