#pragma once
// shade::triangle_bvh: a bounding-volume hierarchy over triangles (a mesh), whose leaves
// are tested with the SIMD batch kernel (shade::triangle_batch) for Möller-Trumbore, or
// triangle by triangle with another algorithm (shade::watertight).
//
// Usage:
//     std::vector<shade::triangle<float>> tris = ...;
//     const shade::triangle_bvh<float> mesh(tris);                 // Möller-Trumbore
//     if (auto h = mesh.closest(r))                                 // nearest hit
//         use(h->primitive, h->hit.t, h->hit.p, h->hit.n, h->hit.barycentric);
//     if (auto x = mesh.find_closest(r))          // the same hit without p, n, dpdu, p_error
//         if (needs_record(x->primitive, x->hit.t)) use(mesh.make_hit(*x)); // closest's record
//     const bool shadowed = mesh.any(shadow_ray);
//     const shade::triangle_bvh<double, shade::watertight> closed(tris_d); // no leaks
//     const shade::triangle_bvh<float> fast(tris, shade::bvh_width::automatic, threads);
//         // built in parallel by an executor (shade/core/parallel.hpp): the same hierarchy
//
// closest() returns exactly what a loop of find_intersection<Algorithm> over all the
// triangles keeps as nearest, with shade::make_hit's record (the hierarchy's box tests
// are conservative; the batch gives the scalar test's bits): the same t and record, and
// the same triangle unless several are hit at the very same t, whenever the real point
// o + t d of that hit lies in its triangle's bounding box, as shade/geometry/bvh.hpp
// states (a Möller-Trumbore hit reported by rounding just off an edge may lie outside).

#include <array>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <new>
#include <optional>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include <shade/core/error.hpp>
#include <shade/core/parallel.hpp>
#include <shade/core/types.hpp>
#include <shade/geometry/aabb.hpp>
#include <shade/geometry/detail/bvh_build.hpp>
#include <shade/geometry/detail/bvh_traverse.hpp>
#include <shade/geometry/hit.hpp>
#include <shade/geometry/ray.hpp>
#include <shade/geometry/triangle.hpp>
#include <shade/geometry/triangle_batch.hpp>

#if defined(__GNUC__)
// Forced inline, so that g++ inlines the AVX kernel's own AVX helpers once the leaf test is
// in the walk compiled for AVX (see triangle_bvh::test).
#define SHADE_DETAIL_LEAF_INLINE __attribute__((always_inline))
#else
#define SHADE_DETAIL_LEAF_INLINE
#endif

namespace shade {

namespace detail {

/// The allocator of triangle_bvh's leaf blocks: aligned operator new, and construct()
/// without arguments default-initialises, which for a trivially default-constructible
/// block writes nothing, so that std::vector::resize allocates the blocks without zeroing
/// them on the calling thread (the tasks that fill them touch their memory first, each in
/// its own core's cache).
template <class T>
struct leaf_allocator {
    using value_type = T;
    leaf_allocator() noexcept = default;
    template <class U>
    leaf_allocator(const leaf_allocator<U>&) noexcept {}
    [[nodiscard]] T* allocate(std::size_t n) {
        return static_cast<T*>(::operator new(n * sizeof(T), std::align_val_t(alignof(T))));
    }
    void deallocate(T* p, std::size_t) noexcept { ::operator delete(p, std::align_val_t(alignof(T))); }
    template <class U, class... Args>
    void construct(U* p, Args&&... args) {
        if constexpr (sizeof...(Args) == 0)
            ::new (static_cast<void*>(p)) U;
        else
            ::new (static_cast<void*>(p)) U(static_cast<Args&&>(args)...);
    }
    template <class U>
    [[nodiscard]] bool operator==(const leaf_allocator<U>&) const noexcept {
        return true;
    }
};

} // namespace detail

/// A hierarchy over a copy of a list of triangles, intersected with Algorithm (a
/// shade::triangle_algorithm; Möller-Trumbore by default, whose leaves run the batch
/// kernel on leaf_width triangles at a time).
template <std::floating_point T, class Algorithm = moller_trumbore>
    requires triangle_algorithm<Algorithm, T>
class triangle_bvh {
public:
    using scalar_type = T;
    /// True when the leaves are tested with shade::triangle_batch.
    static constexpr bool batched = std::is_same_v<Algorithm, moller_trumbore>;
    /// Triangles per batch test in a leaf: 32 bytes of each coordinate, one AVX step (8
    /// floats or 4 doubles; 1 for the scalar algorithms).
    static constexpr std::size_t leaf_width = batched ? 32 / sizeof(T) : 1;

private:
    static constexpr std::size_t batch_width = 32 / sizeof(T);
    using leaf_vertices = detail::vertex_batch<T, batch_width>;

public:

