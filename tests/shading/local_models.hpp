#pragma once
// Tiny reflection models and shaders for the shading tests. They are deliberately trivial
// so that expected values can be derived by hand; the real models live in shade/brdf.

#include <cmath>

#include <glm/geometric.hpp>

#include <shade/core/math.hpp>
#include <shade/core/surface_point.hpp>
#include <shade/core/types.hpp>
#include <shade/light/light_sample.hpp>

namespace test_models {

/// Lambert: f = k_d / pi above the surface, 0 below (Lambert 1760).
template <class T>
struct lambert {
    using scalar_type = T;
    shade::rgb<T> k_d{1, 1, 1};

    [[nodiscard]] shade::rgb<T> f(const shade::vec3<T>& l, const shade::vec3<T>& v,
                                  const shade::surface_point<T>& at) const {
        if (glm::dot(at.n(), l) <= T(0) || glm::dot(at.n(), v) <= T(0)) return shade::rgb<T>(0);
        return k_d * shade::inv_pi<T>;
    }
};

/// A split BRDF: diffuse part k_d / pi, specular part a constant k_s (not physical; only
/// there to see which light colour lights which part).
template <class T>
struct split_constant {
    using scalar_type = T;
    shade::rgb<T> k_d{1, 1, 1};
    shade::rgb<T> k_s{0, 0, 0};

    [[nodiscard]] bool above(const shade::vec3<T>& l, const shade::vec3<T>& v,
                             const shade::surface_point<T>& at) const {
        return glm::dot(at.n(), l) > T(0) && glm::dot(at.n(), v) > T(0);
    }
    [[nodiscard]] shade::rgb<T> f_diffuse(const shade::vec3<T>& l, const shade::vec3<T>& v,
                                          const shade::surface_point<T>& at) const {
        return above(l, v, at) ? k_d * shade::inv_pi<T> : shade::rgb<T>(0);
    }
    [[nodiscard]] shade::rgb<T> f_specular(const shade::vec3<T>& l, const shade::vec3<T>& v,
                                           const shade::surface_point<T>& at) const {
        return above(l, v, at) ? k_s : shade::rgb<T>(0);
    }
    [[nodiscard]] shade::rgb<T> f(const shade::vec3<T>& l, const shade::vec3<T>& v,
                                  const shade::surface_point<T>& at) const {
        return f_diffuse(l, v, at) + f_specular(l, v, at);
    }
};

/// A shader that returns a fixed colour, whatever the light: identifies which child of a
/// combinator was used.
template <class T>
struct constant_shader {
    using scalar_type = T;
    shade::rgb<T> colour{0, 0, 0};

    [[nodiscard]] shade::rgb<T> shade(const shade::surface_point<T>& at, const shade::vec3<T>& v,
                                      const shade::light_sample<T>& s) const {
        (void)at;
        (void)v;
        (void)s;
        return colour;
    }
};

/// True when every channel of a and b differs by at most tol.
template <class T>
[[nodiscard]] bool near(const shade::vec3<T>& a, const shade::vec3<T>& b, T tol) {
    return std::abs(a.x - b.x) <= tol && std::abs(a.y - b.y) <= tol && std::abs(a.z - b.z) <= tol;
}

} // namespace test_models
