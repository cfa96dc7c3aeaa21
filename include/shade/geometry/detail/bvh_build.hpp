#pragma once
// The builder behind shade::bvh and shade::triangle_bvh: a binary tree by binned surface
// area heuristic, collapsed into nodes of four (or eight) children whose float boxes the
// traversal (detail/bvh_traverse.hpp) tests together. Internal: use shade/geometry/bvh.hpp.

#include <array>
#include <bit>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <shade/core/error.hpp>
#include <shade/core/math.hpp>
#include <shade/core/parallel.hpp>
#include <shade/core/types.hpp>
#include <shade/geometry/aabb.hpp>

namespace shade {

/// Children per node of a hierarchy (bvh, primitive_bvh, triangle_bvh). `eight` gives
/// eight, tested with AVX, where the build can (x86-64 with g++ or clang++: chosen at run
/// time, or built with -mavx) and the CPU has AVX, else four (node_width() says which);
/// `automatic` is `eight`. The width changes the speed only, never the hits found.
enum class bvh_width { automatic, four, eight };

} // namespace shade

namespace shade::detail {

/// The next float above f (toward +infinity), or f itself when f is +infinity; f not NaN.
/// One step of the bit pattern (IEEE 754-2019 §3.4: for floats of one sign the encodings
/// are ordered like the values), in integer arithmetic without branches: the signs of the
/// coordinates it is applied to vary from ray to ray, which a branch would mispredict.
[[nodiscard]] inline float next_float_up(float f) noexcept {
    const auto b = std::bit_cast<std::uint32_t>(f + 0.0f); // -0 becomes +0
    const std::uint32_t negative = b >> 31;
    const std::uint32_t infinite = b == 0x7f80'0000u ? 1u : 0u;
    // +1 for positive f, -1 (modulo 2^32) for negative f, 0 for +infinity.
    return std::bit_cast<float>(b + (1u - 2u * negative) * (1u - infinite));
}
/// The next float below f (toward -infinity), or f itself when f is -infinity.
[[nodiscard]] inline float next_float_down(float f) noexcept { return -next_float_up(-f); }

/// A float no larger than x: x itself when T is float; for double, x rounded to the
/// nearest float and then stepped one float down (without comparing, so no branch: one
/// step more than needed when x is a float already, which only widens what it bounds).
template <std::floating_point T>
[[nodiscard]] inline float float_down(T x) noexcept {
    if constexpr (sizeof(T) == sizeof(float)) return x;
    else return next_float_down(static_cast<float>(x));
}

/// A float no smaller than x (see float_down).
template <std::floating_point T>
[[nodiscard]] inline float float_up(T x) noexcept {
    if constexpr (sizeof(T) == sizeof(float)) return x;
    else return next_float_up(static_cast<float>(x));
}

/// A node of the collapsed tree: the boxes of up to W children, stored per axis and side
/// (lo x, hi x, lo y, hi y, lo z, hi z; one float per child in each), so that one vector
/// load gets one plane of all W, and the children's references. A reference is an inner
/// node's index, or a leaf (leaf_flag set) holding `count` items from `first` (see
/// make_leaf_ref). Unused children have an empty box (lo = +inf, hi = -inf), which no
/// finite ray enters, and an empty leaf (count 0) as their reference. W = 4: 128 bytes (two
/// cache lines); W = 8: 256 bytes (four), of which the last 32 (free otherwise, by the
/// alignment) hold `visit`: for each of the eight ray octants (bit k set where the
/// direction's component k has its sign bit set), the children in the order a ray of that
/// octant meets them as judged from their boxes' centres (bvh_visit_orders), position p in
/// bits [3 p, 3 p + 3), the empty children last. Both widths are always declared; only
/// x86-64 builds with g++ or clang++ build and walk nodes of eight (detail/bvh_traverse.hpp).
struct bvh_no_visit {};
template <std::size_t W>
struct alignas(64) bvh_node {
    std::array<std::array<float, W>, 6> planes; ///< [2 k + side][child]: side 0 lo, 1 hi
    std::array<std::uint32_t, W> child;         ///< child references
    /// [octant]: the children in visit order (nodes of eight only)
    [[no_unique_address]] std::conditional_t<W == 8, std::array<std::uint32_t, 8>, bvh_no_visit> visit;
};
static_assert(sizeof(bvh_node<4>) == 128 && sizeof(bvh_node<8>) == 256);

/// Fills node.visit from the boxes of its first n children (the rest empty). A ray of
/// octant o moves along s = (+-1, +-1, +-1) (component k negative where bit k of o is
/// set) and, roughly, meets a box earlier the smaller the dot product of s with the box's
/// centre: the children are sorted by that key; the order of octant 7 - o (the opposite
/// direction) is that of o reversed. Any order finds the nearest hit (a walk visits every
/// entered child whose entry is not beyond the nearest hit found); this one lets a walk
/// stack the entered children far to near without comparing their entry distances
/// (per-octant child orders kept in the node: Fuetterling, Lojewski, Pfreundt, Ebert 2015,
/// "Efficient Ray Tracing Kernels for Modern CPU Architectures", JCGT 4(4)).
inline void bvh_visit_orders(bvh_node<8>& node, std::size_t n) noexcept {
    for (unsigned o = 0; o < 4; ++o) {
        std::array<float, 8> key{};
        std::array<std::uint32_t, 8> order{};
        for (std::size_t j = 0; j < n; ++j) {
            float sum = 0.0f;
            for (std::size_t k = 0; k < 3; ++k) {
                const float centre = node.planes[2 * k][j] + node.planes[2 * k + 1][j]; // twice the centre
                sum += (o >> k & 1u) != 0 ? -centre : centre;
            }
            // Insertion by key (a NaN key, from a box beyond the float range, lands anywhere).
            std::size_t p = j;
            for (; p > 0 && sum < key[p - 1]; --p) {
                key[p] = key[p - 1];
                order[p] = order[p - 1];
            }
            key[p] = sum;
            order[p] = static_cast<std::uint32_t>(j);
        }
        std::uint32_t forward = 0, backward = 0;
        for (std::size_t p = 0; p < 8; ++p) {
            const auto empty = static_cast<std::uint32_t>(p);
            forward |= (p < n ? order[p] : empty) << (3 * p);
            backward |= (p < n ? order[n - 1 - p] : empty) << (3 * p);
        }
        node.visit[o] = forward;
        node.visit[7 - o] = backward;
    }
}

inline constexpr std::uint32_t bvh_leaf_flag = 0x8000'0000u;
/// Items per leaf fit in 4 bits; first items index in the remaining 27.
inline constexpr std::uint32_t bvh_max_leaf_items = 15;
inline constexpr std::uint32_t bvh_max_items = 1u << 27;

[[nodiscard]] constexpr std::uint32_t make_leaf_ref(std::uint32_t first, std::uint32_t count) noexcept {
    return bvh_leaf_flag | (first << 4) | count;
}
[[nodiscard]] constexpr bool is_leaf_ref(std::uint32_t ref) noexcept { return (ref & bvh_leaf_flag) != 0; }
[[nodiscard]] constexpr std::uint32_t leaf_first(std::uint32_t ref) noexcept {
    return (ref & ~bvh_leaf_flag) >> 4;
}
[[nodiscard]] constexpr std::uint32_t leaf_count(std::uint32_t ref) noexcept { return ref & 15u; }

#if defined(__GNUC__)
/// Four floats in one GNU vector (SSE on x86-64, NEON on ARM): the builder's boxes.
using bvh_v4 [[gnu::vector_size(16)]] = float;
[[nodiscard]] inline bvh_v4 bvh_vmin(const bvh_v4& a, const bvh_v4& b) noexcept { return a < b ? a : b; }
[[nodiscard]] inline bvh_v4 bvh_vmax(const bvh_v4& a, const bvh_v4& b) noexcept { return a > b ? a : b; }
/// bvh_vmax(a, b) for the binning's clamp: the same lanes (b where a > b is false, NaN
/// included), in one SSE maxps on x86-64, which g++ does not pick for the select with a
/// constant b (it compares and masks).
[[nodiscard]] inline bvh_v4 bvh_vmax_clamp(const bvh_v4& a, const bvh_v4& b) noexcept {
#if defined(__x86_64__)
    return __builtin_ia32_maxps(a, b);
#else
    return bvh_vmax(a, b);
#endif
}
#else
/// Four floats (the builder's boxes), one at a time where GNU vectors are missing.
struct bvh_v4 {
    std::array<float, 4> v{};
    float& operator[](std::size_t i) noexcept { return v[i]; }
    float operator[](std::size_t i) const noexcept { return v[i]; }
    friend bvh_v4 operator+(bvh_v4 a, const bvh_v4& b) noexcept { for (std::size_t i = 0; i < 4; ++i) a.v[i] += b.v[i]; return a; }
    friend bvh_v4 operator-(bvh_v4 a, const bvh_v4& b) noexcept { for (std::size_t i = 0; i < 4; ++i) a.v[i] -= b.v[i]; return a; }
    friend bvh_v4 operator*(bvh_v4 a, const bvh_v4& b) noexcept { for (std::size_t i = 0; i < 4; ++i) a.v[i] *= b.v[i]; return a; }
};
[[nodiscard]] inline bvh_v4 bvh_vmin(bvh_v4 a, const bvh_v4& b) noexcept { for (std::size_t i = 0; i < 4; ++i) a.v[i] = b.v[i] < a.v[i] ? b.v[i] : a.v[i]; return a; }
[[nodiscard]] inline bvh_v4 bvh_vmax(bvh_v4 a, const bvh_v4& b) noexcept { for (std::size_t i = 0; i < 4; ++i) a.v[i] = a.v[i] < b.v[i] ? b.v[i] : a.v[i]; return a; }
[[nodiscard]] inline bvh_v4 bvh_vmax_clamp(const bvh_v4& a, const bvh_v4& b) noexcept { return bvh_vmax(a, b); }
#endif

/// The lanes of x, each in [0, 2^31), truncated toward zero to integers.
[[nodiscard]] inline std::array<std::uint32_t, 4> bvh_truncate(const bvh_v4& x) noexcept {
#if defined(__GNUC__)
    using lanes_i32 [[gnu::vector_size(16)]] = std::int32_t;
    const auto i = __builtin_convertvector(x, lanes_i32); // one conversion of the four lanes
    return {std::uint32_t(i[0]), std::uint32_t(i[1]), std::uint32_t(i[2]), std::uint32_t(i[3])};
#else
    return {std::uint32_t(x[0]), std::uint32_t(x[1]), std::uint32_t(x[2]), std::uint32_t(x[3])};
#endif
}

/// One primitive while building: its box (rounded outward to floats; x, y, z in lanes 0-2
/// of lo and hi) and its index (lane 3 of lo, bit-cast). The builder partitions these in
/// place.
struct bvh_prim_ref {
    bvh_v4 lo;
    bvh_v4 hi;

