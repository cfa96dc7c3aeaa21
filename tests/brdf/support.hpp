#pragma once
// Shared helpers of the BRDF tests: surface points, the degenerate direction pairs every
// model must survive, and the checks "finite and >= 0" and "zero below the surface".

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <shade/core/frame.hpp>

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <shade/brdf/brdf.hpp>
#include <shade/check/directions.hpp>
#include <shade/core/random.hpp>
#include <shade/core/sampling.hpp>
#include <shade/core/surface_point.hpp>

namespace brdf_test {

using shade::rgb;
using shade::vec3;

/// A surface point whose frame is the identity (n = +z, t = +x, b = +y), so hand
/// derivations can be written in local coordinates.
template <class T>
shade::surface_point<T> flat() {
    return shade::surface_point<T>::at({0, 0, 0}, {0, 0, 1});
}

/// A surface point with a tilted normal and a tangent frame that is not axis-aligned, to
/// catch code that assumes n = +z.
template <class T>
shade::surface_point<T> tilted() {
    shade::surface_point<T> at;
    at.p = vec3<T>(1, 2, 3);
    at.shading = shade::frame<T>::from_normal_tangent(vec3<T>(T(0.3), T(-0.5), T(0.8)),
                                                      vec3<T>(1, T(0.2), 0));
    return at;
}

/// The unit direction with polar angle theta (from n) and azimuth phi (from t) at `at`.
template <class T>
vec3<T> direction(const shade::surface_point<T>& at, T theta, T phi) {
    return glm::normalize(at.shading.to_world(
        vec3<T>(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta))));
}

/// A pair of unit directions with a name for CAPTURE.
template <class T>
struct named_pair {
    std::string name;
    vec3<T> l;
    vec3<T> v;
};

/// The degenerate configurations every model must survive, around `at`, in world space: grazing
/// (n·l = 0 and n·v = 0, exactly on the horizon in the local frame), l = v, l = -v,
/// l = n, h parallel to n (mirror pairs), and near-grazing pairs in both orders. Some have
/// a direction on or below the horizon; those must give exactly 0.
template <class T>
std::vector<named_pair<T>> degenerate_pairs(const shade::surface_point<T>& at) {
    const auto w = [&](T x, T y, T z) { return glm::normalize(at.shading.to_world(vec3<T>(x, y, z))); };
    const vec3<T> n = at.n();
    const T g = sizeof(T) <= 4 ? T(1e-4) : T(1e-8); // near grazing: cos(theta) ~ g
    std::vector<named_pair<T>> p = {
        {"l = v = n", n, n},
        {"l grazing exactly, v = n", at.shading.t, n},
        {"v grazing exactly, l = n", n, at.shading.b},
        {"both grazing exactly", at.shading.t, -at.shading.t},
        {"l = v tilted", w(1, 1, 1), w(1, 1, 1)},
        {"l = v near grazing", w(1, 0, g), w(1, 0, g)},
        {"l = -v", w(1, 0, 1), -w(1, 0, 1)},
        {"l = -v near grazing", w(1, 0, g), -w(1, 0, g)},
        {"l = n, v tilted", n, w(1, 2, 1)},
        {"l tilted, v = n", w(-2, 1, 1), n},
        {"l = n, v near grazing", n, w(0, 1, g)},
        {"l near grazing, v = n", w(1, 0, g), n},
        {"mirror (h = n) at 45 deg", w(1, 0, 1), w(-1, 0, 1)},
        {"mirror (h = n) near grazing", w(1, 0, g), w(-1, 0, g)},
        {"opposite azimuths near grazing", w(0, 1, g), w(0, -1, g)},
        {"same azimuth, both near grazing", w(1, 0, g), w(1, T(1e-3), g)},
        {"l near grazing, v tilted", w(1, 0, g), w(T(0.2), T(0.3), 1)},
    };
    return p;
}