    /// An empty hierarchy: nothing is ever hit.
    triangle_bvh() = default;

    /// Builds over a copy of triangles, into nodes of `width` children. Throws
    /// shade::invalid_parameter naming "triangles" when a vertex is not finite (NaN or
    /// infinite), or for 2^27 triangles or more. Degenerate ones are kept and never hit.
    explicit triangle_bvh(std::span<const triangle<T>> triangles, bvh_width width = bvh_width::automatic)
        : triangle_bvh(triangles, width, serial_executor{}) {}

    /// The same build, its parallel parts run by the executor `run` (see
    /// shade/core/parallel.hpp): the same hierarchy whatever the executor.
    template <parallel_executor E>
    triangle_bvh(std::span<const triangle<T>> triangles, bvh_width width, E&& run) {
        build(triangles, width, detail::executor_ref(run));
    }

    /// A nearest hit without its full record, from find_closest: the index of the triangle
    /// in the list given, the intersection as the triangle algorithm's find returns it (t,
    /// barycentrics, front_face), and where this hierarchy holds the triangle (slot, which
    /// only make_hit of the same hierarchy reads).
    struct intersection {
        std::uint32_t primitive = 0;    ///< index of the triangle in the list given
        triangle_intersection<T> hit{}; ///< t, barycentrics (b0, b1, b2) and front_face
        std::uint32_t slot = 0;         ///< the triangle's place in this hierarchy's leaves
    };

    /// The nearest hit of r (double-sided unless cull is culling::back_faces) without the
    /// record's point, normal, parameterisation and error bound: the triangle's index, t,
    /// barycentrics and front_face, exactly those of closest(r, cull) (which is
    /// make_hit(*find_closest(r, cull))), or nothing. For callers that need the record of
    /// some hits only, or none.
    [[nodiscard]] std::optional<intersection> find_closest(const ray<T>& r, culling cull = culling::none) const {
        triangle_intersection<T> x;
        const std::uint32_t slot = walk(r, cull, x);
        if (slot == no_hit) return std::nullopt;
        return intersection{id_of(slot), x, slot};
    }

    /// The full record of a hit that find_closest of this hierarchy returned: its
    /// primitive and shade::make_hit's record of the triangle and intersection (t, p, n,
    /// front_face, uv, dpdu, p_error, barycentrics): what closest() returns for that ray.
    /// Precondition: h came from this hierarchy (unchanged since).
    [[nodiscard]] primitive_hit<triangle_hit<T>> make_hit(const intersection& h) const noexcept {
        return {h.primitive, record(h.slot, h.hit)};
    }

    /// The nearest hit of r (double-sided unless cull is culling::back_faces): the index
    /// of the triangle in the list given and shade::make_hit's record (t, p, n,
    /// front_face, barycentrics), or nothing: make_hit(*find_closest(r, cull)).
    [[nodiscard]] std::optional<primitive_hit<triangle_hit<T>>> closest(const ray<T>& r,
                                                                       culling cull = culling::none) const {
        triangle_intersection<T> x;
        const std::uint32_t slot = walk(r, cull, x);
        if (slot == no_hit) return std::nullopt;
        return primitive_hit<triangle_hit<T>>{id_of(slot), record(slot, x)};
    }

    /// True when r hits some triangle within [t_min, t_max] (for shadow rays).
    [[nodiscard]] bool any(const ray<T>& r, culling cull = culling::none) const {
        if (size_ == 0) return false; // nothing to hit (the walk turns an invalid ray away)
        bool found = false;
        const auto* const data = leaf_data();
        const auto leaf = [&, data, cull](std::uint32_t first, std::uint32_t count, auto avx) SHADE_DETAIL_LEAF_INLINE {
            if constexpr (batched) {
                for (std::uint32_t b = first; b < first + count; ++b)
                    if (test_any(r, data[b].batch, cull, avx)) return found = true;
            } else {
                for (std::uint32_t i = first; i < first + count; ++i)
                    if (Algorithm::find(r, data[i], cull)) return found = true;
            }
            return false;
        };
        // Nearest child first, as for closest hits: a blocker is found after fewer nodes;
        // the others unsorted (sorting them costs more than the nodes it saves), and
        // prefetched when stacked (nearly all of them are visited unless a blocker is found).
        constexpr std::size_t item_bytes = batched ? sizeof(leaf_batch) : sizeof(triangle<T>);
        detail::bvh_traverse<detail::bvh_order::nearest, true, item_bytes>(tree_, r, r.t_max, leaf, data);
        return found;
    }

