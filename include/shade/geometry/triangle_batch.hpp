#pragma once
// shade::triangle_batch: up to N triangles stored structure-of-arrays, intersected with
// one ray at a time by a branch-free Möller-Trumbore loop that compilers auto-vectorize.
//
// Usage:
//     std::array<shade::triangle<float>, 8> tris = ...;
//     const shade::triangle_batch<float, 8> batch(tris);       // pack once
//     const auto all = shade::intersect(r, batch);              // every lane: hit, t, b
//     if (auto c = shade::intersect_closest(r, batch))          // nearest lane, full record
//         use(c->index, c->hit.t, c->hit.p, c->hit.n);
//
// Results are bitwise identical to the scalar shade::moller_trumbore (shade/geometry/
// triangle.hpp) on each triangle: the same hit or miss, the same t, barycentrics and
// front_face (and, from intersect_closest, the same p and n). This holds because every
// lane performs exactly the scalar algorithm's floating-point operations in the same
// order (GLM's cross and dot, e1 = v1 - v0 and e2 = v2 - v0 stored at packing), and
// because the division-free early-out below only skips work when no lane can hit.
// Like the scalar code it needs the compiler not to contract a*b + c into a fused
// multiply-add differently in the two (x86-64 without -mfma never contracts; elsewhere
// compile with -ffp-contract=off). tests/geometry/test_triangle_batch.cpp checks it.
//
// The division is deferred: each lane first computes the scalar algorithm's numerators
// U = T·P, V = d·Q, T_n = e2·Q and det = e1·P without dividing, and a conservative
// division-free test (a superset of the lanes the scalar test accepts) decides whether
// any lane can hit. Only then are u = U/det, v = V/det and t = T_n/det computed, for all
// lanes at once, and the scalar algorithm's own tests applied to them. A ray that misses
// the whole batch (the common case in a bounding-volume hierarchy) divides nothing.
//
// The loops run over std::array members with no branches in their bodies, so g++ -O2/-O3
// and clang++ -O2 turn them into SIMD code for whatever vector width the target has (4
// floats with the x86-64 baseline SSE2, 8 or 16 with -mavx2 or -mavx512f); no
// intrinsics, so every target compiles the same portable code.

#include <algorithm>
#include <array>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <limits>
#include <optional>
#include <span>
#include <string>

#include <glm/geometric.hpp>

#include <shade/core/error.hpp>
#include <shade/core/math.hpp>
#include <shade/core/types.hpp>
#include <shade/geometry/hit.hpp>
#include <shade/geometry/ray.hpp>
#include <shade/geometry/triangle.hpp>

namespace shade {

namespace detail {
template <std::floating_point T, std::size_t N>
struct batch_access; // reads a triangle_batch's arrays; defined below
} // namespace detail

/// Up to N triangles in structure-of-arrays form (one array per coordinate), ready for
/// shade::intersect(ray, triangle_batch). Lanes past the packed triangles are empty and
/// never hit. Degenerate or non-finite triangles may be packed; like the scalar test they
/// never hit.
///
/// Storage: the hot arrays v0, e1 = v1 - v0 and e2 = v2 - v0 (9 N scalars) are read by
/// every intersection; v1 and v2 (6 N scalars) only by intersect_closest to build its hit
/// point, and by intersect when the batch holds coordinates so large (above max/4 in
/// magnitude) that the hit point could overflow.
template <std::floating_point T, std::size_t N = 8>
class triangle_batch {
    static_assert(N > 0, "a triangle batch needs at least one lane");

public:
    using scalar_type = T;
    /// Number of lanes (triangles the batch can hold).
    static constexpr std::size_t width = N;

    /// An empty batch: no lane ever hits.
    triangle_batch() noexcept = default;

    /// Packs triangles[i] into lane i. Throws shade::invalid_parameter naming "triangles"
    /// if more than N triangles are given.
    explicit triangle_batch(std::span<const triangle<T>> triangles) {
        if (triangles.size() > N)
            throw invalid_parameter("triangles",
                                    "must hold at most " + std::to_string(N) +
                                        " triangles (the batch width)",
                                    std::to_string(triangles.size()) + " triangles");
        count_ = triangles.size();
        for (std::size_t i = 0; i < count_; ++i) {
            const triangle<T>& tri = triangles[i];
            // The same operations as in moller_trumbore::intersect, so the same bits.
            const vec3<T> e1 = tri.v1 - tri.v0;
            const vec3<T> e2 = tri.v2 - tri.v0;
            set(v0_, i, tri.v0);
            set(e1_, i, e1);
            set(e2_, i, e2);
            set(v1_, i, tri.v1);
            set(v2_, i, tri.v2);
            // A lane hits only where the scalar finish step would find a unit normal; a
            // usable lane has finite edges and therefore finite vertices.
            usable_[i] = detail::is_unit_normal(tri.normal());
            if (usable_[i]) large_ = large_ || exceeds_quarter_max(tri);
        }
    }

