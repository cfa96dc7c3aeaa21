#pragma once
// A bounding-volume hierarchy over a list of primitives, for the reference tracer.
//
// Built top-down by splitting the primitives' centroid bounds along their longest axis at
// the median (a simple builder: good enough for the tessellated objects of the examples,
// where it turns O(n) per ray into O(log n)). Traversal is front-to-back with a stack and
// a conservative slab test, so it never culls a box that a watertight primitive test would
// hit (Ize 2013, "Robust BVH Ray Traversal", JCGT 2(2): the far distance is enlarged by
// 2 gamma(3) ulps of relative error).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <optional>
#include <vector>

#include <glm/common.hpp>

#include <shade/geometry/ray.hpp>

namespace tracer {

using real = double;
using vec3 = shade::vec3<real>;

/// An axis-aligned box [lo, hi]; empty when lo > hi.
struct aabb {
    vec3 lo{std::numeric_limits<real>::infinity()};
    vec3 hi{-std::numeric_limits<real>::infinity()};

    void grow(const vec3& p) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    void grow(const aabb& b) {
        lo = glm::min(lo, b.lo);
        hi = glm::max(hi, b.hi);
    }
    [[nodiscard]] vec3 centre() const { return (lo + hi) * real(0.5); }

    /// The entry distance of the ray into the box within [ray.t_min, t_max], or nothing.
    /// inv_dir is 1 / ray.direction per component (infinite for a zero component).
    [[nodiscard]] std::optional<real> enter(const shade::ray<real>& r, const vec3& inv_dir,
                                            real t_max) const {
        // Ize 2013 (JCGT 2(2), sec. 3.2): multiplying the far distance by 1 + 2 gamma(3)
        // absorbs the rounding of the three slab computations, so a box that the exact
        // ray touches is never missed.
        constexpr real eps = std::numeric_limits<real>::epsilon() * real(0.5);
        constexpr real gamma3 = 3 * eps / (1 - 3 * eps);
        real t0 = r.t_min;
        real t1 = t_max;
        for (int a = 0; a < 3; ++a) {
            real near = (lo[a] - r.origin[a]) * inv_dir[a];
            real far = (hi[a] - r.origin[a]) * inv_dir[a];
            if (near > far) std::swap(near, far);
            far *= 1 + 2 * gamma3;
            // NaN (0 * inf for a ray in the slab's plane) fails both comparisons and so
            // leaves the interval unchanged, which is the right answer for that case.
            if (near > t0) t0 = near;
            if (far < t1) t1 = far;
            if (t0 > t1) return std::nullopt;
        }
        return t0;
    }
};

/// A BVH over primitive indices 0..n-1. The primitives themselves stay with the caller,
/// who supplies their bounds when building and an intersection callable when tracing.
class bvh {
public:
    bvh() = default;

    /// Builds over primitives with the given bounds; leaves hold at most max_leaf of them.
    explicit bvh(const std::vector<aabb>& bounds, std::size_t max_leaf = 4) {
        order_.resize(bounds.size());
        std::iota(order_.begin(), order_.end(), std::uint32_t(0));
        if (bounds.empty()) return;
        nodes_.reserve(2 * bounds.size());
        nodes_.emplace_back();
        build(0, bounds, 0, bounds.size(), max_leaf);
    }

    /// The closest hit: `hit_primitive(index, ray)` returns std::optional<H> where H has a
    /// member t; the ray's t_max shrinks to each hit found so far.
    template <class H, class F>
    [[nodiscard]] std::optional<H> closest(shade::ray<real> r, F&& hit_primitive) const {
        std::optional<H> best;
        traverse<true>(r, [&](std::uint32_t primitive) {
            if (auto h = hit_primitive(primitive, r)) {
                r.t_max = h->t;
                best = h;
            }
            return false; // keep looking for a nearer hit
        });
        return best;
    }

    /// True when any primitive is hit within the ray's interval (for shadow rays).
    template <class F>
    [[nodiscard]] bool any(const shade::ray<real>& r, F&& hit_primitive) const {
        bool found = false;
        traverse<false>(r, [&](std::uint32_t primitive) {
            found = static_cast<bool>(hit_primitive(primitive, r));
            return found; // the first hit ends the search
        });
        return found;
    }