    /// Number of triangles.
    [[nodiscard]] std::size_t size() const noexcept { return size_; }
    /// Number of nodes (of up to node_width() children each).
    [[nodiscard]] std::size_t node_count() const noexcept { return tree_.nodes.size() + tree_.wide_nodes.size(); }
    /// Children per node: 4 or 8 (see shade::bvh_width).
    [[nodiscard]] std::size_t node_width() const noexcept { return tree_.width; }
    /// Bytes held on the heap, as allocated: the nodes (128 bytes each with four children,
    /// 256 with eight) and the leaf data, all that is kept of the triangles: batched, a
    /// leaf_bytes block per leaf_width triangles of a leaf; else each triangle and its index.
    [[nodiscard]] std::size_t memory_bytes() const noexcept {
        return tree_.node_bytes() + leaves_.capacity() * sizeof(leaf_batch) +
               triangles_.capacity() * sizeof(triangle<T>) + ids_.capacity() * sizeof(std::uint32_t);
    }

private:
    static constexpr std::uint32_t no_hit = ~std::uint32_t(0);

    /// The walk of find_closest and closest: the nearest hit's slot (no_hit when there is
    /// none), its intersection written to x (left as it was on a miss; written in place,
    /// not returned, so that the caller's record is made from it without a copy).
    [[nodiscard]] std::uint32_t walk(ray<T> r, culling cull, triangle_intersection<T>& x) const {
        if (size_ == 0) return no_hit; // nothing to hit (the walk turns an invalid ray away)
        std::uint32_t best = no_hit;
        // The leaf data and cull held in the leaf function itself (one load each in a leaf).
        const auto* const data = leaf_data();
        const auto leaf = [&, data, cull](std::uint32_t first, std::uint32_t count, auto avx) SHADE_DETAIL_LEAF_INLINE {
            if constexpr (batched) {
                for (std::uint32_t b = first; b < first + count; ++b) {
                    // The line of the indices, fetched with the batch's (the lane is not
                    // known yet): one latency for both in a hierarchy beyond the caches.
                    detail::bvh_prefetch(data[b].id.data());
                    const auto hits = test(r, data[b].batch, cull, avx);
                    if (hits.hit_bits == 0) continue;
                    const std::size_t lane = *hits.closest(); // every hit has t <= r.t_max
                    r.t_max = hits.t[lane];
                    x = triangle_intersection<T>{hits.t[lane],
                                                 vec3<T>(hits.b0[lane], hits.b1[lane], hits.b2[lane]),
                                                 hits.front_face(lane)};
                    best = static_cast<std::uint32_t>(b * leaf_width + lane);
                }
            } else {
                for (std::uint32_t i = first; i < first + count; ++i) {
                    if (auto h = Algorithm::find(r, data[i], cull)) {
                        r.t_max = h->t;
                        x = *h;
                        best = i;
                    }
                }
            }
            return false;
        };
        // Of two entered children the nearer first; of three or more, in nodes of eight
        // where the walk has AVX2, the node's order for the ray's octant (later pops come
        // near first too, without comparing distances), else the nearest first and the
        // others unsorted (sorting them by distance costs more branches than the nodes it
        // would prune). A stacked entry beyond the nearest hit found is skipped when popped.
        detail::bvh_traverse<detail::bvh_order::octant, true>(tree_, r, r.t_max, leaf);
        return best;
    }

    /// The index in the list given of the triangle at slot.
    [[nodiscard]] std::uint32_t id_of(std::uint32_t slot) const noexcept {
        if constexpr (batched)
            return leaves_[slot / leaf_width].id[slot % leaf_width];
        else
            return ids_[slot];
    }

    /// shade::make_hit of the triangle at slot and x; for float leaf blocks, its lanes'
    /// form (the same bits) on the vertices read from the block straight into lanes (not
    /// through a triangle in memory, whose 16-byte reloads would wait for the stores).
    [[nodiscard]] triangle_hit<T> record(std::uint32_t slot, const triangle_intersection<T>& x) const noexcept {
#if defined(__GNUC__)
        if constexpr (batched && std::is_same_v<T, float>) {
            const leaf_vertices& b = leaves_[slot / leaf_width].batch;
            const std::size_t i = slot % leaf_width;
            return detail::make_hit_lanes({detail::triangle_f4{b.v0.x[i], b.v0.y[i], b.v0.z[i], 0.0f},
                                           detail::triangle_f4{b.v1.x[i], b.v1.y[i], b.v1.z[i], 0.0f},
                                           detail::triangle_f4{b.v2.x[i], b.v2.y[i], b.v2.z[i], 0.0f}},
                                          x);
        } else
#endif
        return shade::make_hit(triangle_at(slot), x);
    }

