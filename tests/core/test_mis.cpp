// shade::balance_heuristic and shade::power_heuristic (Veach 1997, eqs. 9.10 and 9.13):
// hand-computed values, weights of the techniques summing to 1, delta and zero densities,
// and no overflow for densities whose squares overflow.

#include <cmath>
#include <limits>

#include <doctest/doctest.h>

#include <shade/core/mis.hpp>

TEST_CASE_TEMPLATE("mis: hand-computed weights", T, float, double) {
    // Balance, one sample each: 3 / (3 + 1) = 0.75. Power: 9 / (9 + 1) = 0.9.
    CHECK(shade::balance_heuristic<T>(3, 1) == doctest::Approx(0.75));
    CHECK(shade::power_heuristic<T>(3, 1) == doctest::Approx(0.9));
    // With sample counts: n_f p_f = 2 * 1 = 2, n_g p_g = 1 * 4 = 4: balance 2/6, power 4/20.
    CHECK(shade::balance_heuristic<T>(2, 1, 1, 4) == doctest::Approx(1.0 / 3));
    CHECK(shade::power_heuristic<T>(2, 1, 1, 4) == doctest::Approx(0.2));
    // Equal densities: one half each.
    CHECK(shade::balance_heuristic<T>(7, 7) == T(0.5));
    CHECK(shade::power_heuristic<T>(7, 7) == T(0.5));
}

TEST_CASE_TEMPLATE("mis: the two techniques' weights sum to 1", T, float, double) {
    const T pdfs[] = {T(1e-30), T(1e-3), T(0.5), T(1), T(3), T(1e4), T(1e30)};
    for (const T a : pdfs)
        for (const T b : pdfs) {
            CHECK(shade::balance_heuristic(a, b) + shade::balance_heuristic(b, a) == doctest::Approx(1).epsilon(1e-6));
            CHECK(shade::power_heuristic(a, b) + shade::power_heuristic(b, a) == doctest::Approx(1).epsilon(1e-6));
            CHECK(shade::power_heuristic(T(2), a, T(3), b) + shade::power_heuristic(T(3), b, T(2), a) ==
                  doctest::Approx(1).epsilon(1e-6));
        }
}

TEST_CASE_TEMPLATE("mis: zero, delta and huge densities", T, float, double) {
    const T inf = std::numeric_limits<T>::infinity();
    const T big = std::numeric_limits<T>::max() / 4;
    // A sample its own technique could not have drawn has no weight.
    CHECK(shade::power_heuristic(T(0), T(1)) == T(0));
    CHECK(shade::balance_heuristic(T(0), T(0)) == T(0));
    CHECK(shade::power_heuristic(T(0), T(0)) == T(0));
    // When the other technique cannot draw it, the weight is 1.
    CHECK(shade::power_heuristic(T(2), T(0)) == T(1));
    // A delta technique (density +inf) takes everything, the other nothing.
    CHECK(shade::power_heuristic(inf, T(5)) == T(1));
    CHECK(shade::power_heuristic(T(5), inf) == T(0));
    CHECK(shade::balance_heuristic(inf, T(5)) == T(1));
    CHECK(shade::balance_heuristic(T(5), inf) == T(0));
    // Densities whose squares (and sums) overflow: the weights come from the ratio.
    CHECK(shade::power_heuristic(big, big) == T(0.5));
    CHECK(shade::balance_heuristic(big, big) == T(0.5));
    CHECK(shade::power_heuristic(big, big / 2) == doctest::Approx(0.8)); // 1 / (1 + 1/4)
    CHECK(!std::isnan(shade::power_heuristic(inf, inf)));
}
