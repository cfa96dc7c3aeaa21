// The two-sided microfacet terms (shade/brdf/microfacet/distribution.hpp, header comment):
// D(m) = D(-m), Lambda and G1 of a direction equal to its mirror image's, G1(w, m) zero for
// microfacets facing away from w (Walter et al. 2007, eq. 7), and D_visible still confined
// to the normals above the surface.

#include <cmath>

#include <doctest/doctest.h>

#include <shade/brdf/microfacet/masking.hpp>
#include <shade/core/random.hpp>
#include <shade/core/sampling.hpp>

#include "brdf/microfacet/quadrature.hpp"
#include "brdf/support.hpp"

using namespace brdf_test;
using namespace microfacet_test;
using shade::vec2;

namespace {

template <class T>
vec3<T> mirrored(const vec3<T>& w) {
    return vec3<T>(w.x, w.y, -w.z);
}

template <class T>
vec3<T> random_direction(shade::rng& random) {
    return shade::square_to_uniform_sphere(vec2<T>(random.uniform<T>(), random.uniform<T>()));
}

// D, Lambda and G1 of the mirror image, to the last bit (w_z enters squared or as |w_z|, and
// negation is exact), for directions and normals all over the sphere.
template <class X>
void expect_mirror_symmetric(const X& d) {
    using T = shade::scalar_of<X>;
    shade::rng random(21);
    for (int i = 0; i < 2000; ++i) {
        const vec3<T> w = random_direction<T>(random);
        CHECK(d.D(w) == d.D(-w));
        CHECK(d.D(w) == d.D(mirrored(w)));
        CHECK(d.Lambda(w) == d.Lambda(mirrored(w)));
        CHECK(d.G1(w) == d.G1(mirrored(w)));
        CHECK(d.D(w.z) == d.D(-w.z));
    }
    // On the horizon: D = 0 for a normal, Lambda = inf and G1 = 0 for a direction.
    const vec3<T> horizon(T(0.6), T(0.8), 0);
    CHECK(d.D(horizon) == T(0));
    CHECK(d.D(T(0)) == T(0));
    CHECK(d.Lambda(horizon) == shade::infinity<T>);
    CHECK(d.G1(horizon) == T(0));
}

} // namespace

TEST_CASE_TEMPLATE("two-sided terms: D(m) = D(-m), Lambda and G1 of the mirror image", T, float, double) {
    expect_mirror_symmetric(shade::ggx<T>(T(0.3)));
    expect_mirror_symmetric(shade::ggx<T>(T(0.05), T(0.7)));
    expect_mirror_symmetric(shade::beckmann<T>(T(0.4)));
    expect_mirror_symmetric(shade::beckmann<T>(T(0.6), T(0.1)));
    // The free cosine forms likewise.
    for (const T c : {T(0.1), T(0.5), T(0.99), T(1)}) {
        CHECK(shade::D_ggx(-c, T(0.3)) == shade::D_ggx(c, T(0.3)));
        CHECK(shade::D_beckmann(-c, T(0.3)) == shade::D_beckmann(c, T(0.3)));
        CHECK(shade::G1_smith_ggx(-c, T(0.3)) == shade::G1_smith_ggx(c, T(0.3)));
        CHECK(shade::G1_smith_beckmann(-c, T(0.3)) == shade::G1_smith_beckmann(c, T(0.3)));
        CHECK(shade::G1_smith_beckmann_exact(-c, T(0.3)) == shade::G1_smith_beckmann_exact(c, T(0.3)));
    }
    CHECK(shade::G1_smith_ggx(T(0), T(0.3)) == T(0));
    CHECK(shade::G1_smith_beckmann(T(-0.0), T(0.3)) == T(0));
}

TEST_CASE_TEMPLATE("two-sided terms: hand values below the surface", T, float, double) {
    // GGX alpha = 1, w 60 degrees from -n: tan^2 = 3, Lambda = (-1 + sqrt(1 + 3))/2 = 1/2
    // (Heitz 2014, eq. 86, with |w_z|), G1 = 2/3. D at m = -n: 1/(pi alpha^2) = 1/pi
    // (Walter et al. 2007, eq. 33, at theta_m = 0 of the mirrored normal).
    const shade::ggx<T> d(T(1));
    const vec3<T> w = mirrored(local(shade::pi<T> / 3, T(0.4)));
    CHECK(close(d.Lambda(w), T(0.5), T(1e-5)));
    CHECK(close(d.G1(w), T(2) / T(3), T(1e-5)));
    CHECK(close(d.D(vec3<T>(0, 0, -1)), T(1) / shade::pi<T>, T(1e-6)));
    // Beckmann m = 1, w 45 degrees below: a = |cos| / (m sin) = 1, Lambda = 0.02512727083000614
    // (tests/brdf/microfacet/test_beckmann.cpp, the value above the surface).
    const shade::beckmann<T> b(T(1));
    CHECK(close(b.Lambda(mirrored(local(shade::pi<T> / 4, T(0)))), T(0.02512727083000614), sizeof(T) <= 4 ? T(1e-4) : T(1e-12)));
}