    [[nodiscard]] std::uint32_t index() const noexcept { return std::bit_cast<std::uint32_t>(float(lo[3])); }
    /// Twice the centroid, lo + hi (lane 3 unused).
    [[nodiscard]] bvh_v4 centroid2() const noexcept { return lo + hi; }
};

/// A float box of the builder (lanes 0-2; lane 3 unused).
struct bvh_box {
    bvh_v4 lo{infinity<float>, infinity<float>, infinity<float>, infinity<float>};
    bvh_v4 hi{-infinity<float>, -infinity<float>, -infinity<float>, -infinity<float>};

    void grow(const bvh_v4& l, const bvh_v4& h) noexcept {
        lo = bvh_vmin(lo, l);
        hi = bvh_vmax(hi, h);
    }
    void grow(const bvh_box& b) noexcept { grow(b.lo, b.hi); }
    /// Half the surface area (the heuristic needs only ratios); 0 when empty.
    [[nodiscard]] float half_area() const noexcept {
        const float x = hi[0] - lo[0], y = hi[1] - lo[1], z = hi[2] - lo[2];
        if (!(x >= 0.0f && y >= 0.0f && z >= 0.0f)) return 0.0f;
        return x * y + y * z + z * x;
    }
};

/// The float box holding b (each bound rounded outward), and the primitive reference.
template <std::floating_point T>
[[nodiscard]] inline bvh_prim_ref make_prim_ref(const aabb<T>& b, std::uint32_t index) noexcept {
    return bvh_prim_ref{bvh_v4{float_down(b.lo.x), float_down(b.lo.y), float_down(b.lo.z),
                               std::bit_cast<float>(index)},
                        bvh_v4{float_up(b.hi.x), float_up(b.hi.y), float_up(b.hi.z), 0.0f}};
}

/// The tree a build produces: the collapsed nodes of four children (nodes) or eight
/// (wide_nodes; node 0 is the root; none for no primitives), and the primitives' indices
/// in leaf order (a leaf reference's first and count index this array).
struct bvh_tree {
    std::vector<bvh_node<4>> nodes;
    std::vector<bvh_node<8>> wide_nodes;
    std::vector<std::uint32_t> order;
    std::size_t width = 4; ///< children per node: 4 (nodes) or 8 (wide_nodes)

