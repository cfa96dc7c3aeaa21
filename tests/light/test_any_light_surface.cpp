// any_light as seen by a path tracer whose BSDF-sampled ray has hit something: the light's
// own surface (intersect), its radiance at that hit, the density of that direction from the
// hit without a second intersection, and each light's power (for power-proportional light
// selection, shade::power_light_sampler::from_lights).

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/core/error.hpp>
#include <shade/core/math.hpp>
#include <shade/core/random.hpp>
#include <shade/geometry/spawn.hpp>
#include <shade/light/any_light.hpp>
#include <shade/light/light_sampler.hpp>

namespace {

template <class T>
using v3 = shade::vec3<T>;

template <class T>
std::vector<shade::any_light<T>> surface_lights() {
    const auto e = shade::emission<T>::from_physical(shade::rgb<T>(2, 3, 4));
    return {shade::area_light<T>(v3<T>(-1, 2, -1), v3<T>(2, 0, 0), v3<T>(0, 0, 2), e),
            shade::disk_light<T>(v3<T>(0, 2, 0), v3<T>(0, -1, 0), T(0.5), e),
            shade::sphere_light<T>(v3<T>(0, 2, 0), T(0.5), e)};
}

} // namespace

TEST_CASE_TEMPLATE("any_light: intersect, radiance at the hit and pdf from the hit agree with the light's own answers", T, float, double) {
    const v3<T> p(T(0.1), T(0), T(-0.2));
    for (const auto& light : surface_lights<T>()) {
        int hits = 0;
        for (int i = 0; i < 64; ++i) {
            // Directions over the upper hemisphere, many toward the light above p.
            const T a = T(0.1) * T(i % 8) - T(0.35), b = T(0.1) * T(i / 8) - T(0.35);
            const v3<T> l = glm::normalize(v3<T>(a, T(1), b));
            const auto h = light.intersect(shade::ray<T>{p, l});
            const T pdf = light.pdf_incident(p, l);
            const shade::rgb<T> radiance = light.incident_radiance(p, l);
            if (!h) {
                CHECK(pdf == T(0));
                CHECK(radiance == shade::rgb<T>(0));
                continue;
            }
            ++hits;
            // Bit for bit what the light computes by intersecting again.
            CHECK(light.pdf_incident(p, l, *h) == pdf);
            CHECK(light.radiance(*h, -l) == radiance);
            CHECK(pdf > T(0));
        }
        CHECK(hits > 8);
    }
}

TEST_CASE_TEMPLATE("any_light: lights without a surface are never hit", T, float, double) {
    const std::vector<shade::any_light<T>> lights{shade::point_light<T>(v3<T>(0, 1, 0)),
                                                  shade::directional_light<T>(v3<T>(0, 1, 0)),
                                                  shade::environment_light<T>()};
    for (const auto& light : lights) CHECK(!light.intersect(shade::ray<T>{v3<T>(0), v3<T>(0, 1, 0)}));
}

TEST_CASE_TEMPLATE("any_light: power in watts, by hand", T, float, double) {
    const T pi = shade::pi<T>;
    const auto e = shade::emission<T>::from_physical(shade::rgb<T>(1, 2, 3));
    const T r = 10; // the scene's bounding radius, for the lights at infinity
    // Point: 4 pi I. Rectangle 2 x 3, one-sided: pi L A = 6 pi L. Disk of radius 0.5,
    // two-sided: 2 pi L (pi 0.25). Sphere of radius 2: pi L 4 pi 2^2 = 16 pi^2 L.
    // Directional: E through the scene's disk, pi r^2 E. Environment: every point of the
    // scene's sphere receives pi L, 4 pi r^2 pi L in all.
    const auto near = [](const shade::rgb<T>& a, const shade::rgb<T>& b) {
        return std::abs(a.x - b.x) <= T(1e-5) * std::abs(b.x) && std::abs(a.y - b.y) <= T(1e-5) * std::abs(b.y) &&
               std::abs(a.z - b.z) <= T(1e-5) * std::abs(b.z);
    };
    const shade::rgb<T> L(1, 2, 3);
    CHECK(near(shade::any_light<T>(shade::point_light<T>(v3<T>(0), e)).power(r), 4 * pi * L));
    CHECK(near(shade::any_light<T>(shade::area_light<T>(v3<T>(0), v3<T>(2, 0, 0), v3<T>(0, 3, 0), e)).power(r),
               6 * pi * L));
    CHECK(near(shade::any_light<T>(shade::disk_light<T>(v3<T>(0), v3<T>(0, 0, 1), T(0.5), e, shade::sidedness::two_sided))
                   .power(r),
               2 * pi * (pi * T(0.25)) * L));
    CHECK(near(shade::any_light<T>(shade::sphere_light<T>(v3<T>(0), T(2), e)).power(r), 16 * pi * pi * L));
    CHECK(near(shade::any_light<T>(shade::directional_light<T>(v3<T>(0, 0, 1), e)).power(r), pi * r * r * L));
    CHECK(near(shade::any_light<T>(shade::environment_light<T>(e)).power(r), 4 * pi * r * r * pi * L));
}

