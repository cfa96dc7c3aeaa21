// libFuzzer target: shade::sphere construction and ray/sphere intersection.
//
// Input: byte 0 bit 0 double/float, bit 1 aimed; then the sphere's centre and radius,
// the ray's origin, then either its direction (free) or a point on the unit sphere u and
// a scale s, the direction being s * (centre + radius * normalize(u) - origin) (aimed, so
// that grazing and tangent rays are common), then t_min and t_max.
// Checked: the validating constructor throws exactly shade::invalid_parameter, and does so
// exactly for a non-finite centre or a radius that is not finite and > 0; every hit obeys
// the common hit rules (hit_checks.hpp).

#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <optional>

#include <glm/geometric.hpp>

#include <shade/geometry/sphere.hpp>

#include "expect.hpp"
#include "hit_checks.hpp"
#include "input.hpp"

namespace {

template <std::floating_point T>
void run(shade::fuzz::input& in, bool aimed) {
    using namespace shade;
    using fuzz::expect;
    const vec3<T> center = in.vector<T>();
    const T radius = in.scalar<T>();
    const bool acceptable = is_finite(center) && std::isfinite(radius) && radius > T(0);
    std::optional<sphere<T>> s;
    try {
        s.emplace(center, radius);
    } catch (const invalid_parameter&) {
        expect(!acceptable, "sphere rejected a finite centre and a finite positive radius");
        return;
    }
    expect(acceptable, "sphere accepted a non-finite centre or a radius not finite and > 0");

    ray<T> r;
    r.origin = in.vector<T>();
    if (aimed) {
        const vec3<T> u = glm::normalize(in.vector<T>()); // NaN for a zero u: fine, no hit
        const T scale = in.scalar<T>();
        r.direction = scale * (center + radius * u - r.origin);
    } else {
        r.direction = in.vector<T>();
    }
    r.t_min = in.scalar<T>();
    r.t_max = in.scalar<T>();
    fuzz::check_ray_checked(r);
    fuzz::check_hit(r, intersect(r, *s));
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    shade::fuzz::input in(data, size);
    const std::uint8_t head = in.byte();
    if ((head & 1u) != 0)
        run<double>(in, (head & 2u) != 0);
    else
        run<float>(in, (head & 2u) != 0);
    return 0;
}
