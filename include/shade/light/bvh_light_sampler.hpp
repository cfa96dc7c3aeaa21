#pragma once
// shade::bvh_light_sampler: chooses one of many lights for a shading point in proportion to
// an estimate of what each contributes there (distance, orientation, power), by walking a
// bounding volume hierarchy over the lights. Conty Estevez, Kulla 2018, "Importance
// Sampling of Many Lights with Adaptive Tree Splitting", Proc. ACM Comput. Graph.
// Interact. Tech. 1(2) (HPG 2018), without their adaptive splitting (one light per walk);
// the same scheme as pbrt-v4's BVHLightSampler (Pharr, Jakob, Humphreys 2023, "Physically
// Based Rendering", 4th ed., sec. 12.6.3).
//
// This header is included on its own: it is not part of the umbrella shade/shade.hpp.
//
// Usage (indices are those of the caller's light list; light_bounds_of is in
// shade/light/light_bounds_of.hpp):
//     std::vector<shade::light_bounds<float>> b;     // one per light, in order
//     for (const auto& l : lights) b.push_back(shade::light_bounds_of(l, scene_radius));
//     const shade::bvh_light_sampler<float> sampler(b);
//     if (auto c = sampler.sample(ctx, u))          // ctx: shade::light_sample_context
//         ... lights[c->index].sample_incident(ctx, u2), divided by c->probability and its pdf;
//     sampler.probability(ctx, i)                   // the same number, for MIS weights
// The choice depends on ctx.p and the geometric normal ctx.n (zero: no surface), so MIS
// must ask probability() with the context the light was sampled for.
//
// Lights at infinity (light_bounds::at_infinity: directional, environment) are not in the
// tree. Each of the k such lights of power > 0 is chosen with probability 1 / (k + 1) and
// the tree with the remaining 1 / (k + 1), as pbrt-v4 does; where the tree's root has
// importance 0 (nothing in it can light the point) the infinite lights share all of it.
// Lights of power 0 are never chosen.

#include <bit>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include <shade/core/error.hpp>
#include <shade/core/math.hpp>
#include <shade/core/types.hpp>
#include <shade/geometry/aabb.hpp>
#include <shade/light/light_bounds.hpp>
#include <shade/light/light_sampler.hpp>
#include <shade/light/sample_context.hpp>

namespace shade {

/// A light sampler over a binary tree of light_bounds, one light per leaf. Each node holds
/// the merge() of its children's bounds; a walk from the root goes to each child with
/// probability proportional to its importance() at the shading point, so a light is chosen
/// with the product of those probabilities along its path. Zero-importance subtrees are
/// never entered. sample() reports that product and probability() recomputes it along the
/// light's stored path with the same operations, so the two agree bit for bit.
///
/// The walk returns nothing where the root's importance is 0 and there is no light at
/// infinity, and where it reaches a node whose two children both have importance 0 (the
/// node's bound is looser than its children's). In both cases no light of the subtree can
/// light the point, so the estimate loses nothing by it; the probabilities then sum to less
/// than 1 by the chance of such a walk.
///
/// The tree is built top-down with Conty Estevez and Kulla's surface area orientation
/// heuristic (SAOH): on each axis, lights are binned by their box centers into 12 buckets and
/// the split between buckets minimizing
///   K_r (Phi_l M_A(l) M_Omega(l) + Phi_r M_A(r) M_Omega(r)) / (M_A M_Omega of the node)
/// is taken (the denominator, alike for every candidate of a node, is left out), with M_A
/// the box's surface area, M_Omega the orientation cone's measure (see
/// orientation_measure below) and K_r = longest extent / extent on the split axis (against
/// thin slabs). Splits are also tried along each coordinate of the lights' cone axes (K_r =
/// 1 there), so that lights facing different ways, which a shading point sees or does not
/// see together, can part even where they are mixed in space. Every light gets a leaf of
/// its own (the paper also weighs a split against keeping a leaf of several). Where all
/// centers and axes coincide the lights are halved by count. So that every light's path fits
/// in 64 bits, nodes deeper than 63 - bit_width(lights) are halved by count.
template <std::floating_point T>
class bvh_light_sampler {
public:
    using scalar_type = T;