    /// The triangle at slot (its vertices from the leaf block when batched).
    [[nodiscard]] triangle<T> triangle_at(std::uint32_t slot) const noexcept {
        if constexpr (batched)
            return leaves_[slot / leaf_width].batch.get(slot % leaf_width);
        else
            return triangles_[slot];
    }

    /// What the leaves' ranges index: the leaf blocks (batched), else the triangles.
    [[nodiscard]] const auto* leaf_data() const noexcept {
        if constexpr (batched)
            return leaves_.data();
        else
            return triangles_.data();
    }

    void build(std::span<const triangle<T>> triangles, bvh_width width, detail::executor_ref run) {
        detail::require_bvh_size("triangles", triangles.size());
        const auto finite = [&](std::size_t i) {
            const triangle<T>& tri = triangles[i];
            return is_finite(tri.v0) && is_finite(tri.v1) && is_finite(tri.v2);
        };
        auto made = detail::make_prim_refs(run, triangles.size(), [&](std::size_t i) { return bounds(triangles[i]); }, finite);
        if (const std::size_t i = made.first_invalid; i < triangles.size()) {
            const triangle<T>& tri = triangles[i];
            throw invalid_parameter("triangles", "must have finite vertices (triangle " + std::to_string(i) + ")",
                                    detail::to_text(tri.v0) + ", " + detail::to_text(tri.v1) + ", " +
                                        detail::to_text(tri.v2));
        }
        constexpr auto leaves = static_cast<std::uint32_t>(leaf_width);
        tree_ = detail::bvh_builder(batched ? 8 : 4, leaves)
                    .build(made.refs, detail::bvh_node_width(width == bvh_width::four ? 4 : 8), run, made.box,
                           made.centroids);
        size_ = triangles.size();
        ids_ = std::move(tree_.order);
        if constexpr (batched) {
            pack_batches(triangles, run);
        } else {
            triangles_.resize(ids_.size());
            detail::bvh_for_ranges(run, ids_.size(), detail::bvh_range_size(ids_.size(), 256, detail::bvh_builder::default_task_size), [&](std::size_t b, std::size_t e) {
                for (std::size_t i = b; i < e; ++i) triangles_[i] = triangles[ids_[i]];
            });
        }
    }

    /// The batch kernel on a leaf's vertex batch (detail/triangle_batch_kernel.hpp), as
    /// shade::intersect(r, triangle_batch) runs it (chosen at run time where the build
    /// dispatches, see shade/geometry/triangle_batch.hpp), or, in the walk compiled for AVX
    /// (Avx; it runs only where the CPU has AVX), the AVX kernel itself, inlined there like
    /// this function and the leaf lambdas (SHADE_DETAIL_LEAF_INLINE): no test of the CPU
    /// and no call per leaf. The same bits either way (the kernel's lanes agree bit for
    /// bit), and triangle_batch's on the same triangles.
    template <bool Avx>
    [[nodiscard]] SHADE_DETAIL_LEAF_INLINE static triangle_batch_hits<T, batch_width>
    test(const ray<T>& r, const leaf_vertices& batch, culling cull, std::bool_constant<Avx>) noexcept {
#if defined(__GNUC__) && defined(__x86_64__)
        if constexpr (Avx) return detail::intersect_batch<detail::vector_lanes<T, 32>>(r, batch, cull);
        if constexpr (detail::batch_dispatch_at_run_time) {
            if (detail::cpu_has_avx()) return detail::intersect_batch_avx(r, batch, cull);
            return detail::intersect_batch_baseline(r, batch, cull);
        }
#endif
        return detail::intersect_batch<detail::default_lanes<T, batch_width>>(r, batch, cull);
    }

