#pragma once
// shade::triangle_algorithms: the set of ray/triangle algorithms shade provides
// (shade/geometry/triangle.hpp), as one type for tests and benchmarks to iterate over.
// Apart from triangle.hpp so that the contract (shade::triangle_algorithm) and its
// algorithms do not make every user pay for <tuple>.
//
// Usage:
//     std::apply([&](auto... a) { (run<decltype(a)>(), ...); }, shade::triangle_algorithms{});

#include <tuple>

#include <shade/geometry/triangle.hpp>

namespace shade {

/// Every triangle algorithm shade provides (std::apply on a value, or doctest's
/// TEST_CASE_TEMPLATE_APPLY).
using triangle_algorithms = std::tuple<moller_trumbore, plane_then_areas, watertight>;

} // namespace shade