/// `count` pairs with both directions above the surface: check::hemisphere_pairs (hard
/// cases first, then uniform random).
template <class T>
std::vector<named_pair<T>> random_pairs(const shade::surface_point<T>& at, std::size_t count,
                                        std::uint64_t seed = 7) {
    std::vector<named_pair<T>> out;
    for (const auto& [l, v] : shade::check::hemisphere_pairs(at, count, seed))
        out.push_back({"random", l, v});
    return out;
}

/// True when every channel of c is finite and >= 0.
template <class T>
bool finite_non_negative(const rgb<T>& c) {
    return std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z) && c.x >= T(0) &&
           c.y >= T(0) && c.z >= T(0);
}

/// Checks that f (and f_diffuse, f_specular when present) is finite and >= 0 on every
/// degenerate pair and on `random` random pairs.
template <shade::brdf B>
void check_finite_non_negative(const B& model, const shade::surface_point<shade::scalar_of<B>>& at,
                               std::size_t random = 2000) {
    using T = shade::scalar_of<B>;
    auto pairs = degenerate_pairs(at);
    for (auto& p : random_pairs(at, random)) pairs.push_back(p);
    for (const auto& p : pairs) {
        CAPTURE(p.name);
        const rgb<T> f = model.f(p.l, p.v, at);
        CAPTURE(f.x);
        CAPTURE(f.y);
        CAPTURE(f.z);
        CHECK(finite_non_negative(f));
        if constexpr (shade::split_brdf<B>) {
            CHECK(finite_non_negative(model.f_diffuse(p.l, p.v, at)));
            CHECK(finite_non_negative(model.f_specular(p.l, p.v, at)));
        }
    }
}

/// Checks f == 0 whenever l or v is on or below the horizon: random directions with
/// n·w <= 0 paired with random directions above, and the exact horizon.
template <shade::brdf B>
void check_zero_below(const B& model, const shade::surface_point<shade::scalar_of<B>>& at) {
    using T = shade::scalar_of<B>;
    shade::rng random(11);
    const rgb<T> zero(0);
    for (int i = 0; i < 500; ++i) {
        const vec3<T> up = direction(at, T(1.5) * random.uniform<T>(), T(6.28) * random.uniform<T>());
        // theta in (pi/2, pi]: strictly below the horizon.
        const vec3<T> down =
            direction(at, T(1.5708) + T(1.5707) * random.uniform<T>(), T(6.28) * random.uniform<T>());
        CHECK(model.f(up, down, at) == zero);
        CHECK(model.f(down, up, at) == zero);
        CHECK(model.f(down, down, at) == zero);
    }
    CHECK(model.f(-at.n(), at.n(), at) == zero);
    CHECK(model.f(at.n(), -at.n(), at) == zero);
    // On the horizon (n·w = 0 exactly for the tangent of an orthonormal frame up to
    // rounding; the frame's t and b are orthogonal to n to within an ulp or two, and a
    // direction not strictly above the surface must give 0 either way).
    if (glm::dot(at.n(), at.shading.t) <= T(0)) CHECK(model.f(at.shading.t, at.n(), at) == zero);
    if (glm::dot(at.n(), at.shading.b) <= T(0)) CHECK(model.f(at.n(), at.shading.b, at) == zero);
}

/// |a - b| <= rel * max(|a|, |b|) per channel.
template <class T>
bool close(const rgb<T>& a, const rgb<T>& b, T rel) {
    for (int i = 0; i < 3; ++i) {
        const T scale = std::max(std::abs(a[i]), std::abs(b[i]));
        if (!(std::abs(a[i] - b[i]) <= rel * scale)) return false;
    }
    return true;
}

/// |a - b| <= rel * max(|a|, |b|).
template <class T>
bool close(T a, T b, T rel) {
    return std::abs(a - b) <= rel * std::max(std::abs(a), std::abs(b));
}

