#pragma once
// Conventions used everywhere in shade (also in docs/conventions.md):
//
//   * All directions are unit vectors pointing AWAY from the surface point:
//       l  toward the light,  v  toward the viewer,  n  the unit surface normal,
//       t, b  unit tangent and bitangent, with (t, b, n) orthonormal and right-handed
//       (cross(t, b) == n).
//   * A direction w is above the surface when dot(n, w) > 0. Reflection models return zero
//     when l or v is not above the surface. Models that transmit (shade/bsdf) take
//     directions on either side; inside is the side opposite n.
//   * h = normalize(l + v) is the half vector.
//   * In the local frame, n is +z, t is +x and b is +y, so cos(theta) = w.z.
//   * Colours are linear RGB (shade::rgb<T>), never sRGB-encoded.

#include <cmath>
#include <concepts>

#include <glm/geometric.hpp>

#include <shade/core/config.hpp>
#include <shade/core/error.hpp>
#include <shade/core/types.hpp>

namespace shade {

/// An orthonormal, right-handed shading frame (t, b, n).
template <std::floating_point T>
struct frame {
    using scalar_type = T;

    vec3<T> t{1, 0, 0}; ///< unit tangent (local +x)
    vec3<T> b{0, 1, 0}; ///< unit bitangent (local +y)
    vec3<T> n{0, 0, 1}; ///< unit normal (local +z)

    /// Builds a frame around the unit normal n, without branches on the normal's direction
    /// and without NaN for any unit n (including n = +z and n = -z).
    /// Precondition: n has unit length (use from_normal_checked for untrusted input).
    ///
    /// Duff, Burgess, Christensen, Hery, Kensler, Liani, Villemin 2017, "Building an
    /// Orthonormal Basis, Revisited", JCGT 6(1), Listing 3. The sign of n.z picks one of
    /// two charts, so the only division, by (sign + n.z), is never by less than 1 in
    /// magnitude.
    [[nodiscard]] static frame from_normal(const vec3<T>& n) noexcept {
        const T sign = std::copysign(T(1), n.z);
        const T a = T(-1) / (sign + n.z);
        const T c = n.x * n.y * a;
        frame f;
        f.t = vec3<T>(T(1) + sign * n.x * n.x * a, sign * c, -sign * n.x);
        f.b = vec3<T>(c, sign + n.y * n.y * a, -n.y);
        f.n = n;
        return f;
    }

    /// As from_normal, but normalises n first and throws shade::invalid_parameter naming
    /// "normal" if n is zero-length or non-finite.
    [[nodiscard]] static frame from_normal_checked(const vec3<T>& n) {
        return from_normal(require_direction("normal", n));
    }

    /// Builds a frame with normal n whose tangent is the given direction made orthogonal to
    /// n (Gram-Schmidt), for anisotropic models. Throws shade::invalid_parameter naming
    /// "normal" or "tangent" if either is zero-length or non-finite, or if the tangent is
    /// parallel to the normal.
    [[nodiscard]] static frame from_normal_tangent(const vec3<T>& normal, const vec3<T>& tangent) {
        const vec3<T> nn = require_direction("normal", normal);
        const vec3<T> tt = require_direction("tangent", tangent);
        const vec3<T> ortho = tt - nn * glm::dot(nn, tt);
        // A tangent within ~1e-3 rad of the normal leaves too little of itself after the
        // projection to give a trustworthy direction; reject rather than return noise.
        if (!(glm::length(ortho) > T(1e-3)))
            throw invalid_parameter("tangent", "must not be parallel to the normal",
                                    detail::to_text(tangent));
        // Projected twice (classical Gram-Schmidt with reorthogonalisation; Giraud, Langou,
        // Rozloznik 2005, "The loss of orthogonality in the Gram-Schmidt orthogonalization
        // process"): one projection leaves t off orthogonal by about epsilon / |ortho|, 1e-4
        // in float for a tangent near the normal; after the second t·n is a few epsilon.
        const vec3<T> t1 = glm::normalize(ortho);
        frame f;
        f.n = nn;
        f.t = glm::normalize(t1 - nn * glm::dot(nn, t1));
        f.b = glm::cross(f.n, f.t);
        return f;
    }

    /// Expresses the world direction w in this frame (n becomes +z).
    [[nodiscard]] vec3<T> to_local(const vec3<T>& w) const noexcept {
        return vec3<T>(glm::dot(w, t), glm::dot(w, b), glm::dot(w, n));
    }

    /// Maps the local direction w (n = +z) back to world space.
    [[nodiscard]] vec3<T> to_world(const vec3<T>& w) const noexcept {
        return t * w.x + b * w.y + n * w.z;
    }
};

} // namespace shade
