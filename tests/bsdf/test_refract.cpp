#include <cmath>
#include <limits>

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/bsdf/refract.hpp>
#include <shade/core/random.hpp>
#include <shade/core/sampling.hpp>

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

TEST_CASE_TEMPLATE("generalized_half_vector: the half vector for eta = 1, turned to n's side", T, float, double) {
    const T tol = T(8) * std::numeric_limits<T>::epsilon();
    shade::rng random(12);
    for (int i = 0; i < 1000; ++i) {
        const vec3<T> l = shade::square_to_uniform_sphere(shade::vec2<T>(random.uniform<T>(), random.uniform<T>()));
        const vec3<T> v = shade::square_to_uniform_sphere(shade::vec2<T>(random.uniform<T>(), random.uniform<T>()));
        const auto m = shade::generalized_half_vector(l, v, T(1));
        REQUIRE(m);
        // Walter et al. 2007, eq. 13: h = normalize(l + v), on n's side (local n = +z).
        vec3<T> h = glm::normalize(l + v);
        if (h.z < 0) h = -h;
        CHECK(glm::length(*m - h) <= tol);
        CHECK(m->z >= T(0));
        // Given another normal, turned to its side.
        const vec3<T> n = glm::normalize(vec3<T>(T(0.3), T(-0.5), T(0.8)));
        const auto m_n = shade::generalized_half_vector(l, v, T(1), n);
        REQUIRE(m_n);
        CHECK(glm::dot(*m_n, n) >= T(0));
        CHECK(glm::length(glm::cross(*m_n, *m)) <= tol);
    }
    // l = -v: no half vector.
    CHECK(!shade::generalized_half_vector(vec3<T>(0, T(0.6), T(0.8)), vec3<T>(0, T(-0.6), T(-0.8)), T(1)));
}

TEST_CASE_TEMPLATE("generalized_half_vector: recovers the normal that refracts v into l (Snell's law)", T, float, double) {
    // For a normal m and v on its side, l = refract(v, m, eta) crosses m; the generalized half
    // vector of (l, v, eta) must be m again (turned to +z), and v, l must satisfy
    // sin(theta_v) = eta sin(theta_l) about it (eta = eta_l / eta_v).
    const T tol = sizeof(T) <= 4 ? T(2e-5) : T(1e-12);
    shade::rng random(13);
    int tested = 0;
    for (const double eta : {1.5, 1.0 / 1.5, 1.33, 1.0 / 1.33, 2.4}) {
        CAPTURE(eta);
        for (int i = 0; i < 500; ++i) {
            const vec3<T> m = shade::square_to_uniform_sphere(shade::vec2<T>(random.uniform<T>(), random.uniform<T>()));
            vec3<T> v = shade::square_to_uniform_sphere(shade::vec2<T>(random.uniform<T>(), random.uniform<T>()));
            if (glm::dot(v, m) < 0) v = -v;
            if (glm::dot(v, m) < T(0.05)) continue; // near-grazing on m: refraction ill-conditioned
            const auto l = shade::refract(v, m, T(eta));
            if (!l) continue; // total internal reflection
            const auto g = shade::generalized_half_vector(*l, v, T(eta));
            REQUIRE(g);
            const vec3<T> expected = m.z < 0 ? -m : m;
            CHECK(glm::length(*g - expected) <= tol);
            // Snell: |v x m| = eta |l x m|, v and l on opposite sides of m.
            CHECK(std::abs(glm::length(glm::cross(v, *g)) - T(eta) * glm::length(glm::cross(*l, *g))) <= tol);
            CHECK(glm::dot(v, *g) * glm::dot(*l, *g) < T(0));
            ++tested;
        }
    }
    CHECK(tested > 1500);
}
