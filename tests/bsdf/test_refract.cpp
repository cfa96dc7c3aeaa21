#include <cmath>
#include <limits>

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/bsdf/refract.hpp>
#include <shade/core/random.hpp>

#include "brdf/support.hpp"

using namespace brdf_test;
using brdf_test::close;

TEST_CASE_TEMPLATE("refract: Snell's law, in the plane of incidence, unit length", T, float, double) {
    const T tol = sizeof(T) <= 4 ? T(1e-5) : T(1e-13);
    const auto at = brdf_test::tilted<T>();
    const vec3<T> n = at.n();
    shade::rng random(5);
    for (const double eta : {1.0 / 2.4, 1.0 / 1.5, 1.0, 1.33, 1.5, 2.4}) {
        CAPTURE(eta);
        for (int i = 0; i < 200; ++i) {
            const T theta = T(1.5707) * random.uniform<T>(); // drawn in sequence: the same
            const T phi = T(6.28) * random.uniform<T>();      // directions with every compiler
            const vec3<T> w = brdf_test::direction(at, theta, phi);
            const T cos_i = glm::dot(n, w);
            const T sin_i = glm::length(w - cos_i * n);
            const auto t = shade::refract(w, n, T(eta));
            if (sin_i / T(eta) >= T(1) + tol) {
                CHECK(!t); // beyond the critical angle
                continue;
            }
            if (sin_i / T(eta) > T(1) - tol) continue; // at the critical angle, either answer
            REQUIRE(t);
            CHECK(std::abs(glm::length(*t) - T(1)) <= tol);
            const T cos_t = -glm::dot(n, *t);
            CHECK(cos_t >= T(0)); // on the other side
            // eta_i sin_i = eta_t sin_t with eta = eta_t / eta_i.
            CHECK(std::abs(T(eta) * glm::length(*t + cos_t * n) - sin_i) <= T(4) * tol);
            // In the plane of w and n, on the far side of n: the tangential parts point
            // in opposite directions.
            CHECK(std::abs(glm::dot(glm::cross(n, w), *t)) <= T(4) * tol);
            CHECK(glm::dot(w - cos_i * n, *t + cos_t * n) <= tol);
            // Refracting back returns w (the path is reversible).
            const auto back = shade::refract(*t, -n, T(1) / T(eta));
            REQUIRE(back);
            CHECK(glm::length(*back - w) <= T(64) * tol);
        }
    }
}

TEST_CASE_TEMPLATE("refract: normal incidence goes straight through; eta = 1 does not bend", T, float, double) {
    const vec3<T> n(0, 0, 1);
    for (const T eta : {T(1e-4), T(0.5), T(1), T(1.5), T(1e4)}) {
        const auto t = shade::refract(n, n, eta);
        REQUIRE(t);
        CHECK(glm::length(*t + n) <= T(1e-6));
    }
    const vec3<T> w = glm::normalize(vec3<T>(1, 2, 3));
    const auto t = shade::refract(w, n, T(1));
    REQUIRE(t);
    CHECK(glm::length(*t + w) <= T(1e-6));
    // Grazing into the denser side: the ray bends to the critical angle, sin_t = 1/eta.
    const auto g = shade::refract(vec3<T>(1, 0, 0), n, T(1.5));
    REQUIRE(g);
    CHECK(close(std::sqrt(g->x * g->x + g->y * g->y), T(1) / T(1.5), T(1e-6)));
    // Grazing from the denser side: totally reflected.
    CHECK(!shade::refract(vec3<T>(1, 0, 0), n, T(1) / T(1.5)));
}
