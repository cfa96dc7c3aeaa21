// shade::emitter as the primary light contract, and shade::classic_light /
// shade::classic_sample, which give any emitter (here two written in this file, with no
// classic member) the classic mode.

#include <cmath>
#include <numbers>
#include <optional>
#include <tuple>
#include <vector>

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/brdf/lambert.hpp>
#include <shade/core/sampling.hpp>
#include <shade/light/any_light.hpp>
#include <shade/light/classic_light.hpp>
#include <shade/light/environment_map.hpp>
#include <shade/shading/sum_over_lights.hpp>

namespace {

template <class T>
using v3 = shade::vec3<T>;
template <class T>
using v2 = shade::vec2<T>;
template <class T>
using rgb = shade::rgb<T>;

constexpr double pi = std::numbers::pi;

// A user's isotropic point source of radiant intensity I (W/sr), written only in
// physical units: the irradiance I / r^2 at normal incidence, a delta light.
template <class T>
struct beacon {
    using scalar_type = T;
    v3<T> position;
    rgb<T> I;

    std::optional<shade::incident_sample<T>> sample_incident(const v3<T>& p, const v2<T>&) const {
        const v3<T> d = position - p;
        const T r = glm::length(d);
        shade::incident_sample<T> s;
        s.l = d / r;
        s.distance = r;
        s.radiance = I / (r * r);
        s.pdf = T(1);
        s.delta = true;
        return s;
    }
    std::optional<shade::incident_sample<T>> sample_incident(const shade::light_sample_context<T>& ctx,
                                                             const v2<T>& u) const {
        return sample_incident(ctx.p, u);
    }
    T pdf_incident(const v3<T>&, const v3<T>&) const { return T(0); }
    T pdf_incident(const shade::light_sample_context<T>&, const v3<T>&) const { return T(0); }
    rgb<T> incident_radiance(const v3<T>&, const v3<T>&) const { return rgb<T>(0); }
    bool is_delta() const { return true; }
    rgb<T> power(T) const { return T(4 * pi) * I; }
};

// A user's uniform sky of radiance L (W/(m^2 sr)), sampled uniformly over the sphere
// (density 1 / (4 pi)).
template <class T>
struct sky {
    using scalar_type = T;
    rgb<T> L;

    std::optional<shade::incident_sample<T>> sample_incident(const v3<T>&, const v2<T>& u) const {
        shade::incident_sample<T> s;
        s.l = shade::square_to_uniform_sphere(u);
        s.radiance = L;
        s.pdf = T(1 / (4 * pi));
        return s;
    }
    std::optional<shade::incident_sample<T>> sample_incident(const shade::light_sample_context<T>& ctx,
                                                             const v2<T>& u) const {
        return sample_incident(ctx.p, u);
    }
    T pdf_incident(const v3<T>&, const v3<T>&) const { return T(1 / (4 * pi)); }
    T pdf_incident(const shade::light_sample_context<T>&, const v3<T>&) const { return T(1 / (4 * pi)); }
    rgb<T> incident_radiance(const v3<T>&, const v3<T>&) const { return L; }
    bool is_delta() const { return false; }
    rgb<T> power(T r) const { return T(4 * pi * pi) * r * r * L; }
};

// A light with the classic members only.
template <class T>
struct classic_only {
    using scalar_type = T;
    shade::light_sample<T> sample(const v3<T>&, const v2<T>&) const { return {}; }
    bool is_delta() const { return true; }
};

// An emitter but for power(scene_radius).
template <class T>
struct without_power : sky<T> {
    void power(T) const {}
};

template <class T>
bool near(const rgb<T>& a, const rgb<T>& b, double tolerance) {
    for (int c = 0; c < 3; ++c)
        if (!(std::fabs(double(a[c]) - double(b[c])) <= tolerance * (1 + std::fabs(double(b[c]))))) return false;
    return true;
}

} // namespace

