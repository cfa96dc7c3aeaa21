// The thin film's share of openpbr_surface's E_spec over a wide sweep of the specification's
// film range (issue #32): film index 1.02-3, thickness 0.03-9 um, specular_ior 1.33 and 2.2,
// roughness 0.02-1, mu 0.1-1, every channel, the read against the quadrature of
// tests/material/openpbr_film.hpp (noise-free). tests/material/test_openpbr_surface.cpp runs
// the films where the margin is largest in every script/test; this file runs the sweep, in
// script/test --all only (tests/sweep/CMakeLists.txt). The white furnace reads
// 1 + E_R,true - E_R: never above 1.001 is E_R read - true >= -1e-3, asserted everywhere;
// the low end 0.99 is read - true <= 1e-2, which films of index below 1.2 and other
// eta'_s may miss (the margin that keeps them from reading low reads them high by more:
// film_test::film_high_bound, from the generator's statement; docs/conventions.md). The
// second case sweeps anisotropic lobes.
#include <algorithm>
#include <vector>

#include <doctest/doctest.h>

#include "material/openpbr_film.hpp"

TEST_CASE("openpbr_surface: a thin film's share of E_spec never reads low, across the film's range (sweep)") {
    using T = double;
    double lowest = 1, highest = -1, highest_from_1_2 = -1;
    for (const T specular_weight : {T(1), T(0.6)}) {
        for (const T base : {T(1.33), T(2.2)}) {
            for (const T ior : {T(1.02), T(1.05), T(1.1), T(1.25), T(1.4), T(1.7), T(2), T(2.5), T(3)}) {
                for (const T thickness : {T(0.03), T(0.1), T(0.25), T(0.5), T(0.75), T(1), T(1.5), T(2), T(2.5), T(3),
                                          T(4), T(6), T(9)}) {
                    if (specular_weight != T(1) && (base != T(1.33) || ior == T(1.25) || ior == T(1.7))) continue;
                    const film_test::film_point<T> fl{1, thickness, ior, base, specular_weight};
                    for (const T r : {T(0.02), T(0.05), T(0.1), T(0.2), T(0.5), T(1)}) {
                        for (const double mu : {0.1, 0.15, 0.3, 0.6, 1.0}) {
                            const shade::rgb<double> error = film_test::film_albedo_error(fl, r, mu, 96);
                            for (int k = 0; k < 3; ++k) {
                                INFO("specular_weight ", specular_weight, " base ", base, " film ior ", ior,
                                     " thickness ", thickness, " roughness ", r, " mu ", mu, " channel ", k,
                                     ": E_R read - true ", error[k]);
                                CHECK(error[k] >= -1e-3);
                                CHECK(error[k] <= film_test::film_high_bound(fl));
                                lowest = std::min(lowest, error[k]);
                                highest = std::max(highest, error[k]);
                                if (ior >= T(1.2) && specular_weight == T(1)) highest_from_1_2 = std::max(highest_from_1_2, error[k]);
                            }
                        }
                    }
                }
            }
        }
    }
    MESSAGE("thin film sweep: E_R read - true in [", lowest, ", ", highest, "] (film index >= 1.2 over its base: up to ",
            highest_from_1_2, ")");
}

TEST_CASE("openpbr_surface: a thin film's share of E_spec on anisotropic lobes never reads low (sweep)") {
    // film_test::film_reader (the read against the anisotropic lobe's own 96^2-cell quadrature
    // of v·h with F_film at each cell's cosine; R_ss by the same quadrature where the
    // material integrates it, strong anisotropy here) over film index 1.02-3, 0.05-3 um, specular_ior
    // 1.33 and 2.2, roughness 0.3-1, anisotropy 0.5-1 (alpha_y / alpha_x 3 to 1e4), mu 0.1-1
    // and azimuths 0 to pi/2, every channel: never above the white furnace's 1.001 is
    // E_R read - true >= -1e-3; the high side is held to the 1.5e-2 of
    // tests/material/test_openpbr_surface.cpp (measured +2.3e-3 to +1.03e-2 with the film's
    // share integrated on the lobe's grid; 2.6e-2 with the isotropic reference plus a tabulated anisotropic correction).
    using T = double;
    double lowest = 1, highest = -1;
    for (const T base : {T(1.33), T(2.2)}) {
        for (const T ior : {T(1.02), T(1.05), T(1.1), T(1.4), T(2), T(3)}) {
            for (const T thickness : {T(0.05), T(0.25), T(1), T(3)}) {
                for (const T r : {T(0.3), T(0.6), T(1)}) {
                    for (const T a : {T(0.5), T(0.9), T(1)}) {
                        const film_test::film_reader<T> reader({1, thickness, ior, base}, r, a);
                        for (const double mu : {0.1, 0.3, 1.0}) {
                            for (const double phi : {0.0, 1.0, 1.5708}) {
                                const shade::rgb<double> error = reader.error(mu, phi, 96, reader.integrates_r_ss());
                                for (int k = 0; k < 3; ++k) {
                                    INFO("base ", base, " film ior ", ior, " thickness ", thickness, " roughness ", r,
                                         " anisotropy ", a, " mu ", mu, " phi ", phi, " channel ", k,
                                         ": E_R read - true ", error[k]);
                                    CHECK(error[k] >= -1e-3);
                                    CHECK(error[k] <= 1.5e-2);
                                    lowest = std::min(lowest, error[k]);
                                    highest = std::max(highest, error[k]);
                                }
                            }
                        }
                    }
                }
            }
        }
    }
    MESSAGE("thin film sweep, anisotropic: E_R read - true in [", lowest, ", ", highest, "]");
}
