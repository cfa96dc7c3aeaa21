// A minimal program that uses shade the way a renderer author would. Built three ways by
// the consumer tests (add_subdirectory, find_package, pkg-config); exits 0 on success.
#include <cmath>
#include <cstdio>

#include <shade/shade.hpp>

int main() {
    const auto f = shade::frame<float>::from_normal({0.0f, 0.0f, -1.0f});
    const bool frame_ok = std::abs(glm::dot(glm::cross(f.t, f.b), f.n) - 1.0f) < 1e-6f;
    std::printf("shade %s consumer: frame %s\n", SHADE_VERSION_STRING, frame_ok ? "ok" : "BROKEN");
    return frame_ok ? 0 : 1;
}