TEST_CASE_TEMPLATE("shade::emitter needs the physical members only; shade::light the classic ones", T, float,
                   double) {
    static_assert(shade::emitter<beacon<T>>);
    static_assert(shade::emitter<sky<T>>);
    static_assert(!shade::light<beacon<T>>);
    static_assert(!shade::emitter<classic_only<T>>);
    static_assert(shade::light<classic_only<T>>);
    static_assert(!shade::emitter<without_power<T>>);
    static_assert(!shade::emitter<int>);
    // Every shade light is both, and environment_map_light and any_light too.
    static_assert(shade::emitter<shade::point_light<T>> && shade::light<shade::point_light<T>>);
    static_assert(shade::emitter<shade::spot_light<T>> && shade::light<shade::spot_light<T>>);
    static_assert(shade::emitter<shade::directional_light<T>> && shade::light<shade::directional_light<T>>);
    static_assert(shade::emitter<shade::area_light<T>> && shade::light<shade::area_light<T>>);
    static_assert(shade::emitter<shade::disk_light<T>> && shade::light<shade::disk_light<T>>);
    static_assert(shade::emitter<shade::sphere_light<T>> && shade::light<shade::sphere_light<T>>);
    static_assert(shade::emitter<shade::triangle_light<T>> && shade::light<shade::triangle_light<T>>);
    static_assert(shade::emitter<shade::environment_light<T>> && shade::light<shade::environment_light<T>>);
    static_assert(shade::emitter<shade::environment_map_light<T>> && shade::light<shade::environment_map_light<T>>);
    static_assert(shade::emitter<shade::any_light<T>> && shade::light<shade::any_light<T>>);
    // The adapter makes a classic light of an emitter, which stays an emitter.
    static_assert(shade::light<shade::classic_light<beacon<T>>> && shade::emitter<shade::classic_light<beacon<T>>>);
    static_assert(shade::light<shade::classic_light<sky<T>>> && shade::emitter<shade::classic_light<sky<T>>>);
}

TEST_CASE_TEMPLATE("classic_light gives a user's delta emitter the classic colours E / pi", T, float, double) {
    // I = pi (1, 2, 3) W/sr at 2 m: E = I / 4, classic colour E / pi = (1, 2, 3) / 4.
    const beacon<T> b{v3<T>(0, 0, 2), T(pi) * rgb<T>(1, 2, 3)};
    const shade::classic_light<beacon<T>> plain(b);
    CHECK(plain.is_delta());
    const shade::light_sample<T> s = plain.sample(v3<T>(0), v2<T>(T(0.5)));
    CHECK(s.l == v3<T>(0, 0, 1));
    CHECK(s.distance == T(2));
    CHECK(near(s.diffuse, rgb<T>(0.25, 0.5, 0.75), 1e-6));
    CHECK(near(s.specular, rgb<T>(0.25, 0.5, 0.75), 1e-6));
    CHECK(s.ambient == rgb<T>(0));
    // Tints multiply per channel; the ambient colour is added as it is.
    const shade::classic_light<beacon<T>> tinted(b, {rgb<T>(T(0.1)), rgb<T>(1, 0, 1), rgb<T>(T(0.5))});
    const shade::light_sample<T> t = tinted.sample(v3<T>(0), v2<T>(T(0.5)));
    CHECK(near(t.diffuse, rgb<T>(0.25, 0, 0.75), 1e-6));
    CHECK(near(t.specular, rgb<T>(0.125, 0.25, 0.375), 1e-6));
    CHECK(t.ambient == rgb<T>(T(0.1)));
    // Its physical members are the emitter's.
    CHECK(tinted.sample_incident(v3<T>(0), v2<T>(T(0.5)))->radiance == b.sample_incident(v3<T>(0), v2<T>(T(0.5)))->radiance);
    CHECK(tinted.power(T(1)) == T(4 * pi) * b.I);
    CHECK(tinted.pdf_incident(v3<T>(0), v3<T>(0, 0, 1)) == T(0));
    // The same as shade's own point light of that intensity (its classic sample:
    // intensity x colour / r^2 with the emission from_intensity gives, colour I / pi).
    const auto shade_bulb = shade::point_light<T>::from_intensity(v3<T>(0, 0, 2), T(pi) * rgb<T>(1, 2, 3));
    CHECK(near(shade_bulb.sample(v3<T>(0), v2<T>(T(0.5))).diffuse, s.diffuse, 1e-6));
    // Bad colours are named.
    const auto parameter_of = [&](const shade::classic_colours<T>& c) -> std::string {
        try {
            const shade::classic_light<beacon<T>> l(b, c);
        } catch (const shade::invalid_parameter& e) {
            return e.parameter();
        }
        return "(accepted)";
    };
    CHECK(parameter_of({rgb<T>(-1), rgb<T>(1), rgb<T>(1)}) == "ambient");
    CHECK(parameter_of({rgb<T>(0), rgb<T>(T(std::nan(""))), rgb<T>(1)}) == "diffuse");
    CHECK(parameter_of({rgb<T>(0), rgb<T>(1), rgb<T>(-1)}) == "specular");
}