TEST_CASE_TEMPLATE("two-sided terms: G1(w, m) is zero for microfacets facing away from w", T, float, double) {
    const shade::ggx<T> g(T(0.4), T(0.2));
    const shade::beckmann<T> b(T(0.3));
    shade::rng random(8);
    int seen = 0, hidden = 0;
    for (int i = 0; i < 4000; ++i) {
        const vec3<T> w = random_direction<T>(random);
        const vec3<T> m = random_direction<T>(random);
        const T w_dot_m = glm::dot(w, m);
        // chi+((w·m)/(w·n)): the microfacet is seen from w when w·m and w·n share a sign.
        const bool facing = (w_dot_m > 0 && w.z > 0) || (w_dot_m < 0 && w.z < 0);
        CHECK(g.G1(w, m) == (facing ? g.G1(w) : T(0)));
        CHECK(b.G1(w, m) == (facing ? b.G1(w) : T(0)));
        // The configuration mirrored below the surface, its normal turned back to n's side
        // (-mirrored(m)): the same value.
        CHECK(g.G1(mirrored(w), -mirrored(m)) == g.G1(w, m));
        (facing ? seen : hidden) += 1;
    }
    CHECK(seen > 1000);
    CHECK(hidden > 1000);
    // The cases by hand, w = (sin 60, 0, cos 60) above the surface and the normal
    // away = (-1, 0, 0.2)/|.| on n's side: w·away = (-0.866 + 0.1)/1.02 < 0, its front
    // faces away from w: 0. Seen from below along w' = (sin 60, 0, -cos 60), the same
    // normal's back, -away, faces w' (w'·away = (-0.866 - 0.1)/1.02 < 0, like w'·n): seen,
    // G1(w') = G1(w). The mirrored configuration of (w, away), (w', -mirrored(away)), is
    // hidden like it: 0.
    const vec3<T> w = local(shade::pi<T> / 3, T(0));
    const vec3<T> away = glm::normalize(vec3<T>(-1, 0, T(0.2)));
    CHECK(glm::dot(w, away) < 0);
    CHECK(g.G1(w, away) == T(0));
    CHECK(glm::dot(mirrored(w), away) < 0);
    CHECK(g.G1(mirrored(w), away) == g.G1(w));
    CHECK(g.G1(w) > T(0));
    CHECK(g.G1(mirrored(w), -mirrored(away)) == T(0));
    const vec3<T> low = glm::normalize(vec3<T>(1, 0, T(-0.2)));
    CHECK(glm::dot(w, low) > 0);
    CHECK(g.G1(w, low) == g.G1(w));
    CHECK(g.G1(w, low) > T(0));
    // w on the horizon sees nothing.
    CHECK(g.G1(vec3<T>(1, 0, 0), vec3<T>(0, 0, 1)) == T(0));
}

TEST_CASE_TEMPLATE("two-sided terms: the Smith G2 of a pair mirrored below equals the pair's", T, float, double) {
    const shade::ggx<T> d(T(0.3), T(0.6));
    shade::rng random(4);
    for (int i = 0; i < 1000; ++i) {
        vec3<T> l = random_direction<T>(random);
        vec3<T> v = random_direction<T>(random);
        l.z = std::abs(l.z);
        v.z = std::abs(v.z);
        const vec3<T> h = glm::normalize(l + v);
        const T v_dot_h = glm::dot(v, h);
        CHECK(shade::smith_height_correlated<T>::G(d, mirrored(l), mirrored(v), -h, v_dot_h) ==
              shade::smith_height_correlated<T>::G(d, l, v, h, v_dot_h));
        CHECK(shade::smith_separable<T>::G(d, mirrored(l), mirrored(v), -h, v_dot_h) ==
              shade::smith_separable<T>::G(d, l, v, h, v_dot_h));
    }
}

TEST_CASE_TEMPLATE("two-sided terms: D_visible keeps to the normals above the surface", T, float, double) {
    // w at 85 degrees: m below the horizon but facing w (w·m > 0). D(m) > 0 now that D is
    // two-sided, but no such normal is visible on the surface seen from above: D_w(m) = 0.
    const shade::ggx<T> d(T(0.5));
    const vec3<T> w = local(T(85) * shade::pi<T> / 180, T(0));
    const vec3<T> m = glm::normalize(vec3<T>(1, 0, T(-0.05)));
    CHECK(glm::dot(w, m) > 0);
    CHECK(d.D(m) > T(0));
    CHECK(shade::D_visible(d, w, m) == T(0));
    // Its normalization over the upper hemisphere is unchanged: integral of D_w = 1
    // (Heitz 2014, eq. 2), here in double with the quadrature of test_ggx.cpp.
    const shade::ggx<double> d64(0.5);
    const vec3<double> w64 = local(85 * shade::pi<double> / 180, 0.0);
    const double total = hemisphere_integral([&](const vec3<double>& n) { return shade::D_visible(d64, w64, n); }, 4000, 800);
    CHECK(total == doctest::Approx(1.0).epsilon(1e-3));
}