    /// A sampler over lights with the given bounds (one per light, in the caller's order).
    /// Throws invalid_parameter naming "lights" when a power is negative, NaN or infinite, or,
    /// for a light not at infinity, when its box is empty or not finite, its axis not unit
    /// length, theta_o outside [0, pi] or theta_e outside [0, pi/2], and when there are 2^31
    /// lights or more.
    explicit bvh_light_sampler(std::span<const light_bounds<T>> lights) : count_(lights.size()) {
        // Nodes and leaves hold 32-bit indices.
        if (count_ >= (std::size_t(1) << 31))
            throw invalid_parameter("lights", "must number fewer than 2^31", std::to_string(count_));
        path_.assign(count_, 0);
        role_.assign(count_, role::unused);
        std::vector<entry> in_tree;
        for (std::size_t i = 0; i < count_; ++i) {
            const light_bounds<T>& b = lights[i];
            validate(b, i);
            if (!(b.power > T(0))) continue;
            if (b.at_infinity) {
                role_[i] = role::infinite;
                infinite_.push_back(i);
                continue;
            }
            role_[i] = role::tree;
            in_tree.push_back({b, b.box.center(), i});
        }
        if (!in_tree.empty()) {
            nodes_.reserve(2 * in_tree.size() - 1);
            const int forced_halving_depth = 63 - static_cast<int>(std::bit_width(in_tree.size()));
            build(in_tree, 0, in_tree.size(), 0, 0, forced_halving_depth);
        }
    }

    /// The number of lights (as given, dark ones included).
    [[nodiscard]] std::size_t size() const noexcept { return count_; }

    /// A light for the shading point ctx with u in [0, 1), and the probability of that choice;
    /// nothing where no light can light ctx.p (see the class comment).
    [[nodiscard]] std::optional<light_choice<T>> sample(const light_sample_context<T>& ctx, T u) const noexcept {
        u = clamp_unit(u);
        const T p_tree = tree_probability(ctx);
        if (u < p_tree) {
            u = clamp_unit(u / p_tree);
            T pmf = p_tree;
            std::uint32_t node_index = 0;
            while (!nodes_[node_index].leaf) {
                const split s = child_probabilities(node_index, ctx);
                if (!(s.p_first > T(0)) && !(s.p_second > T(0))) return std::nullopt;
                if (u < s.p_first) {
                    u = clamp_unit(u / s.p_first);
                    pmf *= s.p_first;
                    node_index = node_index + 1;
                } else {
                    u = clamp_unit((u - s.p_first) / s.p_second);
                    pmf *= s.p_second;
                    node_index = nodes_[node_index].second_or_light;
                }
            }
            return light_choice<T>{nodes_[node_index].second_or_light, pmf};
        }
        if (infinite_.empty()) return std::nullopt;
        const std::size_t k = infinite_.size();
        const T scaled = (u - p_tree) / (T(1) - p_tree) * static_cast<T>(k);
        const std::size_t j = scaled > T(0) ? detail::clamped_index(scaled, k) : 0;
        return light_choice<T>{infinite_[j], infinite_probability(p_tree)};
    }

    /// The probability that sample(ctx, .) chooses light i: 0 for a light of power 0, one
    /// that cannot light ctx.p, or i >= size().
    [[nodiscard]] T probability(const light_sample_context<T>& ctx, std::size_t i) const noexcept {
        if (i >= count_ || role_[i] == role::unused) return T(0);
        const T p_tree = tree_probability(ctx);
        if (role_[i] == role::infinite) return infinite_probability(p_tree);
        if (!(p_tree > T(0))) return T(0);
        T pmf = p_tree;
        std::uint64_t path = path_[i];
        std::uint32_t node_index = 0;
        while (!nodes_[node_index].leaf) {
            const split s = child_probabilities(node_index, ctx);
            if (path & 1u) {
                pmf *= s.p_second;
                node_index = nodes_[node_index].second_or_light;
            } else {
                pmf *= s.p_first;
                node_index = node_index + 1;
            }
            path >>= 1;
        }
        return pmf;
    }

private:
    enum class role : unsigned char { unused, tree, infinite };

    struct node {
        light_bounds<T> bounds;
        std::uint32_t second_or_light = 0; ///< interior: the second child (the first is next); leaf: the light
        bool leaf = false;
    };

    struct entry {
        light_bounds<T> bounds;
        vec3<T> center;
        std::size_t light = 0;
    };

    struct split {
        T p_first = 0;
        T p_second = 0;
    };

    /// u clamped into [0, 1): the rescaled remainder of u may round up to 1.
    [[nodiscard]] static T clamp_unit(T u) noexcept {
        constexpr T below_one = T(1) - std::numeric_limits<T>::epsilon() / T(2);
        if (!(u > T(0))) return T(0);
        return u < below_one ? u : below_one;
    }

    /// The probability of choosing within the tree: 1 / (k + 1) with k lights at infinity, 1
    /// without them, and 0 when the tree is empty or its root's importance is 0.
    [[nodiscard]] T tree_probability(const light_sample_context<T>& ctx) const noexcept {
        if (nodes_.empty() || !(importance(nodes_[0].bounds, ctx) > T(0))) return T(0);
        return T(1) / static_cast<T>(infinite_.size() + 1);
    }

