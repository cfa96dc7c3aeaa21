#include <cmath>

#include <doctest/doctest.h>

#include <shade/brdf/microfacet/masking.hpp>

#include "brdf/microfacet/quadrature.hpp"
#include "brdf/support.hpp"

using namespace brdf_test;
using namespace microfacet_test;
using shade::vec2;

static_assert(shade::masking_for<shade::smith_separable<float>, shade::ggx<float>>);
static_assert(shade::masking_for<shade::smith_separable<double>, shade::beckmann<double>>);
static_assert(shade::masking_for<shade::smith_height_correlated<float>, shade::beckmann<float>>);
static_assert(shade::masking_for<shade::smith_height_correlated<double>, shade::ggx<double>>);
static_assert(!shade::masking_for<shade::smith_height_correlated<double>, shade::ggx<float>>);

namespace {

template <class T>
constexpr T tol = sizeof(T) <= 4 ? T(2e-6) : T(1e-13);

// A distribution with the cosine-only contract, as user code may have written it.
template <class T>
struct cosine_only_distribution {
    using scalar_type = T;
    [[nodiscard]] T D(T n_dot_h) const noexcept { return shade::D_ggx(n_dot_h, T(0.3)); }
    [[nodiscard]] T peak() const noexcept { return T(1) / (shade::pi<T> * T(0.09)); }
};

} // namespace

// The generic Smith terms need Lambda; the V-groove works with anything.
static_assert(shade::microfacet_distribution<cosine_only_distribution<float>>);
static_assert(!shade::sampled_microfacet_distribution<cosine_only_distribution<float>>);
static_assert(!shade::masking_for<shade::smith_separable<float>, cosine_only_distribution<float>>);
static_assert(shade::masking_for<shade::v_groove<float>, cosine_only_distribution<float>>);

TEST_CASE_TEMPLATE("masking: height-correlated and separable Smith, hand values", T, float, double) {
    // GGX alpha = 1, l and v at 60 deg: Lambda = 1/2 each (tan^2 = 3, (-1 + 2)/2).
    // Separable: G1^2 = (2/3)^2 = 4/9. Height-correlated (Heitz 2014, eq. 99):
    // 1/(1 + 1/2 + 1/2) = 1/2.
    const shade::ggx<T> d(T(1));
    const vec3<T> l = local(shade::pi<T> / 3, T(0.2));
    const vec3<T> v = local(shade::pi<T> / 3, T(2.9));
    const vec3<T> h = glm::normalize(l + v);
    const T v_dot_h = glm::dot(v, h);
    CHECK(close(shade::smith_separable<T>::G(d, l, v, h, v_dot_h), T(4) / T(9), T(10) * tol<T>));
    CHECK(close(shade::smith_height_correlated<T>::G(d, l, v, h, v_dot_h), T(0.5), T(10) * tol<T>));
    CHECK(close(shade::smith_ggx<T>::G(d, l, v, h, v_dot_h), T(4) / T(9), T(10) * tol<T>));
    // l = v = n: 1 for every Smith term.
    const vec3<T> n(0, 0, 1);
    CHECK(shade::smith_height_correlated<T>::G(d, n, n, n, T(1)) == T(1));
    CHECK(shade::smith_separable<T>::G(d, n, n, n, T(1)) == T(1));
    // On the horizon: 0 (Lambda = inf). Below the surface: the value of the mirror image
    // (two-sided terms; the side tests are the caller's).
    const vec3<T> horizon(T(0.6), T(0.8), 0);
    CHECK(shade::smith_height_correlated<T>::G(d, horizon, v, h, v_dot_h) == T(0));
    CHECK(shade::smith_separable<T>::G(d, l, horizon, h, v_dot_h) == T(0));
    const vec3<T> below(T(0.6), 0, T(-0.8));
    const vec3<T> above(T(0.6), 0, T(0.8));
    CHECK(shade::smith_height_correlated<T>::G(d, below, v, h, v_dot_h) ==
          shade::smith_height_correlated<T>::G(d, above, v, h, v_dot_h));
    CHECK(shade::smith_separable<T>::G(d, l, below, h, v_dot_h) == shade::smith_separable<T>::G(d, l, above, h, v_dot_h));
}

