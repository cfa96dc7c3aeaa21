#include <limits>

#include <doctest/doctest.h>

#include <shade/core/error.hpp>
#include <shade/core/surface_point.hpp>

TEST_CASE_TEMPLATE("surface_point::checked accepts a unit normal and builds the frame at() builds", T, float,
                   double) {
    using v = shade::vec3<T>;
    const v n(T(0.6), 0, T(0.8));
    const auto a = shade::surface_point<T>::checked(v(1, 2, 3), n);
    const auto b = shade::surface_point<T>::at(v(1, 2, 3), n);
    CHECK(a.p == b.p);
    CHECK(a.n() == n);
    CHECK(a.shading.t == b.shading.t);
    CHECK(a.shading.b == b.shading.b);
    // A normal normalised in float and converted to double: a few float ulps from unit
    // length, well inside the 1e-3 tolerance on |n|^2.
    const shade::vec3<float> nf = glm::normalize(shade::vec3<float>(1, 2, 3));
    CHECK_NOTHROW((void)shade::surface_point<T>::checked(v(0), v(nf)));
}

TEST_CASE_TEMPLATE("surface_point::checked rejects a normal that is not unit length, and a non-finite point",
                   T, float, double) {
    using v = shade::vec3<T>;
    const T nan = std::numeric_limits<T>::quiet_NaN();
    const T inf = std::numeric_limits<T>::infinity();
    // |n|^2 = 4, 0.25, 1.0021 (just over the 1e-3 tolerance: 1.00105^2), 0, NaN, inf.
    for (const v n : {v(0, 0, 2), v(0, 0, T(0.5)), v(0, 0, T(1.00105)), v(0), v(0, nan, 1), v(inf, 0, 0)}) {
        CAPTURE(n.z);
        CHECK_THROWS_WITH_AS((void)shade::surface_point<T>::checked(v(0), n), doctest::Contains("'n'"),
                             shade::invalid_parameter);
    }
    // |n|^2 = 1.0009 (1.00045^2) is inside the tolerance.
    CHECK_NOTHROW((void)shade::surface_point<T>::checked(v(0), v(0, 0, T(1.00045))));
    CHECK_THROWS_WITH_AS((void)shade::surface_point<T>::checked(v(nan, 0, 0), v(0, 0, 1)), doctest::Contains("'p'"),
                         shade::invalid_parameter);
    CHECK_THROWS_WITH_AS((void)shade::surface_point<T>::checked(v(0, inf, 0), v(0, 0, 1)), doctest::Contains("'p'"),
                         shade::invalid_parameter);
}