    /// Each light at infinity's probability given the tree's.
    [[nodiscard]] T infinite_probability(T p_tree) const noexcept {
        if (infinite_.empty()) return T(0);
        return (T(1) - p_tree) / static_cast<T>(infinite_.size());
    }

    /// The probabilities of going to interior node node_index's first and second child: their
    /// importances over the sum (both 0 when both are 0).
    [[nodiscard]] split child_probabilities(std::uint32_t node_index, const light_sample_context<T>& ctx) const noexcept {
        const T first = importance(nodes_[node_index + 1].bounds, ctx);
        const T second = importance(nodes_[nodes_[node_index].second_or_light].bounds, ctx);
        const T sum = first + second; // finite: importance() caps each at max / 4
        if (!(sum > T(0))) return {};
        return {first / sum, second / sum};
    }

    static void validate(const light_bounds<T>& b, std::size_t i) {
        const auto fail = [&](const char* rule, const std::string& got) {
            throw invalid_parameter("lights", rule, "lights[" + std::to_string(i) + "]." + got);
        };
        if (!std::isfinite(b.power) || !(b.power >= T(0)))
            fail("must each have a finite power >= 0", "power = " + detail::to_text(b.power));
        if (b.at_infinity) return;
        if (b.box.empty() || !is_finite(b.box.lo) || !is_finite(b.box.hi))
            fail("must each have a finite, non-empty box",
                 "box = [" + detail::to_text(b.box.lo) + ", " + detail::to_text(b.box.hi) + "]");
        // A unit axis to within 1e-3 in its squared length: normalize() leaves a few ulps.
        if (!is_finite(b.axis) || !(std::fabs(glm::dot(b.axis, b.axis) - T(1)) <= T(1e-3)))
            fail("must each have a unit axis", "axis = " + detail::to_text(b.axis));
        if (!(b.theta_o >= T(0) && b.theta_o <= pi<T>))
            fail("must each have theta_o in [0, pi]", "theta_o = " + detail::to_text(b.theta_o));
        if (!(b.theta_e >= T(0) && b.theta_e <= pi<T> / T(2)))
            fail("must each have theta_e in [0, pi/2]", "theta_e = " + detail::to_text(b.theta_e));
    }

    /// Builds the subtree over entries [begin, end) at the given depth, whose lights' paths
    /// so far are `path`; returns its node index.
    std::uint32_t build(std::vector<entry>& entries, std::size_t begin, std::size_t end, int depth,
                        std::uint64_t path, int forced_halving_depth) {
        const auto index = static_cast<std::uint32_t>(nodes_.size());
        nodes_.push_back({});
        if (end - begin == 1) {
            nodes_[index] = {entries[begin].bounds, static_cast<std::uint32_t>(entries[begin].light), true};
            path_[entries[begin].light] = path;
            return index;
        }
        const std::size_t middle = depth < forced_halving_depth ? saoh_split(entries, begin, end)
                                                                : begin + (end - begin) / 2;
        build(entries, begin, middle, depth + 1, path, forced_halving_depth);
        const std::uint32_t second =
            build(entries, middle, end, depth + 1, path | (std::uint64_t(1) << depth), forced_halving_depth);
        nodes_[index].bounds = merge(nodes_[index + 1].bounds, nodes_[second].bounds);
        nodes_[index].second_or_light = second;
        return index;
    }

