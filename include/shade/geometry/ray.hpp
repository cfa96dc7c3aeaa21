#pragma once
// shade::ray: a half-line origin + t * direction restricted to t in [t_min, t_max].
//
// The direction need NOT be unit length: any finite, non-zero direction works, and the ray
// parameter t is measured in units of the direction (a hit at t lies at distance
// t * |direction| from the origin). Every intersection routine in shade/geometry returns t
// in these units. Use a unit direction when you want t to be a distance.

#include <cmath>
#include <concepts>
#include <string_view>

#include <shade/core/config.hpp>
#include <shade/core/error.hpp>
#include <shade/core/math.hpp>
#include <shade/core/types.hpp>

namespace shade {

/// A ray origin + t * direction for t in the closed interval [t_min, t_max].
///
/// A plain aggregate so that renderers can build millions cheaply; nothing is checked on
/// construction. A ray that is not valid() (see there) never produces a hit from any
/// intersection routine. Use ray::checked to validate untrusted input with an exception.
template <std::floating_point T>
struct ray {
    using scalar_type = T;

    vec3<T> origin{0, 0, 0};    ///< start point (world space)
    vec3<T> direction{0, 0, 1}; ///< any finite non-zero vector; t is in its units
    T t_min = T(0);             ///< smallest accepted t; must be >= 0 (nothing behind the origin)
    T t_max = infinity<T>;      ///< largest accepted t; may be +infinity

    /// The point origin + t * direction.
    [[nodiscard]] constexpr vec3<T> at(T t) const noexcept {
        return origin + t * direction;
    }

    /// True when the ray can produce hits: origin and direction finite, direction not the
    /// zero vector, and 0 <= t_min <= t_max (t_max may be +infinity, neither may be NaN).
    /// Intersection routines return no hit for a ray that is not valid.
    [[nodiscard]] bool valid() const noexcept {
        const bool non_zero = direction.x != T(0) || direction.y != T(0) || direction.z != T(0);
        // Written so that a NaN t_min or t_max fails every comparison and so the test.
        const bool interval_ok = t_min >= T(0) && t_max >= t_min;
        return is_finite(origin) && is_finite(direction) && non_zero && interval_ok;
    }

    /// A ray built from untrusted input: throws shade::invalid_parameter naming "origin",
    /// "direction", "t_min" or "t_max" when the result would not be valid(). The direction
    /// is kept as given (not normalised), so t keeps the caller's units.
    [[nodiscard]] static ray checked(const vec3<T>& origin, const vec3<T>& direction,
                                     T t_min = T(0), T t_max = infinity<T>) {
        require_finite("origin", origin);
        (void)require_direction("direction", direction); // throws for zero or non-finite
        require_non_negative("t_min", t_min);
        if (!(t_max >= t_min))
            throw invalid_parameter("t_max", "must be >= t_min (" + detail::to_text(t_min) + ")",
                                    detail::to_text(t_max));
        return ray{origin, direction, t_min, t_max};
    }
};

} // namespace shade
