#include <doctest/doctest.h>

#include <shade/core/sampling.hpp>

TEST_CASE_TEMPLATE("stratified_u places samples in their strata", T, float, double) {
    // n = 4, stratum (1, 2) at its centre: ((1 + 0.5)/4, (2 + 0.5)/4) = (0.375, 0.625).
    const auto u = shade::stratified_u<T>(1, 2, 4, shade::cell_centre<T>{}(1, 2));
    CHECK(u == shade::vec2<T>(T(0.375), T(0.625)));
    CHECK(shade::stratified_u<T>(0, 0, 4, shade::vec2<T>(0)) == shade::vec2<T>(0));
    CHECK(shade::stratified_u<T>(3, 3, 4, shade::vec2<T>(T(0.5), 0)) == shade::vec2<T>(T(0.875), T(0.75)));
}
