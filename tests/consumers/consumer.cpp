// A minimal program that uses shade the way a renderer author would. Built three ways by
// the consumer tests (add_subdirectory, find_package, pkg-config); exits 0 on success.
#include <cmath>
#include <cstdio>

#include <shade/shade.hpp>
// Included directly as well, so the consumer checks the geometry headers are installed
// whether or not the umbrella lists them yet.
#include <shade/geometry/sphere.hpp>

int main() {
    const auto f = shade::frame<float>::from_normal({0.0f, 0.0f, -1.0f});
    const bool frame_ok = std::abs(glm::dot(glm::cross(f.t, f.b), f.n) - 1.0f) < 1e-6f;

    // A ray from the origin along +z against the unit sphere centred at (0, 0, 5): it
    // enters at z = 4, so t = 4, p = (0, 0, 4) and the outward normal is (0, 0, -1).
    const shade::ray<float> r{{0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 1.0f}};
    const auto h = shade::intersect(r, shade::sphere<float>({0.0f, 0.0f, 5.0f}, 1.0f));
    const bool hit_ok = h.has_value() && std::abs(h->t - 4.0f) < 1e-6f && h->front_face &&
                        std::abs(h->n.z + 1.0f) < 1e-6f;

    std::printf("shade %s consumer: frame %s, ray/sphere %s\n", SHADE_VERSION_STRING,
                frame_ok ? "ok" : "BROKEN", hit_ok ? "ok" : "BROKEN");
    return frame_ok && hit_ok ? 0 : 1;
}
