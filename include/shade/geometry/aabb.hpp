#pragma once
// shade::aabb: an axis-aligned bounding box, and the robust ray/box slab test that
// bounding-volume hierarchies (shade/geometry/bvh.hpp) traverse with.
//
// Usage:
//     shade::aabb<float> box;                        // empty
//     box.grow(p); box.grow(other_box);              // points and boxes
//     // shade::bounds(triangle), bounds(sphere): with the triangle and the sphere
//     if (auto span = shade::intersect(r, box))      // where r is inside the box
//         use(span->t_enter, span->t_exit);
//
// The slab test is conservative (Ize 2013, see intersect below): it never misses a box
// that the exact ray touches, so an exact primitive test behind it (shade::watertight)
// loses nothing to the boxes.

#include <cmath>
#include <concepts>
#include <limits>
#include <optional>

#include <glm/common.hpp>

#include <shade/core/math.hpp>
#include <shade/core/types.hpp>
#include <shade/geometry/ray.hpp>

namespace shade {

/// The closed box [lo, hi] (lo.k <= x.k <= hi.k on every axis k). The default box is
/// empty (lo = +infinity, hi = -infinity), so growing it by anything gives that thing's
/// bounds. Points with NaN coordinates must not be added (the box would not bound them).
template <std::floating_point T>
struct aabb {
    using scalar_type = T;

    vec3<T> lo{infinity<T>};  ///< lower corner
    vec3<T> hi{-infinity<T>}; ///< upper corner

    /// True when the box holds no point (lo > hi on some axis, as for the default box).
    [[nodiscard]] bool empty() const noexcept {
        return !(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z);
    }

    /// Grows the box to contain p.
    void grow(const vec3<T>& p) noexcept {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }

    /// Grows the box to contain b (an empty b changes nothing).
    void grow(const aabb& b) noexcept {
        lo = glm::min(lo, b.lo);
        hi = glm::max(hi, b.hi);
    }

    /// True when p lies in the closed box.
    [[nodiscard]] bool contains(const vec3<T>& p) const noexcept {
        return lo.x <= p.x && p.x <= hi.x && lo.y <= p.y && p.y <= hi.y && lo.z <= p.z &&
               p.z <= hi.z;
    }

    /// The centre (lo + hi) / 2. Precondition: not empty.
    [[nodiscard]] vec3<T> center() const noexcept { return (lo + hi) * T(0.5); }

    /// The surface area 2 (xy + yz + zx) of the box with edge lengths (x, y, z) = hi - lo,
    /// the quantity of the surface area heuristic; 0 for an empty box.
    [[nodiscard]] T surface_area() const noexcept {
        if (empty()) return T(0);
        const vec3<T> e = hi - lo;
        return T(2) * (e.x * e.y + e.y * e.z + e.z * e.x);
    }
};

/// The part of a ray inside a box: t from t_enter to t_exit (ray parameters, in units of
/// the ray's direction), already clipped to the ray's [t_min, t_max].
template <std::floating_point T>
struct box_interval {
    T t_enter = T(0); ///< where the ray enters the box, or t_min when it starts inside
    T t_exit = T(0);  ///< where it leaves, or t_max; enlarged by the rounding bound (see intersect)
};

namespace detail {

/// gamma(n) = n u / (1 - n u) with u the unit roundoff of T (2^-24 for float, 2^-53 for
/// double): the bound on the relative error of n rounded operations (Higham 2002,
/// "Accuracy and Stability of Numerical Algorithms", 2nd ed., §3.1, Lemma 3.1).
template <std::floating_point T>
[[nodiscard]] constexpr T rounding_gamma(int n) noexcept {
    constexpr T u = std::numeric_limits<T>::epsilon() / T(2);
    return T(n) * u / (T(1) - T(n) * u);
}

/// The larger of a and the slab distance t, where a NaN t is ignored (a is returned):
/// t = 0 * infinity arises when the ray's direction component is zero and its origin lies
/// exactly on the slab's plane, and such a ray is inside that slab for every t.
template <std::floating_point T>
[[nodiscard]] constexpr T max_ignoring_nan(T t, T a) noexcept {
    return t > a ? t : a;
}
/// The smaller of a and t, a NaN t ignored (see max_ignoring_nan).
template <std::floating_point T>
[[nodiscard]] constexpr T min_ignoring_nan(T t, T a) noexcept {
    return t < a ? t : a;
}

} // namespace detail

/// Where r is inside box (within r's [t_min, t_max]), or nothing: the slab test of Kay and
/// Kajiya, in the robust form of Ize.
///
/// Kay, Kajiya 1986, "Ray Tracing Complex Scenes", SIGGRAPH, §3: on each axis k the ray is
/// between the box's two planes for t between (lo_k - o_k) / d_k and (hi_k - o_k) / d_k;
/// it is inside the box where all three intervals and [t_min, t_max] overlap. Each
/// distance is computed as (plane - o_k) * (1 / d_k), the near plane being lo_k when d_k
/// has its sign bit clear and hi_k otherwise (so no distances need sorting).
///
/// Ize 2013, "Robust BVH Ray Traversal", Journal of Computer Graphics Techniques 2(2):
/// 12-20, §3: each computed distance is the exact one times (1 + e) with |e| <= gamma(3)
/// (three roundings: the subtraction, the reciprocal, the product; an exact zero stays
/// exact and no sign changes), so multiplying every far distance by 1 + 2 gamma(3)
/// makes the test pass whenever the exact intervals overlap. The test is therefore
/// conservative: it may accept a box the ray misses by a few ulps, and never rejects one
/// the ray touches.
///
/// A zero direction component gives 1 / d_k = ±infinity: the slab's distances are then
/// ±infinity (the ray is inside the slab for every t or for none), or NaN where the
/// origin lies exactly on the slab's plane, which is ignored (the ray stays on the
/// closed slab's boundary). An empty box is never entered; an invalid ray (ray::valid)
/// enters nothing. Precondition: box has no NaN coordinate.
template <std::floating_point T>
[[nodiscard]] std::optional<box_interval<T>> intersect(const ray<T>& r, const aabb<T>& box) noexcept {
    if (!r.valid()) return std::nullopt;
    constexpr T enlarge = T(1) + T(2) * detail::rounding_gamma<T>(3);
    T t_enter = r.t_min;
    T t_exit = r.t_max;
    for (int k = 0; k < 3; ++k) {
        const T inv = T(1) / r.direction[k];
        const bool negative = std::signbit(r.direction[k]);
        const T t_near = ((negative ? box.hi[k] : box.lo[k]) - r.origin[k]) * inv;
        const T t_far = ((negative ? box.lo[k] : box.hi[k]) - r.origin[k]) * inv * enlarge;
        t_enter = detail::max_ignoring_nan(t_near, t_enter);
        t_exit = detail::min_ignoring_nan(t_far, t_exit);
    }
    if (!(t_enter <= t_exit)) return std::nullopt;
    return box_interval<T>{t_enter, t_exit};
}

} // namespace shade