    /// Bytes of the nodes held (both widths' arrays, as allocated).
    [[nodiscard]] std::size_t node_bytes() const noexcept {
        return nodes.capacity() * sizeof(bvh_node<4>) + wide_nodes.capacity() * sizeof(bvh_node<8>);
    }
};

/// The size of the ranges that a parallel pass over n items is cut into: n / parts (8 by
/// default), so that a small build is shared out too, but at least `least` items (each
/// range has its cost to hand out) and at most `most`.
[[nodiscard]] constexpr std::size_t bvh_range_size(std::size_t n, std::size_t least, std::size_t most,
                                                   std::size_t parts = 8) noexcept {
    const std::size_t t = n / parts > least ? n / parts : least;
    return t < most ? t : most;
}

/// Runs body(begin, end) through run on the ranges of `size` indices that [0, n) splits into.
template <class F>
void bvh_for_ranges(executor_ref run, std::size_t n, std::size_t size, const F& body) {
    run((n + size - 1) / size, [&](std::size_t c) { body(c * size, n - c * size > size ? c * size + size : n); });
}

/// Binned SAH builder (Wald 2007, "On fast Construction of SAH-based Bounding Volume
/// Hierarchies", IEEE Symposium on Interactive Ray Tracing, §3-4): at each node the
/// primitives' centroids are sorted into equal bins along each axis of their bounds
/// (`bins`, fewer in small nodes: bins_for), and of the planes between bins on the three
/// axes the one of least surface area heuristic cost is taken (Goldsmith, Salmon 1987,
/// "Automatic Creation of Object Hierarchies for Ray Tracing", IEEE CG&A 7(5); MacDonald,
/// Booth 1990, "Heuristics for ray tracing using space subdivision", The Visual Computer 6(3)):
///     cost(split) = C_trav + (A_L N_L + A_R N_R) / A,    cost(leaf) = N,
/// with A the surface areas, N the numbers of primitives (counted in whole blocks of
/// `block` primitives, the width of the leaves' batch tests) and C_trav = 1. A node
/// becomes a leaf when it holds at most max_leaf primitives and the leaf is no more
/// costly, or when all centroids coincide; otherwise it is split (at the median when
/// binning cannot separate the centroids, or below depth median_depth, which bounds the
/// depth and so the traversal's stack).
///
/// In parallel (through an executor, shade/core/parallel.hpp), as Wald 2007 proposes for
/// few cores: nodes of more than t primitives (t = n / 4 for n primitives, at least 256,
/// at most task_size: task_for) are split level by level, the partitions of a level's
/// nodes side by side and, for nodes of more than 4 t, their binning shared out t
/// primitives per task first (a smaller node is binned by the task that partitions it:
/// one synchronisation per level instead of two); each node of at most t primitives then
/// has its subtree built, its primitives' indices written and its nodes planned for the
/// collapse (plan_slots) by one task. Bins merge by min, max and integer
/// sums, which no order changes, and each partition is the recursive build's, so the tree
/// is the same whatever the executor and task_size; through shade::serial_executor the
/// build is the recursive one.
class bvh_builder {
public:
    static constexpr int bins = 16;
    static constexpr int median_depth = 48;
    /// The most primitives per task of the parallel build (see above), unless given.
    static constexpr std::uint32_t default_task_size = 4096;

    /// block: a power of two; task_size > 0.
    bvh_builder(std::uint32_t max_leaf, std::uint32_t block, std::uint32_t task_size = default_task_size)
        : max_leaf_(max_leaf), block_(block), block_shift_(static_cast<std::uint32_t>(std::countr_zero(block))),
          task_size_(task_size) {}

    /// Builds over refs (reordered in place), into nodes of `width` (4 or 8) children,
    /// running the parallel parts through `run`; the same tree whatever it is.
    [[nodiscard]] bvh_tree build(std::vector<bvh_prim_ref>& refs, std::size_t width, executor_ref run) {
        const auto n = static_cast<std::uint32_t>(refs.size());
        const std::size_t size = bvh_range_size(n, 256, default_task_size);
        std::vector<std::array<bvh_box, 2>> part((n + size - 1) / size); // each range's box and centroid box
        refs_ = refs.data();
        bvh_for_ranges(run, n, size, [&](std::size_t begin, std::size_t end) {
            bounds_of(static_cast<std::uint32_t>(begin), static_cast<std::uint32_t>(end), part[begin / size][0],
                      part[begin / size][1]);
        });
        bvh_box box, centroids;
        for (const auto& b : part) box.grow(b[0]), centroids.grow(b[1]);
        return build(refs, width, run, box, centroids);
    }
    /// The same, given the box of refs and the box of their doubled centroids (lo + hi).
    [[nodiscard]] bvh_tree build(std::vector<bvh_prim_ref>& refs, std::size_t width, executor_ref run,
                                 const bvh_box& box, const bvh_box& centroids) {
        bvh_tree tree;
        tree.width = width == 8 ? 8 : 4;
        refs_ = refs.data();
        binary_.clear();
        subtrees_.clear();
        plans_.clear();
        if (refs.empty()) return tree;
        const auto n = static_cast<std::uint32_t>(refs.size());
        binary_.reserve(2 * refs.size() / block_ + 2);
        task_ = task_for(n);
        // Through a serial executor, the recursive build (the same tree, without the level
        // phase's bins and merges).
        tree.order.resize(refs.size());
        if (n <= task_ || run.serial()) {
            build_binary(0, n, 0, box, centroids); // the root is binary_[0]
            for (std::uint32_t i = 0; i < n; ++i) tree.order[i] = refs[i].index();
        } else {
            build_top(n, box, centroids, tree.width, tree.order.data(), run);
        }
        if (tree.width == 8) collapse_root(tree.wide_nodes, 0), visit_orders(tree.wide_nodes, run);
        else collapse_root(tree.nodes, 0);
        return tree;
    }
    /// The same, on the caller's thread.
    [[nodiscard]] bvh_tree build(std::vector<bvh_prim_ref>& refs, std::size_t width = 4) {
        const serial_executor serial;
        return build(refs, width, executor_ref(serial));
    }

private:
    struct binary_node {
        bvh_box box;
        std::uint32_t first = 0; ///< leaf: first primitive; inner: left child
        std::uint32_t count = 0; ///< leaf: number of primitives; inner: 0
        std::uint32_t right = 0; ///< inner: right child
    };

    /// The primitives per task of the level phase for a build over n: n / 4, so that a
    /// small mesh is shared out too, over few levels (each level is a synchronisation of
    /// all threads; a node of at most 4 t primitives, so the root unless t is clamped,
    /// is binned by the task that partitions it),
    /// but no fewer than 256 (each task's bins and merges have their cost) and no more
    /// than task_size.
    [[nodiscard]] std::uint32_t task_for(std::uint32_t n) const noexcept {
        return static_cast<std::uint32_t>(bvh_range_size(n, 256, task_size_, 4));
    }
    /// The tasks of task_ primitives over n, and the range of task c from `first`.
    [[nodiscard]] std::size_t tasks(std::uint32_t n) const noexcept { return (n - 1) / task_ + 1; }
    [[nodiscard]] std::uint32_t task_begin(std::uint32_t first, std::size_t c) const noexcept {
        return first + static_cast<std::uint32_t>(c) * task_;
    }
    [[nodiscard]] std::uint32_t task_end(std::uint32_t first, std::uint32_t end, std::size_t c) const noexcept {
        return end - task_begin(first, c) > task_ ? task_begin(first, c) + task_ : end;
    }