    /// test(r, batch, cull, avx).hit_bits != 0, for any(): in the walk compiled for AVX the
    /// kernel's any-hit form (detail::intersect_batch_any: the same decision, without the
    /// hit record, stopping at the first step with a hit; r.t_min >= 0 not tested again, as
    /// the walk has turned away rays that are not valid()), elsewhere test() itself.
    template <bool Avx>
    [[nodiscard]] SHADE_DETAIL_LEAF_INLINE static bool test_any(const ray<T>& r, const leaf_vertices& batch, culling cull,
                                                                std::bool_constant<Avx> avx) noexcept {
#if defined(__GNUC__) && defined(__x86_64__)
        if constexpr (Avx) return detail::intersect_batch_any<detail::vector_lanes<T, 32>, true>(r, batch, cull);
#endif
        return test(r, batch, cull, avx).hit_bits != 0;
    }

    /// One batch test of a leaf (its triangles' vertices, which also make the hit record)
    /// and, next to it, each lane's index in the list given (a partly filled batch repeats
    /// its last index). A closest hit then reads the block whose batch it has just tested,
    /// not a lookup in separate arrays.
    struct alignas(64) leaf_batch { // the batch's arrays start a cache line
        leaf_vertices batch;
        std::array<std::uint32_t, batch_width> id; // index in the list given
    };
    static_assert(std::is_trivially_default_constructible_v<leaf_batch>); // see detail::leaf_allocator

public:
    /// Bytes of a leaf block (batched only, else 0): the vertices (9 arrays of 32 bytes: 288)
    /// and the lanes' indices (8 x 4 in float, 4 x 4 in double), a multiple of 64: 320.
    static constexpr std::size_t leaf_bytes = batched ? sizeof(leaf_batch) : 0;

private:

    /// Replaces every leaf's range of triangles (in ids_ order) by its range of leaf_batch
    /// blocks (ceil(count / leaf_width) of them, the last one partly filled), in the order
    /// of the nodes and their children; the blocks are filled through run.
    void pack_batches(std::span<const triangle<T>> triangles, detail::executor_ref run) {
        std::vector<std::array<std::uint32_t, 3>> leaf; // each leaf's first triangle, count and first block
        std::uint32_t blocks = 0;
        const auto each_node = [this](auto&& f) {
            for (auto& n : tree_.nodes) f(n);
            for (auto& n : tree_.wide_nodes) f(n);
        };
        each_node([&](auto& node) {
            for (std::uint32_t& ref : node.child) {
                if (!detail::is_leaf_ref(ref)) continue;
                const auto count = static_cast<std::uint32_t>((detail::leaf_count(ref) + leaf_width - 1) / leaf_width);
                leaf.push_back({detail::leaf_first(ref), detail::leaf_count(ref), blocks});
                ref = detail::make_leaf_ref(blocks, count);
                blocks += count;
            }
        });
        leaves_.resize(blocks); // not written: each block is filled below, in the tasks
        detail::bvh_for_ranges(run, leaf.size(), detail::bvh_range_size(leaf.size(), 32, 512), [&](std::size_t begin, std::size_t end) {
            for (std::size_t l = begin; l < end; ++l)
                for (std::uint32_t i = leaf[l][0], k = leaf[l][2]; i < leaf[l][0] + leaf[l][1]; i += leaf_width, ++k) {
                    const std::uint32_t left = leaf[l][0] + leaf[l][1] - i;
                    const std::uint32_t n = left < leaf_width ? left : std::uint32_t(leaf_width);
                    leaf_batch& b = leaves_[k];
                    std::array<triangle<T>, batch_width> tri;
                    for (std::uint32_t j = 0; j < leaf_width; ++j) {
                        // The triangles a block further on, fetched now: the leaf order
                        // gathers the list given out of order, beyond the caches' reach.
                        const std::size_t ahead = i + j + 2 * leaf_width;
                        detail::bvh_prefetch(&triangles[ids_[ahead < ids_.size() ? ahead : ids_.size() - 1]]);
                        const std::uint32_t id = ids_[i + (j < n ? j : n - 1)];
                        tri[j] = triangles[id];
                        b.id[j] = id;
                    }
                    b.batch = leaf_vertices(tri.data(), n);
                }
        });
        std::vector<std::uint32_t>().swap(ids_); // frees it (= {} would keep the capacity)
    }

    detail::bvh_tree tree_;             // the nodes (its order is moved to ids_)
    std::vector<leaf_batch, detail::leaf_allocator<leaf_batch>> leaves_; // batched only: the leaves' tests and hit data
    std::vector<triangle<T>> triangles_; // not batched: in leaf order
    std::vector<std::uint32_t> ids_;     // not batched: leaf order -> index given
    std::size_t size_ = 0;
};

} // namespace shade
#undef SHADE_DETAIL_LEAF_INLINE
