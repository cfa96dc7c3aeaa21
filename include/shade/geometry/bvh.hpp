#pragma once
// shade::bvh: a bounding-volume hierarchy over any primitives, given their boxes; and
// shade::primitive_bvh, which also holds the primitives (spheres, or any type with
// shade::bounds and shade::intersect). For triangles, shade::triangle_bvh
// (shade/geometry/triangle_bvh.hpp) tests its leaves with the SIMD batch kernel.
//
// Usage:
//     std::vector<shade::sphere<double>> spheres = ...;
//     const shade::primitive_bvh<shade::sphere<double>> accel(spheres);
//     if (auto h = accel.closest(r))        // nearest hit: h->primitive, h->hit (t, p, n, ...)
//         ...;
//     bool blocked = accel.any(shadow_ray); // any hit in [t_min, t_max]
//
//     // Or only the tree, with your own primitives and test:
//     const shade::bvh<float> tree(boxes);  // std::span<const shade::aabb<float>>
//     auto h = tree.closest(r, [&](std::uint32_t i, const shade::ray<float>& rr) {
//         return my_intersect(rr, prims[i]);  // std::optional<X>, X with a member t
//     });
//
// Built with a binned surface area heuristic (Wald 2007) into nodes of four children, or
// of eight where the CPU has AVX (shade::bvh_width); traversed nearest child first,
// testing a node's children's boxes together with the
// conservative slab test of Ize 2013 (never missing a box the exact ray touches, see
// shade::intersect(ray, aabb)), on float boxes rounded outward, also for double, with the
// ray's direction scaled by a power of two so that no reciprocal overflows (an axis whose
// direction component is too small for one is tested as the interval the ray sweeps
// along it).
//
// The guarantee: the walk tests every primitive whose bounds the real ray segment from
// t_min to the nearest hit found (or t_max) meets. So closest() returns exactly the hit a
// loop of the same primitive test over all primitives returns (the same t and record; the
// same primitive unless several are hit at that very t) whenever that hit's real point
// o + t d lies in its primitive's bounds, and any() is then true. That holds for every ray
// when the test reports only points of its primitive. A test that rounds can report a hit
// a little off its primitive, and when that point lies outside the primitive's bounds the
// hierarchy may miss it: Möller-Trumbore on a ray through an edge whose origin is within
// rounding of the triangle's plane (t = 0) is such a case; closest() then returns the next
// hit the loop would find without it, or nothing. Whatever closest() returns is a hit the
// test reports, never nearer than the loop's. A watertight test (shade::watertight) stays
// watertight behind the hierarchy: a ray through a shared edge or vertex hits a triangle
// there, whose bounds contain that point.
// See shade/geometry/detail/bvh_build.hpp and bvh_traverse.hpp for the algorithms.

#include <concepts>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <shade/core/error.hpp>
#include <shade/core/parallel.hpp>
#include <shade/core/types.hpp>
#include <shade/geometry/aabb.hpp>
#include <shade/geometry/detail/bvh_build.hpp>
#include <shade/geometry/detail/bvh_traverse.hpp>
#include <shade/geometry/ray.hpp>
#include <shade/geometry/sphere.hpp>
#include <shade/geometry/triangle.hpp>

namespace shade {

namespace detail {

/// Throws invalid_parameter naming `parameter` unless every coordinate of box is finite
/// and lo <= hi (a NaN would make the box tests meaningless).
template <std::floating_point T>
void require_finite_box(const char* parameter, std::size_t index, const aabb<T>& box) {
    if (!(is_finite(box.lo) && is_finite(box.hi)) || box.empty())
        throw invalid_parameter(parameter,
                                "must hold finite, non-empty boxes (element " + std::to_string(index) + ")",
                                to_text(box.lo) + " - " + to_text(box.hi));
}

} // namespace detail

/// A hierarchy over primitives 0 .. n-1 given by their boxes; the primitives stay with the
/// caller, who passes a test for them to closest and any. Leaves hold up to 8 primitives.
template <std::floating_point T>
class bvh {
public:
    using scalar_type = T;

    /// An empty hierarchy: nothing is ever hit.
    bvh() = default;

    /// Builds over the primitives with the given boxes, into nodes of `width` children.
    /// Throws shade::invalid_parameter naming "boxes" when a box is empty or not finite,
    /// or when there are 2^27 or more.
    explicit bvh(std::span<const aabb<T>> boxes, bvh_width width = bvh_width::automatic)
        : bvh(boxes, width, serial_executor{}) {}

    /// The same build, its parallel parts run by the executor `run` (see
    /// shade/core/parallel.hpp): the same hierarchy whatever the executor.
    template <parallel_executor E>
    bvh(std::span<const aabb<T>> boxes, bvh_width width, E&& run) {
        detail::require_bvh_size("boxes", boxes.size());
        const detail::executor_ref exec(run);
        auto made = detail::make_prim_refs(exec, boxes.size(), [&](std::size_t i) { return boxes[i]; },
                                           [&](std::size_t i) {
                                               return is_finite(boxes[i].lo) && is_finite(boxes[i].hi) && !boxes[i].empty();
                                           });
        if (made.first_invalid < boxes.size())
            detail::require_finite_box("boxes", made.first_invalid, boxes[made.first_invalid]);
        tree_ = detail::bvh_builder(8, 1).build(made.refs, detail::bvh_node_width(width == bvh_width::four ? 4 : 8), exec, made.box,
                                                made.centroids);
    }