    /// plan_slots's result for one binary node.
    struct slot_plan {
        std::array<float, 8> cost{};        ///< [i - 1]: least cost as at most i children
        std::array<std::uint8_t, 8> left{}; ///< [i - 1]: children from the left subtree; 0: one child, itself
        std::uint8_t node_left = 0;          ///< as a node of its own: children from the left subtree
    };

    [[nodiscard]] std::uint32_t blocks(std::uint32_t n) const noexcept {
        return (n + block_ - 1) >> block_shift_; // block_ = 2^block_shift_
    }
    /// blocks of three counts, as floats in lanes 0-2.
    [[nodiscard]] bvh_v4 blocks3(const std::array<std::uint32_t, 3>& n) const noexcept {
        return bvh_v4{float(blocks(n[0])), float(blocks(n[1])), float(blocks(n[2])), 0.0f};
    }
    /// The half_area of three boxes, in lanes 0-2 (lane 3: 0).
    [[nodiscard]] static bvh_v4 half_areas(const std::array<bvh_box, 3>& b) noexcept {
#if defined(__GNUC__)
        const bvh_v4 e0 = b[0].hi - b[0].lo, e1 = b[1].hi - b[1].lo, e2 = b[2].hi - b[2].lo;
        const bvh_v4 x{e0[0], e1[0], e2[0], 0.0f}, y{e0[1], e1[1], e2[1], 0.0f}, z{e0[2], e1[2], e2[2], 0.0f};
        const bvh_v4 area = x * y + y * z + z * x; // as bvh_box::half_area, lane by lane
        using mask [[gnu::vector_size(16)]] = std::int32_t;
        const mask valid = (x >= 0.0f) & (y >= 0.0f) & (z >= 0.0f); // not empty (nor NaN)
        return reinterpret_cast<bvh_v4>(reinterpret_cast<mask>(area) & valid);
#else
        return bvh_v4{b[0].half_area(), b[1].half_area(), b[2].half_area(), 0.0f};
#endif
    }

    /// Fills every node's visit orders (bvh_visit_orders), in ranges of nodes through run:
    /// apart from the collapse, which runs on the caller alone in a parallel build.
    static void visit_orders(std::vector<bvh_node<8>>& nodes, executor_ref run) {
        bvh_for_ranges(run, nodes.size(), bvh_range_size(nodes.size(), 256, 4096), [&](std::size_t begin, std::size_t end) {
            for (std::size_t i = begin; i < end; ++i) {
                // collapse fills the children from the first; set_empty's leaf marks the rest.
                std::size_t n = 0;
                while (n < 8 && nodes[i].child[n] != make_leaf_ref(0, 0)) ++n;
                bvh_visit_orders(nodes[i], n);
            }
        });
    }

    template <std::size_t W>
    void collapse_root(std::vector<bvh_node<W>>& nodes, std::uint32_t root) {
        if (binary_[root].count > 0) {
            // A single leaf: one root node with one child.
            nodes.emplace_back();
            set_empty(nodes[0]);
            set_child(nodes[0], 0, binary_[root].box, leaf_ref(binary_[root]));
        } else {
            plan_slots(W);
            nodes.reserve(count_nodes<W>(root)); // exactly: no unused capacity is kept
            nodes.emplace_back();
            collapse(nodes, 0, root);
            plans_ = {};
        }
    }

    /// The number of nodes collapse makes for the inner binary node `node`.
    template <std::size_t W>
    [[nodiscard]] std::size_t count_nodes(std::uint32_t node) const {
        std::array<std::uint32_t, W> kids{};
        std::size_t n = 0;
        const std::size_t left = plans_[node].node_left;
        gather(binary_[node].first, left, kids.data(), n);
        gather(binary_[node].right, W - left, kids.data(), n);
        std::size_t total = 1;
        for (std::size_t j = 0; j < n; ++j)
            if (binary_[kids[j]].count == 0) total += count_nodes<W>(kids[j]);
        return total;
    }

    template <std::size_t W>
    static void set_empty(bvh_node<W>& node) noexcept {
        for (auto& plane : node.planes) plane.fill(0.0f);
        for (int k = 0; k < 3; ++k) {
            node.planes[std::size_t(2 * k)].fill(infinity<float>);
            node.planes[std::size_t(2 * k + 1)].fill(-infinity<float>);
        }
        // An empty leaf, not node 0: a ray for which the slab test cannot rule the empty
        // box out (a NaN slab distance, ignored by the test, from an origin or a box beyond
        // the float range) then visits nothing, instead of walking back to the root.
        node.child.fill(make_leaf_ref(0, 0));
    }
    template <std::size_t W>
    static void set_child(bvh_node<W>& node, std::size_t j, const bvh_box& b, std::uint32_t ref) noexcept {
        for (std::size_t k = 0; k < 3; ++k) {
            node.planes[2 * k][j] = b.lo[k];
            node.planes[2 * k + 1][j] = b.hi[k];
        }
        node.child[j] = ref;
    }
    [[nodiscard]] static std::uint32_t leaf_ref(const binary_node& n) noexcept {
        return make_leaf_ref(n.first, n.count);
    }

    /// Fills nodes[index] with the W (or fewer) children plan_slots chose for the binary
    /// node `node`, and every inner one of them with its own node, recursively.
    template <std::size_t W>
    void collapse(std::vector<bvh_node<W>>& nodes, std::size_t index, std::uint32_t node) {
        std::array<std::uint32_t, W> kids{};
        std::size_t n = 0;
        const std::size_t left = plans_[node].node_left;
        gather(binary_[node].first, left, kids.data(), n);
        gather(binary_[node].right, W - left, kids.data(), n);
        set_empty(nodes[index]);
        for (std::size_t j = 0; j < n; ++j) {
            const binary_node& c = binary_[kids[j]];
            std::uint32_t ref;
            if (c.count > 0) {
                ref = leaf_ref(c);
            } else {
                ref = static_cast<std::uint32_t>(nodes.size());
                nodes.emplace_back();
                collapse(nodes, ref, kids[j]);
            }
            set_child(nodes[index], j, c.box, ref);
        }
    }

    /// Appends to kids the children that the binary subtree under `node` becomes when it
    /// may take up to `slots` of them (plans_: itself, or its two subtrees' choices).
    void gather(std::uint32_t node, std::size_t slots, std::uint32_t* kids, std::size_t& n) const {
        const std::size_t left = plans_[node].left[slots - 1];
        if (left == 0) {
            kids[n++] = node;
            return;
        }
        gather(binary_[node].first, left, kids, n);
        gather(binary_[node].right, slots - left, kids, n);
    }