    /// Reorders entries [begin, end) (at least 2) into two non-empty parts by the lowest-cost
    /// SAOH split (see the class comment) and returns where the second begins.
    static std::size_t saoh_split(std::vector<entry>& entries, std::size_t begin, std::size_t end) {
        constexpr int bucket_count = 12;
        light_bounds<T> all = entries[begin].bounds;
        T key_lo[6], key_hi[6];
        for (int dim = 0; dim < 6; ++dim) key_lo[dim] = key_hi[dim] = key_of(entries[begin], dim);
        for (std::size_t i = begin + 1; i < end; ++i) {
            all = merge(all, entries[i].bounds);
            for (int dim = 0; dim < 6; ++dim) {
                const T k = key_of(entries[i], dim);
                key_lo[dim] = k < key_lo[dim] ? k : key_lo[dim];
                key_hi[dim] = k > key_hi[dim] ? k : key_hi[dim];
            }
        }
        const vec3<T> extent = all.box.hi - all.box.lo;
        const T longest = extent.x > extent.y ? (extent.x > extent.z ? extent.x : extent.z)
                                              : (extent.y > extent.z ? extent.y : extent.z);
        T best_cost = infinity<T>;
        int best_dim = -1;
        int best_bucket = 0;
        for (int dim = 0; dim < 6; ++dim) {
            const T lo = key_lo[dim];
            const T width = key_hi[dim] - lo;
            if (!(width > T(0))) continue;
            std::optional<light_bounds<T>> buckets[bucket_count];
            for (std::size_t i = begin; i < end; ++i) {
                const int b = bucket_of(key_of(entries[i], dim), lo, width, bucket_count);
                buckets[b] = buckets[b] ? merge(*buckets[b], entries[i].bounds) : entries[i].bounds;
            }
            // K_r: long thin boxes split across their short side poorly bound their lights.
            const T k_r = dim < 3 ? longest / extent[dim] : T(1);
            for (int split_after = 0; split_after + 1 < bucket_count; ++split_after) {
                std::optional<light_bounds<T>> left, right;
                for (int b = 0; b < bucket_count; ++b) {
                    if (!buckets[b]) continue;
                    auto& side = b <= split_after ? left : right;
                    side = side ? merge(*side, *buckets[b]) : *buckets[b];
                }
                if (!left || !right) continue;
                const T cost = k_r * (cluster_cost(*left) + cluster_cost(*right));
                if (cost < best_cost) {
                    best_cost = cost;
                    best_dim = dim;
                    best_bucket = split_after;
                }
            }
        }
        if (best_dim < 0) return begin + (end - begin) / 2; // all centers and axes coincide
        // Partition: entries whose bucket is at most best_bucket first.
        const T lo = key_lo[best_dim];
        const T width = key_hi[best_dim] - lo;
        std::size_t middle = begin;
        for (std::size_t i = begin; i < end; ++i) {
            if (bucket_of(key_of(entries[i], best_dim), lo, width, bucket_count) <= best_bucket) {
                const entry e = entries[i];
                entries[i] = entries[middle];
                entries[middle] = e;
                ++middle;
            }
        }
        return middle;
    }

    /// What a split sorts by: the box center's coordinate on axis dim (0 to 2), or the cone
    /// axis's coordinate dim - 3 (3 to 5).
    [[nodiscard]] static T key_of(const entry& e, int dim) noexcept {
        return dim < 3 ? e.center[dim] : e.bounds.axis[dim - 3];
    }

    /// The bucket of coordinate x among `count` equal buckets over [lo, lo + width].
    [[nodiscard]] static int bucket_of(T x, T lo, T width, int count) noexcept {
        const T scaled = (x - lo) / width * static_cast<T>(count);
        return scaled > T(0) ? static_cast<int>(detail::clamped_index(scaled, static_cast<std::size_t>(count))) : 0;
    }

    /// Phi M_A M_Omega of a cluster: its power times its box's surface area times its
    /// orientation measure. The box of lights on a line has area 0 whatever its length, so
    /// its squared diagonal stands in, and the smallest normal number for coincident lights
    /// (which then still compare by power and orientation).
    [[nodiscard]] static T cluster_cost(const light_bounds<T>& b) noexcept {
        T area = b.box.surface_area();
        if (!(area > T(0))) area = glm::dot(b.box.hi - b.box.lo, b.box.hi - b.box.lo);
        if (!(area > T(0))) area = std::numeric_limits<T>::min();
        return b.power * area * orientation_measure(b);
    }

    /// M_Omega, the solid-angle measure of an orientation cone weighted by the cosine of
    /// emission, of Conty Estevez and Kulla 2018 (their SAOH): with theta_w =
    /// min(theta_o + theta_e, pi),
    ///   M_Omega = 2 pi (1 - cos theta_o)
    ///           + pi/2 (2 theta_w sin theta_o - cos(theta_o - 2 theta_w) - 2 theta_o sin theta_o + cos theta_o).
    [[nodiscard]] static T orientation_measure(const light_bounds<T>& b) noexcept {
        const T theta_o = b.theta_o;
        const T theta_w = theta_o + b.theta_e < pi<T> ? theta_o + b.theta_e : pi<T>;
        const T cos_o = std::cos(theta_o);
        const T sin_o = std::sin(theta_o);
        return T(2) * pi<T> * (T(1) - cos_o) +
               pi<T> / T(2) *
                   (T(2) * theta_w * sin_o - std::cos(theta_o - T(2) * theta_w) - T(2) * theta_o * sin_o + cos_o);
    }

    std::size_t count_;
    std::vector<node> nodes_;                ///< depth first: an interior node's first child follows it
    std::vector<std::uint64_t> path_;        ///< per light: bit d set where its path takes the second child at depth d
    std::vector<role> role_;                 ///< per light: in the tree, at infinity, or never chosen
    std::vector<std::size_t> infinite_;      ///< the lights at infinity of power > 0
};

} // namespace shade