TEST_CASE_TEMPLATE("masking: height-correlated G2 >= separable G2, equal only without masking", T, float, double) {
    shade::rng random(5);
    for (const auto& parameters : {std::pair{T(0.05), T(0.5)}, std::pair{T(0.3), T(0.3)}, std::pair{T(1), T(2)}}) {
        const auto ax = parameters.first;
        const auto ay = parameters.second;
        const shade::ggx<T> g(ax, ay);
        const shade::beckmann<T> b(ax, ay);
        for (int i = 0; i < 500; ++i) {
            const vec3<T> l = shade::square_to_uniform_hemisphere(vec2<T>(random.uniform<T>(), random.uniform<T>()));
            const vec3<T> v = shade::square_to_uniform_hemisphere(vec2<T>(random.uniform<T>(), random.uniform<T>()));
            if (!(l.z > T(0)) || !(v.z > T(0))) continue;
            const vec3<T> h = glm::normalize(l + v);
            const T vh = glm::dot(v, h);
            // (1 + a)(1 + b) = 1 + a + b + ab >= 1 + a + b.
            CHECK(shade::smith_height_correlated<T>::G(g, l, v, h, vh) >= shade::smith_separable<T>::G(g, l, v, h, vh) * T(1 - 1e-6));
            CHECK(shade::smith_height_correlated<T>::G(b, l, v, h, vh) >= shade::smith_separable<T>::G(b, l, v, h, vh) * T(1 - 1e-6));
        }
        // Strictly greater where both directions are masked.
        const vec3<T> l = local(T(1.3), T(0.3)), v = local(T(1.2), T(2.0));
        const vec3<T> h = glm::normalize(l + v);
        CHECK(shade::smith_height_correlated<T>::G(g, l, v, h, glm::dot(v, h)) >
              shade::smith_separable<T>::G(g, l, v, h, glm::dot(v, h)) * T(1.001));
    }
}

TEST_CASE_TEMPLATE("masking: the local forms equal the cosine forms for isotropic distributions", T, float, double) {
    shade::rng random(9);
    const shade::ggx<T> g(T(0.4));
    const shade::beckmann<T> b(T(0.4));
    for (int i = 0; i < 500; ++i) {
        const vec3<T> l = shade::square_to_uniform_hemisphere(vec2<T>(random.uniform<T>(), random.uniform<T>()));
        const vec3<T> v = shade::square_to_uniform_hemisphere(vec2<T>(random.uniform<T>(), random.uniform<T>()));
        if (!(l.z > T(0)) || !(v.z > T(0))) continue;
        const vec3<T> h = glm::normalize(l + v);
        const T vh = glm::dot(v, h);
        const T rel = sizeof(T) <= 4 ? T(1e-5) : T(1e-12);
        CHECK(close(shade::smith_ggx<T>::G(g, l, v, h, vh), shade::smith_ggx<T>::G(g, l.z, v.z, h.z, vh), rel));
        CHECK(close(shade::smith_beckmann<T>::G(b, l, v, h, vh), shade::smith_beckmann<T>::G(b, l.z, v.z, h.z, vh), T(100) * rel));
        CHECK(shade::v_groove<T>::G(g, l, v, h, vh) == shade::v_groove<T>::G(g, l.z, v.z, h.z, vh));
        // The exact separable Smith-Beckmann is the product of the free exact G1s.
        CHECK(close(shade::smith_separable<T>::G(b, l, v, h, vh),
                    shade::G1_smith_beckmann_exact(l.z, T(0.4)) * shade::G1_smith_beckmann_exact(v.z, T(0.4)), T(100) * rel));
    }
}

TEST_CASE("masking: the anisotropic rational Smith-Beckmann uses the projected slope") {
    // Along t the projected slope is m_x, along b m_y: the isotropic rational G1 with that m.
    const shade::beckmann<double> b(0.2, 0.8);
    const vec3<double> along_t = local(1.2, 0.0), along_b = local(1.2, shade::pi<double> / 2), n(0, 0, 1);
    CHECK(shade::smith_beckmann<double>::G(b, along_t, n, n, 1.0) == doctest::Approx(shade::G1_smith_beckmann(std::cos(1.2), 0.2)).epsilon(1e-12));
    CHECK(shade::smith_beckmann<double>::G(b, along_b, n, n, 1.0) == doctest::Approx(shade::G1_smith_beckmann(std::cos(1.2), 0.8)).epsilon(1e-12));
}