    /// How each binary subtree is best spread over the children of wide nodes, by dynamic
    /// programming from the leaves up (the conversion of a binary BVH in Ylitie, Karras,
    /// Laine 2017, "Efficient Incoherent Ray Traversal on GPUs Through Compressed Wide
    /// BVHs", HPG, here with the binary build's leaves kept as they are): cost[i - 1] is the
    /// least surface area heuristic cost of the subtree as at most i children of one node,
    /// a leaf costing its area times its blocks and an inner node of its own its area
    /// (C_trav = 1, as in the build) plus the cheapest split of its W children between its
    /// two subtrees. Partly filled nodes then go where they cost least, which fills the
    /// many nodes next to the leaves.
    ///
    /// Children come after their parent, so a walk down the indices meets them first. The
    /// nodes of the parallel build's subtree tasks (subtrees_) are planned by those tasks
    /// (build_top); here the rest.
    void plan_slots(std::size_t width) {
        plans_.resize(binary_.size());
        for (std::size_t m = subtrees_.empty() ? binary_.size() : subtrees_[0][1]; m-- > 0;) plan_node(m, width);
    }

    /// plan_slots's plan of binary node m, whose children's plans are made.
    void plan_node(std::size_t m, std::size_t width) noexcept {
        const binary_node& b = binary_[m];
        slot_plan& p = plans_[m];
        const float area = b.box.half_area();
        if (b.count > 0) {
            p.cost.fill(area * float(blocks(b.count)));
            return;
        }
        const slot_plan& l = plans_[b.first];
        const slot_plan& r = plans_[b.right];
        std::array<float, 8> open{};
        std::array<std::uint8_t, 8> open_left{};
        for (std::size_t i = 2; i <= width; ++i) {
            // Half each way unless a split costs less (also where the costs are
            // infinite or NaN, from boxes beyond the float range).
            open[i - 1] = infinity<float>;
            open_left[i - 1] = static_cast<std::uint8_t>(i / 2);
            for (std::size_t k = 1; k < i; ++k) {
                const float c = l.cost[k - 1] + r.cost[i - k - 1];
                if (c < open[i - 1]) {
                    open[i - 1] = c;
                    open_left[i - 1] = static_cast<std::uint8_t>(k);
                }
            }
        }
        p.node_left = open_left[width - 1];
        p.cost[0] = area + open[width - 1];
        for (std::size_t i = 2; i <= width; ++i) {
            // Opened where no costlier than fewer children: fewer nodes on a tie.
            const bool opened = open[i - 1] <= p.cost[i - 2];
            p.cost[i - 1] = opened ? open[i - 1] : p.cost[i - 2];
            p.left[i - 1] = opened ? open_left[i - 1] : p.left[i - 2];
        }
    }

    std::uint32_t make_leaf(const bvh_box& box, std::uint32_t begin, std::uint32_t end) {
        binary_.push_back(binary_node{box, begin, end - begin, 0});
        return static_cast<std::uint32_t>(binary_.size() - 1);
    }

    /// The box and the centroid box (of doubled centroids, lo + hi) of refs_[begin, end).
    void bounds_of(std::uint32_t begin, std::uint32_t end, bvh_box& box, bvh_box& centroids) const noexcept {
        for (std::uint32_t i = begin; i < end; ++i) {
            const bvh_prim_ref& r = refs_[i];
            box.grow(r.lo, r.hi);
            const bvh_v4 c = r.centroid2();
            centroids.grow(c, c);
        }
    }

    /// The primitives' boxes and counts per axis and bin.
    struct bin_set {
        std::array<std::array<bvh_box, bins>, 3> box;
        std::array<std::array<std::uint32_t, bins>, 3> count;
    };
    /// bin_into's sets of bins, merged into the first.
    using bin_sets = std::array<bin_set, 4>;

    /// Builds the binary subtree over refs_[begin, end), whose box and centroid box are
    /// given; returns its node's index.
    std::uint32_t build_binary(std::uint32_t begin, std::uint32_t end, int depth, const bvh_box& box,
                               const bvh_box& centroids) {
        const split_result s = split(begin, end, depth, box, centroids, nullptr);
        if (s.leaf) return make_leaf(box, begin, end);
        const auto index = static_cast<std::uint32_t>(binary_.size());
        binary_.push_back(binary_node{box, 0, 0, 0});
        const std::uint32_t left = build_binary(begin, s.mid, depth + 1, s.left_box, s.left_centroids);
        const std::uint32_t right = build_binary(s.mid, end, depth + 1, s.right_box, s.right_centroids);
        binary_[index].first = left;
        binary_[index].right = right;
        return index;
    }

    /// A node of the parallel build's levels: its primitives, depth, boxes and binary_ index.
    struct pending {
        std::uint32_t begin, end;
        int depth;
        bvh_box box, centroids;
        std::uint32_t node;
    };

