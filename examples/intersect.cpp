// intersect: prints what a few rays hit in a plane, a sphere and a triangle, with every
// triangle algorithm, in float. Run by script/demo.
#include <cstdio>
#include <optional>
#include <string_view>
#include <tuple>

#include <shade/geometry/plane.hpp>
#include <shade/geometry/sphere.hpp>
#include <shade/geometry/triangle.hpp>
#include <shade/geometry/triangle_algorithms.hpp>

#include "support/cli.hpp"

namespace {

using real = float;
using vec3 = shade::vec3<real>;

void print_vec(const char* label, const vec3& v) {
    std::printf("%s(%.4g, %.4g, %.4g)", label, double(v.x), double(v.y), double(v.z));
}

void print_ray(const shade::ray<real>& r) {
    print_vec("  ray o=", r.origin);
    print_vec(" d=", r.direction);
    std::printf(": ");
}

template <class H>
void print_hit(const std::optional<H>& h) {
    if (!h) {
        std::printf("miss\n");
        return;
    }
    std::printf("t=%.6g", double(h->t));
    print_vec(" p=", h->p);
    print_vec(" n=", h->n);
    std::printf(" %s", h->front_face ? "front" : "back");
    if constexpr (requires { h->barycentric; }) print_vec(" b=", h->barycentric);
    std::printf("\n");
}

void print_all();

} // namespace

int main(int argc, char** argv) {
    namespace ex = shade::examples;
    return ex::run_cli("intersect", [&] {
        ex::command_line args(argc, argv);
        while (args.next()) {
            if (args.flag("--help") || args.flag("-h")) {
                std::fputs("usage: intersect\n\nPrints what a few rays hit in a plane, a sphere and a triangle,\n"
                           "with every triangle algorithm, in float. Takes no options but --help.\n",
                           stdout);
                return 0;
            }
            args.unknown();
        }
        print_all();
        return 0;
    });
}

namespace {

void print_all() {
    const shade::ray<real> rays[] = {
        {{0.25f, 0.25f, 3.0f}, {0.0f, 0.0f, -1.0f}},  // straight down
        {{0.25f, 0.25f, -2.0f}, {0.0f, 0.0f, 2.0f}},  // straight up, non-unit direction
        {{-3.0f, 0.25f, 0.5f}, {1.0f, 0.0f, -0.15f}}, // oblique
        {{5.0f, 5.0f, 3.0f}, {0.0f, 0.0f, -1.0f}},    // off to the side
        {{0.0f, 0.0f, 3.0f}, {0.0f, 0.0f, 0.0f}},     // invalid: zero direction
    };

    const shade::plane<real> ground({0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 1.0f});
    std::printf("plane z = 0, normal +z\n");
    for (const auto& r : rays) {
        print_ray(r);
        print_hit(shade::intersect(r, ground));
    }

    const shade::sphere<real> ball({0.5f, 0.5f, 0.0f}, 1.0f);
    std::printf("\nsphere centre (0.5, 0.5, 0), radius 1\n");
    for (const auto& r : rays) {
        print_ray(r);
        print_hit(shade::intersect(r, ball));
    }

    const shade::triangle<real> tri{{0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}};
    std::printf("\ntriangle (0,0,0) (1,0,0) (0,1,0), front face +z\n");
    std::apply(
        [&](auto... algorithm) {
            (
                [&] {
                    using A = decltype(algorithm);
                    std::printf(" %.*s\n", int(A::name.size()), A::name.data());
                    for (const auto& r : rays) {
                        print_ray(r);
                        print_hit(shade::intersect<A>(r, tri));
                    }
                }(),
                ...);
        },
        shade::triangle_algorithms{});
    std::printf(" watertight with back-face culling, ray from below\n");
    print_ray(rays[1]);
    print_hit(shade::intersect<shade::watertight>(rays[1], tri, shade::culling::back_faces));
}

} // namespace