    /// Number of packed triangles (lanes 0 .. size()-1).
    [[nodiscard]] std::size_t size() const noexcept { return count_; }

    /// The triangle in lane i, as packed. Precondition: i < size().
    [[nodiscard]] triangle<T> triangle_at(std::size_t i) const noexcept {
        return triangle<T>{get(v0_, i), get(v1_, i), get(v2_, i)};
    }

    /// True when some usable lane has a coordinate above max/4 in magnitude, so that the
    /// hit point b0 v0 + b1 v1 + b2 v2 could overflow and must be checked per hit.
    [[nodiscard]] bool large() const noexcept { return large_; }

private:
    using lanes = std::array<T, N>;
    struct soa3 {
        lanes x{}, y{}, z{};
    };

    static void set(soa3& a, std::size_t i, const vec3<T>& v) noexcept {
        a.x[i] = v.x;
        a.y[i] = v.y;
        a.z[i] = v.z;
    }
    static vec3<T> get(const soa3& a, std::size_t i) noexcept {
        return vec3<T>(a.x[i], a.y[i], a.z[i]);
    }
    // With every |coordinate| <= max/4 and barycentrics in [0, 1], each component of
    // b0 v0 + b1 v1 + b2 v2 is at most 3 (max/4) (1 + eps)^2 < max: it cannot overflow.
    static bool exceeds_quarter_max(const triangle<T>& tri) noexcept {
        const T quarter_max = std::numeric_limits<T>::max() / T(4);
        for (const vec3<T>& v : {tri.v0, tri.v1, tri.v2})
            for (int k = 0; k < 3; ++k)
                if (!(std::abs(v[k]) <= quarter_max)) return true;
        return false;
    }

    soa3 v0_, e1_, e2_; // hot
    soa3 v1_, v2_;      // cold: hit points only
    std::array<bool, N> usable_{};
    std::size_t count_ = 0;
    bool large_ = false;

    template <std::floating_point U, std::size_t M>
    friend struct detail::batch_access;
};

/// Per-lane results of one ray against a triangle_batch. For lane i: hit[i] says whether
/// shade::moller_trumbore would report a hit; where it does, t[i], b0[i], b1[i], b2[i] and
/// front_face[i] are bitwise the scalar hit's t, barycentric and front_face. Where it
/// does not, t[i] = +infinity, the barycentrics are 0 and front_face[i] is false.
template <std::floating_point T, std::size_t N>
struct triangle_batch_hits {
    std::array<bool, N> hit{};        ///< lane i was hit
    std::array<T, N> t{};             ///< ray parameter (direction units); +inf on a miss
    std::array<T, N> b0{};            ///< barycentric weight of v0
    std::array<T, N> b1{};            ///< barycentric weight of v1 (u)
    std::array<T, N> b2{};            ///< barycentric weight of v2 (v)
    std::array<bool, N> front_face{}; ///< the ray struck the counter-clockwise side

    /// Number of lanes hit.
    [[nodiscard]] std::size_t count() const noexcept {
        return static_cast<std::size_t>(std::count(hit.begin(), hit.end(), true));
    }