    /// The parallel build of the binary tree over the n > task_size primitives (see the
    /// class comment), the root at binary_[0]: the nodes of more than task_size
    /// primitives level by level, then the smaller ones' subtrees, one task each, whose
    /// nodes are appended (children after their parent, as plan_slots needs). Each subtree
    /// task also writes its primitives' indices to order and plans its nodes for nodes of
    /// `width` children (plan_slots). A node of at most 4 tasks' primitives is binned by
    /// the task that splits it, so a level of such nodes takes one run, not two.
    void build_top(std::uint32_t n, const bvh_box& box, const bvh_box& centroids, std::size_t width,
                   std::uint32_t* order, executor_ref run) {
        binary_.push_back(binary_node{box, 0, 0, 0});
        std::vector<pending> level{pending{0, n, 0, box, centroids, 0}}, subtrees;
        subtrees_.clear();
        while (!level.empty()) {
            // The bins of the level's larger nodes, task_size primitives per task (none below
            // median_depth, split at the median).
            std::vector<std::size_t> first(level.size() + 1, 0);
            std::vector<std::uint32_t> owner;
            const auto shared = [&](const pending& p) { return p.depth < median_depth && p.end - p.begin > 4 * task_; };
            for (std::size_t i = 0; i < level.size(); ++i) {
                first[i + 1] = first[i] + (shared(level[i]) ? tasks(level[i].end - level[i].begin) : 0);
                owner.resize(first[i + 1], static_cast<std::uint32_t>(i));
            }
            std::vector<bin_sets> binned(first.back());
            run(binned.size(), [&](std::size_t c) {
                const pending& p = level[owner[c]];
                const std::size_t nb = bins_for(p.end - p.begin);
                bin_into(task_begin(p.begin, c - first[owner[c]]), task_end(p.begin, p.end, c - first[owner[c]]),
                         p.centroids.lo, bin_scale(p.centroids, nb), nb, binned[c]);
            });
            std::vector<split_result> split_of(level.size());
            run(level.size(), [&](std::size_t i) {
                const pending& p = level[i];
                const std::size_t nb = bins_for(p.end - p.begin);
                for (std::size_t c = first[i] + 1; c < first[i + 1]; ++c) merge_bins(binned[first[i]][0], binned[c][0], nb);
                if (first[i] < first[i + 1] || p.depth >= median_depth) {
                    split_of[i] = split(p.begin, p.end, p.depth, p.box, p.centroids,
                                        first[i] < first[i + 1] ? &binned[first[i]][0] : nullptr);
                } else {
                    // Binned here, into bins of this task's own (bins_ is not to be shared).
                    bin_sets own;
                    bin_into(p.begin, p.end, p.centroids.lo, bin_scale(p.centroids, nb), nb, own);
                    split_of[i] = split(p.begin, p.end, p.depth, p.box, p.centroids, &own[0]);
                }
            });
            std::vector<pending> next;
            for (std::size_t i = 0; i < level.size(); ++i) {
                const pending& p = level[i];
                const split_result& s = split_of[i];
                if (s.leaf) {
                    binary_[p.node] = binary_node{p.box, p.begin, p.end - p.begin, 0};
                    continue;
                }
                const auto left = static_cast<std::uint32_t>(binary_.size());
                binary_.resize(binary_.size() + 2); // the children, filled below or by a task
                binary_[p.node] = binary_node{p.box, left, 0, left + 1};
                for (const pending& c : {pending{p.begin, s.mid, p.depth + 1, s.left_box, s.left_centroids, left},
                                         pending{s.mid, p.end, p.depth + 1, s.right_box, s.right_centroids, left + 1}})
                    (c.end - c.begin > task_ ? next : subtrees).push_back(c);
            }
            level = std::move(next);
        }
        // The subtrees in the order of their primitives, as each level's nodes are: an
        // executor that deals a run's tasks to its threads in index order (a part from the
        // front to one, from the back to another) then gives a thread the subtrees of about
        // the nodes it partitioned, whose primitives are in its core's caches.
        // (An insertion sort: a few dozen subtrees, mostly in order already.)
        for (std::size_t i = 1; i < subtrees.size(); ++i)
            for (std::size_t j = i; j > 0 && subtrees[j].begin < subtrees[j - 1].begin; --j)
                std::swap(subtrees[j], subtrees[j - 1]);
        std::vector<std::vector<binary_node>> part(subtrees.size());
        std::vector<std::vector<slot_plan>> part_plans(subtrees.size());
        run(part.size(), [&](std::size_t i) {
            const pending& p = subtrees[i];
            bvh_builder b(max_leaf_, block_, task_size_);
            b.refs_ = refs_;
            b.binary_.reserve(2 * (p.end - p.begin) / block_ + 2);
            b.build_binary(p.begin, p.end, p.depth, p.box, p.centroids);
            for (std::uint32_t j = p.begin; j < p.end; ++j) order[j] = refs_[j].index();
            // Plans hold no node indices: made on the local numbering, they hold at the nodes' places.
            b.plans_.resize(b.binary_.size());
            for (std::size_t m = b.binary_.size(); m-- > 0;) b.plan_node(m, width);
            part[i] = std::move(b.binary_);
            part_plans[i] = std::move(b.plans_);
        });
        std::size_t total = binary_.size();
        for (const auto& q : part) total += q.size() - 1;
        plans_.resize(total);
        for (std::size_t i = 0; i < part.size(); ++i) {
            // Local node j: the task's root (0) at its place, the others appended.
            const auto offset = static_cast<std::uint32_t>(binary_.size()) - 1;
            const auto place = [&](std::uint32_t j) { return j == 0 ? subtrees[i].node : offset + j; };
            subtrees_.push_back({subtrees[i].node, offset + 1, offset + static_cast<std::uint32_t>(part[i].size())});
            for (std::uint32_t j = 0; j < part[i].size(); ++j) {
                binary_node b = part[i][j];
                if (b.count == 0) b.first = place(b.first), b.right = place(b.right);
                plans_[place(j)] = part_plans[i][j];
                if (j == 0) binary_[subtrees[i].node] = b;
                else binary_.push_back(b);
            }
        }
    }

    /// How a node is split: a leaf, or at mid with both sides' boxes.
    struct split_result {
        bool leaf = true;
        std::uint32_t mid = 0;
        bvh_box left_box, left_centroids, right_box, right_centroids;
    };

    /// The scale of binning into nb bins: bin = floor((c - centroids.lo) scale) per axis,
    /// 0 on an axis without extent.
    [[nodiscard]] static bvh_v4 bin_scale(const bvh_box& centroids, std::size_t nb) noexcept {
        bvh_v4 scale{0.0f, 0.0f, 0.0f, 0.0f};
        for (std::size_t k = 0; k < 3; ++k) {
            const float extent = centroids.hi[k] - centroids.lo[k];
            // Slightly under nb / extent, so the largest centroid falls in the last bin.
            scale[k] = extent > 0.0f ? float(nb) * 0.99999f / extent : 0.0f;
        }
        return scale;
    }

