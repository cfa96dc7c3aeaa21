#pragma once
// Numerical integration over the upper hemisphere for the microfacet tests, in double.

#include <cmath>

#include <shade/core/math.hpp>
#include <shade/core/types.hpp>

namespace microfacet_test {

/// integral over the upper hemisphere of g(w) dw, by the midpoint rule in
/// (u, phi) with theta = (pi/2) u^2, which crowds the nodes near the normal (where the sharp
/// lobes peak): dw = sin(theta) dtheta dphi, dtheta = pi u du.
template <class G>
double hemisphere_integral(G&& g, int n_u = 3000, int n_phi = 400) {
    const double pi = shade::pi<double>;
    double sum = 0;
    for (int i = 0; i < n_u; ++i) {
        const double u = (i + 0.5) / n_u;
        const double theta = 0.5 * pi * u * u;
        const double weight = std::sin(theta) * pi * u / n_u * (2 * pi / n_phi);
        const double s = std::sin(theta), c = std::cos(theta);
        double ring = 0;
        for (int j = 0; j < n_phi; ++j) {
            const double phi = 2 * pi * (j + 0.5) / n_phi;
            ring += g(shade::vec3<double>(s * std::cos(phi), s * std::sin(phi), c));
        }
        sum += ring * weight;
    }
    return sum;
}

/// The local unit direction with polar angle theta and azimuth phi.
template <class T>
shade::vec3<T> local(T theta, T phi) {
    return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

} // namespace microfacet_test