    /// Number of nodes (for tests and statistics).
    [[nodiscard]] std::size_t size() const { return nodes_.size(); }

    /// Bounds of everything (empty box for an empty BVH).
    [[nodiscard]] aabb bounds() const { return nodes_.empty() ? aabb{} : nodes_[0].box; }

private:
    /// Depth-first walk over the nodes whose boxes r enters within [t_min, t_max]: calls
    /// visit(primitive) for each primitive of each leaf reached, and stops as soon as visit
    /// returns true. visit may shrink r.t_max (r is re-read at every node), which prunes
    /// the rest. NearFirst visits the nearer child first (worth two extra box tests per
    /// node when t_max shrinks, as for closest hits; not for any-hit queries).
    template <bool NearFirst, class Visit>
    void traverse(const shade::ray<real>& r, Visit&& visit) const {
        if (nodes_.empty()) return;
        const vec3 inv_dir = real(1) / r.direction;
        std::array<std::uint32_t, 64> stack{};
        std::size_t top = 0;
        stack[top++] = 0;
        while (top > 0) {
            const node& nd = nodes_[stack[--top]];
            if (!nd.box.enter(r, inv_dir, r.t_max)) continue;
            if (nd.count > 0) {
                for (std::uint32_t i = nd.first; i < nd.first + nd.count; ++i)
                    if (visit(order_[i])) return;
                continue;
            }
            std::uint32_t a = nd.first;
            std::uint32_t b = nd.first + 1;
            if constexpr (NearFirst) {
                const auto ta = nodes_[a].box.enter(r, inv_dir, r.t_max);
                const auto tb = nodes_[b].box.enter(r, inv_dir, r.t_max);
                if (!ta && !tb) continue;
                if (ta && tb && *tb < *ta) std::swap(a, b);
            }
            stack[top++] = b; // a is popped first
            stack[top++] = a;
        }
    }

    struct node {
        aabb box;
        std::uint32_t first = 0; ///< leaf: first index into order_; inner: left child
        std::uint32_t count = 0; ///< leaf: number of primitives; inner: 0
    };

    /// Fills nodes_[index] with the subtree over order_[begin, end).
    void build(std::size_t index, const std::vector<aabb>& bounds, std::size_t begin,
               std::size_t end, std::size_t max_leaf) {
        aabb box;
        aabb centroids;
        for (std::size_t i = begin; i < end; ++i) {
            box.grow(bounds[order_[i]]);
            centroids.grow(bounds[order_[i]].centre());
        }
        nodes_[index].box = box;
        const vec3 extent = centroids.hi - centroids.lo;
        const int axis = extent.x > extent.y ? (extent.x > extent.z ? 0 : 2) : (extent.y > extent.z ? 1 : 2);
        // Depth is bounded by the 64-entry traversal stack: a median split halves the
        // count each level, so 2^60 primitives would be needed to overflow it.
        if (end - begin <= max_leaf || !(extent[axis] > 0)) {
            nodes_[index].first = static_cast<std::uint32_t>(begin);
            nodes_[index].count = static_cast<std::uint32_t>(end - begin);
            return;
        }
        const std::size_t mid = begin + (end - begin) / 2;
        std::nth_element(order_.begin() + std::ptrdiff_t(begin), order_.begin() + std::ptrdiff_t(mid),
                         order_.begin() + std::ptrdiff_t(end), [&](std::uint32_t x, std::uint32_t y) {
                             return bounds[x].centre()[axis] < bounds[y].centre()[axis];
                         });
        // Children are stored next to each other so that one index finds both.
        const std::size_t left = nodes_.size();
        nodes_[index].first = static_cast<std::uint32_t>(left);
        nodes_[index].count = 0;
        nodes_.emplace_back();
        nodes_.emplace_back();
        build(left, bounds, begin, mid, max_leaf);
        build(left + 1, bounds, mid, end, max_leaf);
    }

    std::vector<node> nodes_;
    std::vector<std::uint32_t> order_;
};

} // namespace tracer