    /// Decides how refs_[begin, end) (its box and centroid box given) is split and, if
    /// split, partitions it; its bins are `binned` when given (bin_into's, with bins_for
    /// and bin_scale), else made here in bins_.
    split_result split(std::uint32_t begin, std::uint32_t end, int depth, const bvh_box& box,
                       const bvh_box& centroids, const bin_set* binned) {
        split_result result;
        const std::uint32_t n = end - begin;
        // A leaf without binning where no split can win: at most max_leaf primitives in one
        // block cost area x 1 as a leaf, a split area + (A_L N_L + A_R N_R) >= area (the
        // leaf wins ties), so the binning below would end in the same leaf.
        if (n <= max_leaf_ && n <= block_) return result;

        std::uint32_t mid = begin;
        bool found = false;
        bvh_box left_box, left_centroids, right_box, right_centroids;
        if (depth < median_depth) {
            // Bin the centroids on every axis with extent: bin = floor((c - lo) scale).
            const std::size_t nb = bins_for(n);
            const bvh_v4 scale = bin_scale(centroids, nb);
            const bvh_v4 c_lo = centroids.lo;
            if (binned == nullptr) bin_into(begin, end, c_lo, scale, nb, bins_);
            const auto& bin_box = (binned ? *binned : bins_[0]).box;
            const auto& bin_count = (binned ? *binned : bins_[0]).count;
            // Sweep, axis k in lane k: cost[j] = (A N of bins < j) + (A N of bins >= j),
            // infinite where one side is empty or the axis has no extent.
            std::array<bvh_v4, bins> right_cost; // [1, nb) written below before it is read
            std::array<bvh_v4, bins> cost; // likewise
            std::array<bvh_box, 3> acc{};
            std::array<std::uint32_t, 3> count{};
            for (std::size_t j = nb - 1; j > 0; --j) {
                for (std::size_t k = 0; k < 3; ++k) {
                    acc[k].grow(bin_box[k][j]);
                    count[k] += bin_count[k][j];
                }
                right_cost[j] = half_areas(acc) * blocks3(count);
            }
            acc = {};
            count = {};
            for (std::size_t j = 1; j < nb; ++j) {
                for (std::size_t k = 0; k < 3; ++k) {
                    acc[k].grow(bin_box[k][j - 1]);
                    count[k] += bin_count[k][j - 1];
                }
                cost[j] = half_areas(acc) * blocks3(count) + right_cost[j];
                for (std::size_t k = 0; k < 3; ++k)
                    if (count[k] == 0 || count[k] == n || !(scale[k] > 0.0f)) cost[j][k] = infinity<float>;
            }
            // The least cost, the first one in the order axis by axis, split by split.
            float best_cost = infinity<float>;
            std::size_t best_axis = 0, best_split = 0;
            for (std::size_t k = 0; k < 3; ++k)
                for (std::size_t j = 1; j < nb; ++j)
                    if (cost[j][k] < best_cost) {
                        best_cost = cost[j][k];
                        best_axis = k;
                        best_split = j;
                    }
            if (best_cost < infinity<float>) {
                const float area = box.half_area();
                const float split_cost = area + best_cost; // C_trav A + (A_L N_L + A_R N_R)
                const float leaf_cost = area * float(blocks(n));
                if (n <= max_leaf_ && leaf_cost <= split_cost) return result;
                // Partition (Hoare), gathering both sides' centroid boxes on the way. A
                // primitive goes left when its bin (bin_into's) is below best_split, an
                // integer in [1, nb - 1]: for the scaled coordinate x that is
                // !(x >= best_split) (the clamp to [0, nb - 1] and the truncation change no
                // side; a NaN x, bin 0, goes left). So each side's box is its bins' union on
                // the split axis (min and max: the same floats as over its primitives).
                for (std::size_t b = 0; b < nb; ++b) (b < best_split ? left_box : right_box).grow(bin_box[best_axis][b]);
                const float lo = c_lo[best_axis], sc = scale[best_axis];
                const auto plane = static_cast<float>(best_split);
                const auto on = [&](auto axis) {
                    return partition<decltype(axis)::value>(begin, end, lo, sc, plane, left_centroids, right_centroids);
                };
                mid = best_axis == 0   ? on(std::integral_constant<std::size_t, 0>{})
                      : best_axis == 1 ? on(std::integral_constant<std::size_t, 1>{})
                                       : on(std::integral_constant<std::size_t, 2>{});
                found = mid > begin && mid < end;
            } else if (n <= max_leaf_) {
                return result; // all centroids coincide
            }
        }
        if (!found) {
            if (n <= max_leaf_) return result;
            // Median split on the widest centroid axis (or by index when they coincide).
            std::size_t axis = 0;
            for (std::size_t k = 1; k < 3; ++k)
                if (centroids.hi[k] - centroids.lo[k] > centroids.hi[axis] - centroids.lo[axis]) axis = k;
            mid = begin + n / 2;
            select_nth(begin, mid, end, axis);
            left_box = left_centroids = right_box = right_centroids = bvh_box{};
            bounds_of(begin, mid, left_box, left_centroids);
            bounds_of(mid, end, right_box, right_centroids);
        }
        return split_result{false, mid, left_box, left_centroids, right_box, right_centroids};
    }

    /// Partitions refs_[begin, end) (Hoare) into those whose scaled doubled centroid on
    /// Axis, (c - lo) sc, is not >= plane (NaN included), then the others; returns where the
    /// second side starts, and grows left and right by each side's doubled centroids. The
    /// axis is a template argument so that the coordinate is a lane of the centroid, not a
    /// load at an offset known only at run time; the same floats either way.
    template <std::size_t Axis>
    std::uint32_t partition(std::uint32_t begin, std::uint32_t end, float lo, float sc, float plane, bvh_box& left,
                            bvh_box& right) noexcept {
        bvh_prim_ref* i = refs_ + begin;
        bvh_prim_ref* j = refs_ + end;
        for (;;) {
            for (; i < j; ++i) {
                const bvh_v4 c = i->centroid2();
                if ((c[Axis] - lo) * sc >= plane) break;
                left.grow(c, c);
            }
            for (; i < j; --j) {
                const bvh_v4 c = j[-1].centroid2();
                if (!((c[Axis] - lo) * sc >= plane)) break;
                right.grow(c, c);
            }
            if (i >= j) break;
            std::swap(*i, j[-1]);
        }
        return static_cast<std::uint32_t>(i - refs_);
    }

    /// Bins for a node of n primitives: 4 + n / 20, at most `bins` (the rule of Embree's
    /// builder, Wald et al. 2014, "Embree: A Kernel Framework for Efficient CPU Ray
    /// Tracing", ACM TOG 33(4), in kernels/builders/heuristic_binning.h): cheaper small nodes.
    [[nodiscard]] static std::size_t bins_for(std::uint32_t n) noexcept {
        const std::size_t nb = 4 + n / 20;
        return nb < bins ? nb : std::size_t(bins);
    }

    /// The first nb bins of `into` grown by those of `other`.
    static void merge_bins(bin_set& into, const bin_set& other, std::size_t nb) noexcept {
        for (std::size_t k = 0; k < 3; ++k)
            for (std::size_t j = 0; j < nb; ++j) {
                into.box[k][j].grow(other.box[k][j]);
                into.count[k][j] += other.count[k][j];
            }
    }