    /// The hit lane with the smallest t (the lowest such index on ties), or nothing.
    [[nodiscard]] std::optional<std::size_t> closest() const noexcept {
        std::optional<std::size_t> best;
        for (std::size_t i = 0; i < N; ++i)
            if (hit[i] && (!best || t[i] < t[*best])) best = i;
        return best;
    }
};

/// The nearest hit in a triangle_batch: its lane and the full hit record, equal bit for
/// bit to shade::intersect<moller_trumbore>(ray, batch.triangle_at(index), culling).
template <std::floating_point T>
struct batch_hit {
    std::size_t index = 0; ///< lane of the nearest triangle hit
    triangle_hit<T> hit;   ///< t, p, n, front_face and barycentrics of that hit
};

namespace detail {

/// Reads a triangle_batch's arrays for the intersection routines below.
template <std::floating_point T, std::size_t N>
struct batch_access {
    using batch = triangle_batch<T, N>;
    static const auto& v0(const batch& b) noexcept { return b.v0_; }
    static const auto& e1(const batch& b) noexcept { return b.e1_; }
    static const auto& e2(const batch& b) noexcept { return b.e2_; }
    static const auto& v1(const batch& b) noexcept { return b.v1_; }
    static const auto& v2(const batch& b) noexcept { return b.v2_; }
    static const auto& usable(const batch& b) noexcept { return b.usable_; }
};

} // namespace detail

/// Intersects r with every lane of batch: Möller and Trumbore's algorithm exactly as in
/// shade::moller_trumbore (Möller, Trumbore 1997, "Fast, Minimum Storage Ray-Triangle
/// Intersection", Journal of Graphics Tools 2(1):21-28, §2; see triangle.hpp for the
/// equations: P = d × e2, det = e1·P, T = o - v0, Q = T × e1, u = T·P / det,
/// v = d·Q / det, t = e2·Q / det), lane by lane, with the same culling rule and the same
/// rejection of invalid rays, degenerate triangles and t outside [t_min, t_max].
///
/// Before dividing, a lane is kept as a candidate when, with s = sign(det), a = |det|:
///     det != 0,  s U >= -m,  s V >= -m,  s U <= a + m,  a - s (U + V) >= -a 2^-10,
///     s T_n >= -m,  s T_n <= t_max a (1 + 2^-10) + m,        m = a 2^-20,
/// (and det > 0 under back-face culling). These are u >= 0, v >= 0, u <= 1, 1 - u - v >= 0,
/// t >= 0 and t <= t_max multiplied by |det|, loosened so that no lane the rounded scalar
/// test accepts can fail them: m covers a quotient U/det that underflows to -0 (which the
/// scalar test accepts as u >= 0; it needs |U| < a 2^-148 or so), and 2^-10 covers the few
/// roundings in 1 - u - v and t (about 2^-22 relative in float). Where no lane is a
/// candidate the result is all misses without any division; otherwise the scalar tests
/// decide, on the divided values, for every lane.
template <std::floating_point T, std::size_t N>
[[nodiscard]] triangle_batch_hits<T, N> intersect(const ray<T>& r, const triangle_batch<T, N>& batch,
                                                  culling cull = culling::none) noexcept {
    using access = detail::batch_access<T, N>;
    triangle_batch_hits<T, N> out;
    out.t.fill(infinity<T>);
    if (!r.valid()) return out;

    const auto& v0 = access::v0(batch);
    const auto& e1 = access::e1(batch);
    const auto& e2 = access::e2(batch);
    const auto& usable = access::usable(batch);
    const T o_x = r.origin.x, o_y = r.origin.y, o_z = r.origin.z;
    const T d_x = r.direction.x, d_y = r.direction.y, d_z = r.direction.z;
    const bool front_only = cull == culling::back_faces;
    const T loose = T(0x1p-10); // relative slack for the rounded tests, see above
    const T tiny = T(0x1p-20);  // covers quotients that underflow to -0, see above
    const T t_max_loose = r.t_max * (T(1) + loose);

    std::array<T, N> det{}, u_num{}, v_num{}, t_num{};
    std::array<bool, N> candidate{};
    // Pass 1, division-free: the scalar code's dot and cross products in GLM's order,
    // cross(a, b) = (a.y b.z - b.y a.z, a.z b.x - b.z a.x, a.x b.y - b.x a.y) and
    // dot(a, b) = (a.x b.x + a.y b.y) + a.z b.z.
    for (std::size_t i = 0; i < N; ++i) {
        const T p_x = d_y * e2.z[i] - e2.y[i] * d_z;
        const T p_y = d_z * e2.x[i] - e2.z[i] * d_x;
        const T p_z = d_x * e2.y[i] - e2.x[i] * d_y;
        const T dt = e1.x[i] * p_x + e1.y[i] * p_y + e1.z[i] * p_z;
        const T s_x = o_x - v0.x[i];
        const T s_y = o_y - v0.y[i];
        const T s_z = o_z - v0.z[i];
        const T un = s_x * p_x + s_y * p_y + s_z * p_z;
        const T q_x = s_y * e1.z[i] - e1.y[i] * s_z;
        const T q_y = s_z * e1.x[i] - e1.z[i] * s_x;
        const T q_z = s_x * e1.y[i] - e1.x[i] * s_y;
        const T vn = d_x * q_x + d_y * q_y + d_z * q_z;
        const T tn = e2.x[i] * q_x + e2.y[i] * q_y + e2.z[i] * q_z;
        det[i] = dt;
        u_num[i] = un;
        v_num[i] = vn;
        t_num[i] = tn;

        const T sign = dt > T(0) ? T(1) : T(-1);
        const T a = std::abs(dt);
        const T m = a * tiny;
        const T su = sign * un;
        const T sv = sign * vn;
        const T st = sign * tn;
        candidate[i] = usable[i] & (dt != T(0)) & (!front_only | (dt > T(0))) & (su >= -m) &
                       (sv >= -m) & (su <= a + m) & (a - (su + sv) >= -a * loose) &
                       (st >= -m) & (st <= t_max_loose * a + m);
    }
    bool any = false;
    for (std::size_t i = 0; i < N; ++i) any = any | candidate[i];
    if (!any) return out;

    // Pass 2: the scalar algorithm's divisions and tests, for every lane at once.
    for (std::size_t i = 0; i < N; ++i) {
        const T u = u_num[i] / det[i];
        const T v = v_num[i] / det[i];
        const T b0 = T(1) - u - v;
        const T t = t_num[i] / det[i];
        const bool ok = candidate[i] & (u >= T(0)) & (u <= T(1)) & (v >= T(0)) & (b0 >= T(0)) &
                        (std::abs(t) <= std::numeric_limits<T>::max()) & (t >= r.t_min) &
                        (t <= r.t_max);
        out.hit[i] = ok;
        out.t[i] = ok ? t : infinity<T>;
        out.b0[i] = ok ? b0 : T(0);
        out.b1[i] = ok ? u : T(0);
        out.b2[i] = ok ? v : T(0);
        out.front_face[i] = ok & (det[i] > T(0));
    }

    if (batch.large()) {
        // Only for batches with coordinates above max/4: the hit point must be finite,
        // as the scalar finish step requires (computed in the same order as there).
        const auto& v1 = access::v1(batch);
        const auto& v2 = access::v2(batch);
        for (std::size_t i = 0; i < N; ++i) {
            const T p_x = out.b0[i] * v0.x[i] + out.b1[i] * v1.x[i] + out.b2[i] * v2.x[i];
            const T p_y = out.b0[i] * v0.y[i] + out.b1[i] * v1.y[i] + out.b2[i] * v2.y[i];
            const T p_z = out.b0[i] * v0.z[i] + out.b1[i] * v1.z[i] + out.b2[i] * v2.z[i];
            const bool finite = std::isfinite(p_x) && std::isfinite(p_y) && std::isfinite(p_z);
            if (out.hit[i] && !finite) {
                out.hit[i] = false;
                out.t[i] = infinity<T>;
                out.b0[i] = out.b1[i] = out.b2[i] = T(0);
                out.front_face[i] = false;
            }
        }
    }
    return out;
}

/// The nearest hit of r among the lanes of batch (the lowest lane on equal t), with the
/// full hit record exactly as shade::intersect<moller_trumbore> returns it for that
/// triangle, or nothing when no lane is hit.
template <std::floating_point T, std::size_t N>
[[nodiscard]] std::optional<batch_hit<T>> intersect_closest(const ray<T>& r,
                                                            const triangle_batch<T, N>& batch,
                                                            culling cull = culling::none) noexcept {
    const triangle_batch_hits<T, N> all = intersect(r, batch, cull);
    const std::optional<std::size_t> best = all.closest();
    if (!best) return std::nullopt;
    const std::size_t i = *best;
    const triangle<T> tri = batch.triangle_at(i);
    batch_hit<T> out;
    out.index = i;
    out.hit.t = all.t[i];
    out.hit.barycentric = vec3<T>(all.b0[i], all.b1[i], all.b2[i]);
    out.hit.p = all.b0[i] * tri.v0 + all.b1[i] * tri.v1 + all.b2[i] * tri.v2;
    out.hit.n = tri.normal();
    out.hit.front_face = all.front_face[i];
    return out;
}

} // namespace shade
