#pragma once
// shade::light_sample_context: what a light may know about the point it is sampled for.

#include <concepts>

#include <shade/core/types.hpp>

namespace shade {

/// The point a light is sampled for, with its surface: `p` (a ray origin, e.g. from
/// shade::offset_ray_origin), the unit geometric normal `n` and the unit shading normal
/// `ns`, both on the side from which light is wanted (where the path continues). A zero
/// `n` means there is no surface (a point in a medium): every direction is wanted.
///
/// Lights that can use the surface take it: the constant environment then samples only the
/// hemisphere above n, cosine-weighted, where the light sample is worth something;
/// pdf_incident(ctx, l) is the density of that sampling. Every other light samples as for
/// p alone (shade::any_light forwards either way).
template <std::floating_point T>
struct light_sample_context {
    using scalar_type = T;

    vec3<T> p{0, 0, 0};  ///< the point (a ray origin)
    vec3<T> n{0, 0, 0};  ///< unit geometric normal on the wanted side, or zero (no surface)
    vec3<T> ns{0, 0, 0}; ///< unit shading normal on the same side, or zero
};

} // namespace shade
