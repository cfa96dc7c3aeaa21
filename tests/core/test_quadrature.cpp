// shade::gauss_legendre_integral, the 5-point rule shared by the albedo and Fresnel averages.

#include <cmath>
#include <numbers>

#include <doctest/doctest.h>
#include <glm/vec3.hpp>

#include <shade/core/quadrature.hpp>

TEST_CASE("gauss_legendre_integral: exact for degree 9, on one interval") {
    // integral_0^1 x^9 dx = 1/10; integral_0^1 x^10 dx = 1/11 is not exact for five points.
    CHECK(shade::gauss_legendre_integral([](double x) { return std::pow(x, 9); }, 0, 1, 1) ==
          doctest::Approx(0.1).epsilon(1e-15));
    CHECK(std::abs(shade::gauss_legendre_integral([](double x) { return std::pow(x, 10); }, 0, 1, 1) - 1.0 / 11) > 1e-9);
    // integral_{-1}^{3} (x^2 + 1) dx = (27 + 1) / 3 + 4 = 40 / 3.
    CHECK(shade::gauss_legendre_integral([](double x) { return x * x + 1; }, -1, 3, 3) ==
          doctest::Approx(40.0 / 3).epsilon(1e-14));
}

TEST_CASE("gauss_legendre_integral: converges on smooth functions and takes vector values") {
    // integral_0^pi sin = 2, and integral_0^1 e^x = e - 1: 8 intervals give 1e-12.
    CHECK(shade::gauss_legendre_integral([](double x) { return std::sin(x); }, 0, std::numbers::pi, 8) ==
          doctest::Approx(2.0).epsilon(1e-12));
    const glm::dvec3 v = shade::gauss_legendre_integral(
        [](double x) { return glm::dvec3(1, 2 * x, std::exp(x)); }, 0, 1, 8);
    CHECK(v.x == doctest::Approx(1.0).epsilon(1e-14));
    CHECK(v.y == doctest::Approx(1.0).epsilon(1e-14));
    CHECK(v.z == doctest::Approx(std::numbers::e - 1).epsilon(1e-12));
}