TEST_CASE_TEMPLATE("classic_light of a user's sky: a Lambertian surface reflects k_d L, as physically", T, float,
                   double) {
    // Each classic sample has colour L / (pi / (4 pi)) = 4 L along a uniform direction;
    // lit Lambert gives k_d x 4 L x max(n.l, 0), and max(n.l, 0) averages 1/4 over the
    // sphere: k_d L, which is also the radiance a Lambertian surface reflects under a
    // uniform sky (k_d / pi x the irradiance pi L).
    const shade::classic_light<sky<T>> light(sky<T>{rgb<T>(1, 2, 3)});
    CHECK_FALSE(light.is_delta());
    const auto at = shade::surface_point<T>::at(v3<T>(0), v3<T>(0, 0, 1));
    const shade::lambert<T> brdf(rgb<T>(T(0.5)));
    const rgb<T> out = shade::sum_over_lights(brdf, at, v3<T>(0, 0, 1), std::tuple(light), shade::always_visible{}, 64);
    CHECK(near(out, rgb<T>(0.5, 1, 1.5), 2e-3));
}

TEST_CASE_TEMPLATE("classic_sample of shade's lights is their own classic sample", T, float, double) {
    // With equal diffuse and specular colours and the ambient colour passed as
    // intensity x ambient, classic_sample over the physical sample equals each light's own
    // sample(p, u) up to rounding (their units agree: physical() = pi x intensity x diffuse).
    shade::emission<T> e;
    e.intensity = T(2);
    e.ambient = rgb<T>(T(0.05));
    e.diffuse = rgb<T>(1, T(0.5), T(0.25));
    e.specular = e.diffuse;
    const shade::classic_colours<T> c{e.intensity * e.ambient, rgb<T>(1), rgb<T>(1)};
    const std::vector<shade::any_light<T>> lights = {
        shade::point_light<T>(v3<T>(0, 1, 3), e),
        shade::spot_light<T>(v3<T>(0, 0, 3), v3<T>(0, 0.2, -1), T(0.2), T(0.6), e),
        shade::directional_light<T>(v3<T>(1, 2, 3), e),
        shade::area_light<T>(v3<T>(-1, -1, 2), v3<T>(2, 0, 0), v3<T>(0, 2, 0), e, shade::sidedness::two_sided),
        shade::disk_light<T>(v3<T>(0, 0, 2), v3<T>(0, 0, -1), T(1), e),
        shade::sphere_light<T>(v3<T>(0, 0, 3), T(1), e),
        shade::triangle_light<T>(v3<T>(-1, -1, 2), v3<T>(0, 1, 2), v3<T>(1, -1, 2), e, shade::sidedness::two_sided),
        shade::environment_light<T>(e)};
    const v3<T> p(T(0.1), T(-0.2), 0);
    for (const auto& light : lights)
        for (int k = 0; k < 16; ++k) {
            const v2<T> u((T(k % 4) + T(0.3)) / 4, (T(k / 4) + T(0.6)) / 4);
            const shade::light_sample<T> own = light.sample(p, u);
            const shade::light_sample<T> adapted = shade::classic_sample(light, c, p, u);
            CHECK(near(adapted.diffuse, own.diffuse, 1e-5));
            CHECK(near(adapted.specular, own.specular, 1e-5));
            CHECK(adapted.ambient == own.ambient);
            if (own.diffuse != rgb<T>(0)) {
                CHECK(glm::length(adapted.l - own.l) < T(1e-5));
                if (std::isinf(own.distance))
                    CHECK(adapted.distance == own.distance);
                else
                    CHECK(double(adapted.distance) == doctest::Approx(double(own.distance)).epsilon(1e-5));
            }
        }
    // An environment map's classic sample is the adapter's with the default colours.
    const std::vector<rgb<T>> texels = {rgb<T>(1), rgb<T>(2, 1, 0), rgb<T>(0), rgb<T>(T(0.5))};
    const shade::environment_map_light<T> map(2, 2, texels);
    for (int k = 0; k < 16; ++k) {
        const v2<T> u((T(k % 4) + T(0.5)) / 4, (T(k / 4) + T(0.5)) / 4);
        const shade::light_sample<T> own = map.sample(p, u);
        const shade::light_sample<T> adapted = shade::classic_sample(map, shade::classic_colours<T>{}, p, u);
        CHECK(adapted.diffuse == own.diffuse);
        CHECK(adapted.l == own.l);
    }
}