    /// Fills out[0] with refs_[begin, end) binned on each axis into nb bins: the bin of a
    /// scaled centroid coordinate x is x clamped to [0, nb - 1] and truncated (a NaN x, from
    /// infinite bounds, lands in bin 0, never in a conversion).
    /// Successive primitives often share a bin, whose box then grows through a chain of
    /// loads and stores: from 64 on, they go round two sets of bins, from 256 on round all
    /// four (out[i % 4]), merged at the end (exactly: min, max and integer sums).
    void bin_into(std::uint32_t begin, std::uint32_t end, const bvh_v4& c_lo, const bvh_v4& scale, std::size_t nb,
                  bin_sets& out) const noexcept {
        const std::size_t sets = end - begin >= 256 ? 4 : end - begin >= 64 ? 2 : 1;
        for (std::size_t s = 0; s < sets; ++s)
            for (std::size_t k = 0; k < 3; ++k)
                for (std::size_t j = 0; j < nb; ++j) {
                    out[s].box[k][j] = bvh_box{};
                    out[s].count[k][j] = 0;
                }
        const bvh_v4 zero{0.0f, 0.0f, 0.0f, 0.0f};
        const auto top = float(nb - 1);
        const bvh_v4 last{top, top, top, top};
        const bvh_v4 c_lo_v = c_lo, scale_v = scale; // copies: not reloaded after the stores
        const auto bin_one = [&](bin_set& set, const bvh_prim_ref& r) {
            const bvh_v4 lo = r.lo, hi = r.hi; // copies: no reload after the stores
            // Clamped without branches (a NaN lane gives 0), then truncated.
            const std::array<std::uint32_t, 4> b = bvh_truncate(bvh_vmin(bvh_vmax_clamp((lo + hi - c_lo_v) * scale_v, zero), last));
            // Each bin through one pointer, both bounds loaded before either is stored (two
            // indexings of the array had g++ form the address twice).
            const auto grow = [&](bvh_box* bin) {
                const bvh_v4 l = bvh_vmin(bin->lo, lo), h = bvh_vmax(bin->hi, hi);
                bin->lo = l;
                bin->hi = h;
            };
            grow(set.box[0].data() + b[0]); // unrolled by hand (-O2 does not)
            grow(set.box[1].data() + b[1]);
            grow(set.box[2].data() + b[2]);
            ++set.count[0][b[0]], ++set.count[1][b[1]], ++set.count[2][b[2]];
        };
        // Walked by pointer (one increment per step, not an index scaled per reference).
        const bvh_prim_ref* r = refs_ + begin;
        const bvh_prim_ref* const last_ref = refs_ + end;
        if (sets == 4) {
            for (; last_ref - r >= 4; r += 4) {
                bin_one(out[0], r[0]);
                bin_one(out[1], r[1]);
                bin_one(out[2], r[2]);
                bin_one(out[3], r[3]);
            }
        } else if (sets == 2) {
            for (; last_ref - r >= 2; r += 2) {
                bin_one(out[0], r[0]);
                bin_one(out[1], r[1]);
            }
        }
        for (; r != last_ref; ++r) bin_one(out[0], *r);
        for (std::size_t s = 1; s < sets; ++s) merge_bins(out[0], out[s], nb);
    }

    /// Reorders refs_[begin, end) so that refs_[mid] holds the reference whose doubled
    /// centroid on `axis` would be there after sorting, with none greater before it and
    /// none smaller after it (Hoare 1961, "Algorithm 65: Find", CACM 4(7): partition
    /// around a median-of-three pivot, then continue in the side holding mid). Expected
    /// linear time; written here so the builder needs no <algorithm>.
    void select_nth(std::uint32_t begin, std::uint32_t mid, std::uint32_t end, std::size_t axis) noexcept {
        auto key = [&](std::uint32_t i) { return refs_[i].centroid2()[axis]; };
        while (end - begin > 2) {
            // Median of the first, middle and last keys as the pivot value.
            const std::uint32_t m = begin + (end - begin) / 2;
            const float a = key(begin), b = key(m), c = key(end - 1);
            const float pivot = a < b ? (b < c ? b : (a < c ? c : a)) : (a < c ? a : (b < c ? c : b));
            std::uint32_t i = begin, j = end - 1;
            for (;;) { // Hoare partition: [begin, i) <= pivot, (j, end) >= pivot
                while (key(i) < pivot) ++i;
                while (pivot < key(j)) --j;
                if (i >= j) break;
                std::swap(refs_[i], refs_[j]);
                ++i;
                --j;
            }
            // Now [begin, j] <= pivot <= [j + 1, end), both sides non-empty.
            if (mid <= j) end = j + 1;
            else begin = j + 1;
        }
        if (end - begin == 2 && key(begin + 1) < key(begin)) std::swap(refs_[begin], refs_[begin + 1]);
    }

    std::uint32_t max_leaf_;
    std::uint32_t block_;
    std::uint32_t block_shift_;
    std::uint32_t task_size_;
    std::uint32_t task_ = 0; // the current build's primitives per task (task_for)
    bvh_prim_ref* refs_ = nullptr;
    std::vector<binary_node> binary_;
    std::vector<slot_plan> plans_;
    /// build_top's subtree tasks: the root's index and the range [begin, end) of the others.
    std::vector<std::array<std::uint32_t, 3>> subtrees_;
    bin_sets bins_; // the serial build's bins (bin_into's out)
};


/// The references of primitives 0 .. n-1, whose boxes box_of(i) gives (an aabb), made
/// through run, and the least i with !valid(i) (n if none: then every box was made, and
/// box and centroids bound the references and their doubled centroids, for
/// bvh_builder::build).
struct bvh_prim_refs {
    std::vector<bvh_prim_ref> refs;
    std::size_t first_invalid;
    bvh_box box, centroids;
};
template <class Box, class Valid>
[[nodiscard]] bvh_prim_refs make_prim_refs(executor_ref run, std::size_t n, const Box& box_of, const Valid& valid) {
    bvh_prim_refs r{std::vector<bvh_prim_ref>(n), n, {}, {}};
    // Ranges of the parallel build's task size t (bvh_builder::task_for with the default
    // task size), so that the root's binning tasks read ranges made by one task each; one
    // range where the root is binned and partitioned by one task (n <= 4 t): references
    // made on another core would then cost that task their trip between the cores'
    // caches, more than making them on two threads saves.
    const std::size_t t = bvh_range_size(n, 256, bvh_builder::default_task_size, 4);
    const std::size_t size = n <= 4 * t ? 4 * t : t;
    std::vector<std::size_t> invalid((n + size - 1) / size, n);
    std::vector<std::array<bvh_box, 2>> part(invalid.size()); // each range's box and centroid box
    bvh_for_ranges(run, n, size, [&](std::size_t begin, std::size_t end) {
        bvh_box box, centroids;
        for (std::size_t i = begin; i < end; ++i) {
            if (!valid(i)) {
                invalid[begin / size] = i;
                return;
            }
            const bvh_prim_ref ref = make_prim_ref(box_of(i), static_cast<std::uint32_t>(i));
            r.refs[i] = ref;
            box.grow(ref.lo, ref.hi);
            const bvh_v4 c = ref.centroid2();
            centroids.grow(c, c);
        }
        part[begin / size] = {box, centroids};
    });
    for (const std::size_t i : invalid) r.first_invalid = i < r.first_invalid ? i : r.first_invalid;
    for (const auto& b : part) r.box.grow(b[0]), r.centroids.grow(b[1]);
    return r;
}

/// Throws shade::invalid_parameter naming `parameter` unless there are fewer than 2^27
/// primitives (the leaf references' index field).
inline void require_bvh_size(const char* parameter, std::size_t n) {
    if (n >= bvh_max_items)
        throw invalid_parameter(parameter, "must hold fewer than 2^27 primitives", std::to_string(n));
}

} // namespace shade::detail
