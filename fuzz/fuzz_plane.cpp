// libFuzzer target: shade::plane construction and ray/plane intersection.
//
// Input: byte 0 bit 0 double/float, bit 1 back-face culling; then the plane's point and
// normal, the ray's origin, direction, t_min and t_max (input.hpp decodes each scalar).
// Checked: the validating constructor throws exactly shade::invalid_parameter, and does so
// exactly when the point is non-finite or the normal is zero or non-finite; an accepted
// plane has a finite unit normal; every hit obeys the common hit rules (hit_checks.hpp)
// and lies on the ray's side given by front_face.

#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>

#include <glm/geometric.hpp>

#include <shade/geometry/plane.hpp>

#include "expect.hpp"
#include "hit_checks.hpp"
#include "input.hpp"

namespace {

template <std::floating_point T>
void run(shade::fuzz::input& in, shade::culling cull) {
    using namespace shade;
    using fuzz::expect;
    const vec3<T> point = in.vector<T>();
    const vec3<T> normal = in.vector<T>();
    const bool acceptable = is_finite(point) && is_finite(normal) && normal != vec3<T>(0);
    std::optional<plane<T>> pl;
    try {
        pl.emplace(point, normal);
    } catch (const invalid_parameter&) {
        expect(!acceptable, "plane rejected a finite point and a finite non-zero normal");
        return;
    }
    expect(acceptable, "plane accepted a non-finite point or a zero/non-finite normal");
    const T n_error = std::abs(glm::length(pl->normal()) - T(1));
    expect(is_finite(pl->normal()) && n_error <= T(8) * std::numeric_limits<T>::epsilon(),
           "plane's normal is not a finite unit vector");

    ray<T> r{in.vector<T>(), in.vector<T>(), in.scalar<T>(), in.scalar<T>()};
    fuzz::check_ray_checked(r);
    const auto h = intersect(r, *pl, cull);
    fuzz::check_hit(r, h, cull);
    if (h) {
        // front_face is defined as n·d < 0; the hit must report the plane's own normal.
        expect(h->front_face == (glm::dot(pl->normal(), r.direction) < T(0)),
               "plane hit's front_face disagrees with the sign of n·d");
        expect(h->n == pl->normal(), "plane hit's normal is not the plane's normal");
    }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    shade::fuzz::input in(data, size);
    const std::uint8_t head = in.byte();
    const shade::culling cull = (head & 2u) != 0 ? shade::culling::back_faces : shade::culling::none;
    if ((head & 1u) != 0)
        run<double>(in, cull);
    else
        run<float>(in, cull);
    return 0;
}