/// Checks that the exception thrown by `make` is shade::invalid_parameter naming `name`.
template <class F>
void check_throws_naming(F&& make, const std::string& name) {
    CAPTURE(name);
    bool threw = false;
    try {
        make();
    } catch (const shade::invalid_parameter& e) {
        threw = true;
        CHECK(e.parameter() == name);
        CHECK(std::string(e.what()).find("'" + name + "'") != std::string::npos);
    }
    CHECK(threw);
}

// ---- narrow lobes at shininess 10^4 (tests/brdf/test_phong.cpp, test_blinn_phong.cpp) ----

/// The integral of model.pdf(., v, at) over the cap of half-angle theta_max about the unit
/// axis a (double), by the composite midpoint rule in (theta, phi) about a with n_theta x
/// n_phi points. For narrow lobes about a (the tests that use it bound its error).
template <class B>
double pdf_over_cap(const B& model, const vec3<shade::scalar_of<B>>& v,
                    const shade::surface_point<shade::scalar_of<B>>& at, const glm::dvec3& a, double theta_max,
                    int n_theta = 2000, int n_phi = 32) {
    using T = shade::scalar_of<B>;
    const shade::frame<double> about = shade::frame<double>::from_normal(a);
    const double d_theta = theta_max / n_theta;
    const double d_phi = 2 * 3.141592653589793 / n_phi;
    double sum = 0;
    for (int i = 0; i < n_theta; ++i) {
        const double theta = (i + 0.5) * d_theta;
        double ring = 0;
        for (int j = 0; j < n_phi; ++j) {
            const double phi = (j + 0.5) * d_phi;
            const glm::dvec3 w = about.to_world(glm::dvec3(std::sin(theta) * std::cos(phi),
                                                           std::sin(theta) * std::sin(phi), std::cos(theta)));
            // w rounded to T: each component to nearest, so l is unit only to within rounding,
            // as every direction of T is, without the one-sided bias a renormalisation in T
            // adds.
            ring += double(model.pdf(vec3<T>(w), v, at));
        }
        sum += ring * std::sin(theta) * d_theta * d_phi;
    }
    return sum;
}

/// A normal n and the view v along it: v a vector of T that is unit to far better than an
/// ulp (so that its own rounding plays no part), n = v or v with its z one ulp longer or
/// shorter.
template <class T>
struct normal_and_view {
    vec3<T> n, v;
};

/// Normals one ulp (of a component) off unit length, and exactly unit ones as controls,
/// each with the view along it (normal_and_view).
template <class T>
std::vector<normal_and_view<T>> normals_off_unit_length() {
    // Tilted: among the vectors of T within 3 ulps (in each component) of
    // normalize(0.3, -0.5, 0.8), the one whose length is nearest 1.
    const vec3<T> guess = glm::normalize(vec3<T>(T(0.3), T(-0.5), T(0.8)));
    const auto step = [](T x, int k) {
        for (; k > 0; --k) x = std::nextafter(x, T(2));
        for (; k < 0; ++k) x = std::nextafter(x, T(-2));
        return x;
    };
    vec3<T> tilted = guess;
    for (int i = -3; i <= 3; ++i)
        for (int j = -3; j <= 3; ++j)
            for (int k = -3; k <= 3; ++k) {
                const vec3<T> w(step(guess.x, i), step(guess.y, j), step(guess.z, k));
                if (std::abs(glm::length(glm::dvec3(w)) - 1) < std::abs(glm::length(glm::dvec3(tilted)) - 1))
                    tilted = w;
            }
    const vec3<T> z(0, 0, 1);
    return {{z, z},                                                          // exactly unit
            {vec3<T>(0, 0, std::nextafter(T(1), T(2))), z},                  // |n| = 1 + eps
            {vec3<T>(0, 0, std::nextafter(T(1), T(0))), z},                  // |n| = 1 - eps/2
            {tilted, tilted},                                                // unit to ~1e-10
            {vec3<T>(tilted.x, tilted.y, std::nextafter(tilted.z, T(2))), tilted}, // longer
            {vec3<T>(tilted.x, tilted.y, std::nextafter(tilted.z, T(0))), tilted}}; // shorter
}

} // namespace brdf_test
