// libFuzzer target: shade::sphere_light in the physical mode (cone sampling from outside,
// area sampling from inside): sample_incident, pdf_incident, incident_radiance, the
// classic sample, and any_light's forwarding (the checks of light_target.hpp).
//
// Input: byte 0 bit 0 double/float; center (vector), radius (scalar); the emission
// (intensity, ambient, diffuse, specular); a sides byte (0 one-sided, 1 two-sided, 2
// invalid); then the situation of light_target.hpp (p, u, w).
//
// Well conditioned for the sample/pdf agreement: every number moderate, radius at least
// 1e-2, and p either outside with |p - c| >= 1.01 R and u.x <= 0.99 (the direction at
// least ~0.5 % of R inside the cone's edge), or inside with |p - c| <= 0.99 R, the sampled
// point at least 1e-2 away and its direction at least 1e-2 (cosine) from grazing.

#include <cmath>
#include <cstddef>
#include <cstdint>

#include <glm/geometric.hpp>

#include <shade/light/sphere.hpp>

#include "light_target.hpp"

namespace {

using namespace shade;

template <std::floating_point T>
void run(fuzz::input& in) {
    auto r = fuzz::light_reader<T>(in);
    const vec3<T> center = r.vector();
    const T radius = r.scalar();
    const emission<T> e = fuzz::decode_emission(r);
    const sidedness sides = fuzz::decode_sides(in);
    const auto s = fuzz::decode_light_situation(r);
    const auto light = fuzz::build<sphere_light<T>>(center, radius, e, sides);
    if (!light) return;
    const T d = glm::length(s.p - center);
    const bool outside = d >= T(1.01) * radius && s.u.x <= T(0.99);
    const bool inside = d <= T(0.99) * radius;
    const bool shape_ok = r.moderate && radius >= T(1e-2) && (outside || inside);
    fuzz::check_light(*light, s, [&](const incident_sample<T>& x) {
        if (!shape_ok) return false;
        if (outside) return true;
        const vec3<T> n_x = glm::normalize(s.p + x.distance * x.l - center);
        return x.distance >= T(1e-2) && std::abs(glm::dot(n_x, x.l)) >= T(1e-2);
    });
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return shade::fuzz::dispatch(data, size, &run<float>, &run<double>);
}
