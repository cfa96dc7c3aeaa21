// shade::detail::heap_value (the heap-held member of the large optional tables): emptiness,
// emplace, copies that own their block, moves that take it.

#include <doctest/doctest.h>

#include <array>
#include <utility>

#include <shade/core/heap_value.hpp>

using shade::detail::heap_value;

TEST_CASE("heap_value: empty by default, emplace holds the value and replaces it") {
    heap_value<std::array<int, 4>> h;
    CHECK(!h.has_value());
    CHECK(h.get() == nullptr);
    h.emplace(std::array<int, 4>{1, 2, 3, 4});
    REQUIRE(h.has_value());
    CHECK((*h)[2] == 3);
    CHECK(h->size() == 4);
    h.emplace(std::array<int, 4>{5, 6, 7, 8});
    CHECK((*h)[0] == 5);
}

TEST_CASE("heap_value: a copy holds its own value; a move takes it and leaves the source empty") {
    heap_value<std::array<int, 2>> original;
    original.emplace(std::array<int, 2>{1, 2});
    heap_value<std::array<int, 2>> copy(original);
    REQUIRE(copy.has_value());
    CHECK(copy.get() != original.get()); // its own block, not a shared one
    (*original)[0] = 9;
    CHECK((*copy)[0] == 1);
    heap_value<std::array<int, 2>> assigned;
    assigned = original;
    REQUIRE(assigned.has_value());
    CHECK((*assigned)[0] == 9);
    CHECK(assigned.get() != original.get());
    const std::array<int, 2>* block = original.get();
    heap_value<std::array<int, 2>> moved(std::move(original));
    CHECK(moved.get() == block);
    CHECK(!original.has_value()); // the moved-from state is the point
    heap_value<std::array<int, 2>> empty;
    assigned = empty; // copying an empty one empties
    CHECK(!assigned.has_value());
    moved = heap_value<std::array<int, 2>>();
    CHECK(!moved.has_value());
}
