// The integral identities every microfacet distribution satisfies, checked for each shipped
// one (GGX and Beckmann, whose own Lambda and G1 are the exact Smith terms) by quadrature
// over the hemisphere of normals, anisotropic parameters included.

#include <algorithm>
#include <utility>

#include <doctest/doctest.h>

#include <glm/geometric.hpp>

#include <shade/brdf/microfacet/beckmann.hpp>
#include <shade/brdf/microfacet/ggx.hpp>

#include "brdf/microfacet/quadrature.hpp"
#include "brdf/support.hpp"

using namespace brdf_test;
using namespace microfacet_test;

// The (roughness along t, roughness along b) pairs: anisotropic both ways, isotropic, and
// sharp (0.01, where the quadrature must resolve a narrow peak).
constexpr std::pair<double, double> parameter_sets[] = {{0.05, 0.5}, {0.3, 0.3}, {1.0, 0.2}, {1.0, 1.0}, {0.01, 0.01}};

TEST_CASE_TEMPLATE("microfacet distributions: normalized, integral of D(m) (m.n) dm = 1", D, shade::ggx<double>,
                   shade::beckmann<double>) {
    for (const auto& parameters : parameter_sets) {
        const double rx = parameters.first;
        const double ry = parameters.second;
        const D d(rx, ry);
        CAPTURE(rx);
        CAPTURE(ry);
        CHECK(hemisphere_integral([&](const vec3<double>& m) { return d.D(m) * m.z; }) ==
              doctest::Approx(1.0).epsilon(1e-4));
    }
}

TEST_CASE_TEMPLATE("microfacet distributions: integral of G1(v) max(0, v.m) D(m) dm = n.v (Heitz 2014, eq. 2)", D,
                   shade::ggx<double>, shade::beckmann<double>) {
    for (const auto& parameters : parameter_sets) {
        const double rx = parameters.first;
        const double ry = parameters.second;
        const D d(rx, ry);
        for (const double theta_v : {0.0, 1.0, 1.4, 1.52}) {
            for (const double phi_v : {0.0, 0.9}) {
                const vec3<double> v = local(theta_v, phi_v);
                CAPTURE(rx);
                CAPTURE(ry);
                CAPTURE(theta_v);
                CAPTURE(phi_v);
                const double projected = hemisphere_integral(
                    [&](const vec3<double>& m) { return d.G1(v) * std::max(0.0, glm::dot(v, m)) * d.D(m); });
                CHECK(projected == doctest::Approx(v.z).epsilon(1e-3));
                // Without masking, the projected area of the visible normals is
                // n.v (1 + Lambda(v)) (Heitz 2014, the definition of Lambda: the projected area of
                // the back-facing normals over n.v); this checks Lambda independently, and it
                // differs from n.v wherever Lambda is not negligible.
                const double unmasked = hemisphere_integral(
                    [&](const vec3<double>& m) { return std::max(0.0, glm::dot(v, m)) * d.D(m); });
                CHECK(unmasked == doctest::Approx(v.z * (1 + d.Lambda(v))).epsilon(1e-3));
            }
        }
    }
}