    /// The nearest hit of r: test(index, ray) is called for primitives whose boxes r
    /// enters, returning std::optional<H> with H having a member t (the ray parameter);
    /// the ray passed shrinks its t_max to the nearest hit so far, so test must honour
    /// [t_min, t_max]. Returns that primitive and its record, or nothing.
    template <class Test>
    [[nodiscard]] auto closest(ray<T> r, Test&& test) const {
        using H = typename std::invoke_result_t<Test&, std::uint32_t, const ray<T>&>::value_type;
        std::optional<primitive_hit<H>> best;
        if (tree_.order.empty() || !r.valid()) return best;
        constexpr auto order = detail::bvh_order::sorted;
        detail::bvh_traverse<order>(tree_, r, r.t_max, [&](std::uint32_t first, std::uint32_t count, auto) {
            for (std::uint32_t i = first; i < first + count; ++i) {
                const std::uint32_t p = tree_.order[i];
                if (auto h = test(p, std::as_const(r))) {
                    r.t_max = h->t;
                    best = primitive_hit<H>{p, *h};
                }
            }
            return false;
        });
        return best;
    }

    /// True when test(index, r) reports a hit for some primitive (for shadow rays); stops
    /// at the first one found.
    template <class Test>
    [[nodiscard]] bool any(const ray<T>& r, Test&& test) const {
        if (tree_.order.empty() || !r.valid()) return false;
        bool found = false;
        constexpr auto order = detail::bvh_order::child;
        detail::bvh_traverse<order>(tree_, r, r.t_max, [&](std::uint32_t first, std::uint32_t count, auto) {
            for (std::uint32_t i = first; i < first + count; ++i)
                if (test(tree_.order[i], r)) return found = true;
            return false;
        });
        return found;
    }

    /// Number of primitives.
    [[nodiscard]] std::size_t size() const noexcept { return tree_.order.size(); }
    /// Number of nodes (of up to node_width() children each).
    [[nodiscard]] std::size_t node_count() const noexcept { return tree_.nodes.size() + tree_.wide_nodes.size(); }
    /// Children per node: 4 or 8 (see shade::bvh_width).
    [[nodiscard]] std::size_t node_width() const noexcept { return tree_.width; }
    /// Bytes the hierarchy holds on the heap: its nodes (128 bytes each with four
    /// children, 256 with eight) and its leaves' primitive indices (4 bytes each), as
    /// allocated; not the object itself nor the caller's primitives.
    [[nodiscard]] std::size_t memory_bytes() const noexcept {
        return tree_.node_bytes() + tree_.order.capacity() * sizeof(std::uint32_t);
    }

private:
    detail::bvh_tree tree_;
};

/// A primitive a primitive_bvh can hold: shade::bounds(p) gives its aabb and
/// shade::intersect(r, p) its nearest hit in [t_min, t_max] as a std::optional of a record
/// with a member t (found by argument-dependent lookup, as for shade::sphere).
template <class P>
concept bvh_primitive = requires(const P& p, const ray<typename P::scalar_type>& r) {
    { bounds(p) } -> std::same_as<aabb<typename P::scalar_type>>;
    { intersect(r, p)->t } -> std::convertible_to<typename P::scalar_type>;
};

/// A hierarchy that holds its primitives (copied in).
template <bvh_primitive P>
class primitive_bvh {
public:
    using scalar_type = typename P::scalar_type;
    /// The record shade::intersect(ray, P) returns inside its std::optional.
    using hit_type = typename decltype(intersect(std::declval<const ray<scalar_type>&>(),
                                                 std::declval<const P&>()))::value_type;

    /// An empty hierarchy.
    primitive_bvh() = default;

    /// Builds over a copy of primitives, into nodes of `width` children. Throws
    /// shade::invalid_parameter naming "primitives" when a primitive's bounds are not finite.
    explicit primitive_bvh(std::span<const P> primitives, bvh_width width = bvh_width::automatic)
        : primitives_(primitives.begin(), primitives.end()), tree_(boxes_of(primitives), width) {}

    /// The same, the hierarchy built in parallel by the executor `run` (see
    /// shade/core/parallel.hpp): the same hierarchy whatever the executor.
    template <parallel_executor E>
    primitive_bvh(std::span<const P> primitives, bvh_width width, E&& run)
        : primitives_(primitives.begin(), primitives.end()), tree_(boxes_of(primitives), width, run) {}

    /// The nearest hit of r, with the index of the primitive hit, or nothing.
    [[nodiscard]] std::optional<primitive_hit<hit_type>> closest(const ray<scalar_type>& r) const {
        return tree_.closest(r, [this](std::uint32_t i, const ray<scalar_type>& rr) {
            return intersect(rr, primitives_[i]);
        });
    }

    /// True when r hits some primitive within [t_min, t_max].
    [[nodiscard]] bool any(const ray<scalar_type>& r) const {
        return tree_.any(r, [this](std::uint32_t i, const ray<scalar_type>& rr) {
            return intersect(rr, primitives_[i]).has_value();
        });
    }

    /// Children per node: 4 or 8 (see shade::bvh_width).
    [[nodiscard]] std::size_t node_width() const noexcept { return tree_.node_width(); }

    /// The primitives, in the order given.
    [[nodiscard]] std::span<const P> primitives() const noexcept { return primitives_; }

private:
    static std::vector<aabb<scalar_type>> boxes_of(std::span<const P> primitives) {
        std::vector<aabb<scalar_type>> boxes;
        boxes.reserve(primitives.size());
        for (std::size_t i = 0; i < primitives.size(); ++i) {
            boxes.push_back(bounds(primitives[i]));
            if (!(is_finite(boxes.back().lo) && is_finite(boxes.back().hi)))
                throw invalid_parameter("primitives",
                                        "must have finite bounds (element " + std::to_string(i) + ")",
                                        detail::to_text(boxes.back().lo) + " - " +
                                            detail::to_text(boxes.back().hi));
        }
        return boxes;
    }

    std::vector<P> primitives_;
    bvh<scalar_type> tree_;
};

} // namespace shade