TEST_CASE_TEMPLATE("power_light_sampler::from_lights: probabilities follow the lights' power", T, float, double) {
    const T pi = shade::pi<T>;
    // Two point lights of intensity 1 and 3 (white) and a 1 x 1 one-sided rectangle of
    // radiance 2: powers 4 pi, 12 pi and 2 pi, so probabilities 4/18, 12/18 and 2/18.
    const std::vector<shade::any_light<T>> lights{
        shade::point_light<T>(v3<T>(0), shade::emission<T>::from_physical(shade::rgb<T>(1))),
        shade::point_light<T>(v3<T>(1), shade::emission<T>::from_physical(shade::rgb<T>(3))),
        shade::area_light<T>(v3<T>(0), v3<T>(1, 0, 0), v3<T>(0, 1, 0), shade::emission<T>::from_physical(shade::rgb<T>(2)))};
    const auto sampler = shade::power_light_sampler<T>::from_lights(std::span<const shade::any_light<T>>(lights), T(1));
    CHECK(sampler.probability(0) == doctest::Approx(4.0 / 18));
    CHECK(sampler.probability(1) == doctest::Approx(12.0 / 18));
    CHECK(sampler.probability(2) == doctest::Approx(2.0 / 18));
    (void)pi;
}

TEST_CASE_TEMPLATE("triangle_light: area, normal, uniform points and bad vertices", T, float, double) {
    // The right triangle (0,0,0), (2,0,0), (0,3,0): area 3, normal +z.
    const shade::triangle_light<T> tri(v3<T>(0), v3<T>(2, 0, 0), v3<T>(0, 3, 0));
    CHECK(tri.area() == doctest::Approx(3));
    CHECK(tri.normal() == v3<T>(0, 0, 1));
    // Uniform by area: the mean of point_at over a grid of u is the centroid (2/3, 1).
    double mx = 0, my = 0;
    const int n = 64;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const v3<T> x = tri.point_at(shade::vec2<T>((T(i) + T(0.5)) / T(n), (T(j) + T(0.5)) / T(n)));
            CHECK(x.x >= T(0));
            CHECK(x.y >= T(0));
            CHECK(x.x / T(2) + x.y / T(3) <= T(1) + T(1e-6));
            mx += double(x.x) / (n * n);
            my += double(x.y) / (n * n);
        }
    CHECK(mx == doctest::Approx(2.0 / 3).epsilon(1e-3));
    CHECK(my == doctest::Approx(1.0).epsilon(1e-3));
    const auto parameter_of = [](auto make) {
        try {
            make();
        } catch (const shade::invalid_parameter& e) {
            return e.parameter();
        }
        return std::string("(accepted)");
    };
    const T nan = std::numeric_limits<T>::quiet_NaN();
    CHECK(parameter_of([&] { shade::triangle_light<T> t(v3<T>(nan), v3<T>(1, 0, 0), v3<T>(0, 1, 0)); }) == "v0");
    CHECK(parameter_of([&] { shade::triangle_light<T> t(v3<T>(0), v3<T>(1, 0, 0), v3<T>(2, 0, 0)); }) == "v2");
}

TEST_CASE_TEMPLATE("rectangle and disk lights: hits carry a rounding bound that spawned rays clear", T, float, double) {
    // Far from the origin (1e5), where a point's rounding is large, every ray offset off a
    // hit by its p_error (shade::offset_ray_origin) starts strictly on the side it leaves
    // toward: the signed distance from the light's plane, computed in long double from the
    // exact plane, is positive toward the normal's side and negative behind.
    const T far = T(1e5);
    const shade::vec3<T> c(far, T(-far), far);
    const auto e = shade::emission<T>::from_physical(shade::rgb<T>(1));
    const shade::area_light<T> rect(c, shade::vec3<T>(T(0.3), T(0.9), T(0.1)), shade::vec3<T>(T(-0.8), T(0.2), T(0.5)), e);
    const shade::disk_light<T> disk(c, glm::normalize(shade::vec3<T>(T(0.2), T(-1), T(0.4))), T(1), e);
    shade::rng g(9);
    int hits = 0, wrong = 0;
    const auto side = [](const shade::vec3<T>& p, const shade::vec3<T>& q, const shade::vec3<T>& n) {
        return (static_cast<long double>(p.x) - q.x) * n.x + (static_cast<long double>(p.y) - q.y) * n.y +
               (static_cast<long double>(p.z) - q.z) * n.z;
    };
    for (int k = 0; k < 20000; ++k) {
        const shade::vec3<T> o = c + shade::vec3<T>(T(4) * g.uniform<T>() - T(2), T(4) * g.uniform<T>() - T(2),
                                                    T(4) * g.uniform<T>() - T(2));
        const shade::vec3<T> target = c + shade::vec3<T>(g.uniform<T>() - T(0.5), g.uniform<T>() - T(0.5), g.uniform<T>() - T(0.5));
        const shade::ray<T> r{o, glm::normalize(target - o)};
        for (const auto& h : {rect.intersect(r), disk.intersect(r)}) {
            if (!h) continue;
            ++hits;
            const shade::vec3<T> n = h->n;
            const shade::vec3<T> up = shade::offset_ray_origin(h->p, h->p_error, n, n);
            const shade::vec3<T> down = shade::offset_ray_origin(h->p, h->p_error, n, -n);
            // c, the rectangle's corner and the disk's centre, lies on both planes.
            if (!(side(up, c, n) > 0) || !(side(down, c, n) < 0)) ++wrong;
        }
    }
    CHECK(hits > 10000);
    CHECK(wrong == 0);
}
