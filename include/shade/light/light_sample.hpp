#pragma once
// shade::light_sample: what a light contributes at one shaded point, as seen by a shader.

#include <concepts>

#include <shade/core/math.hpp>
#include <shade/core/types.hpp>

namespace shade {

/// One sample of one light at a shaded point.
///
/// Units: the three colours follow the classic lighting model
///   I = k_a I_a + k_d I_d (n.l) + k_s I_s (...),
/// i.e. a light's colour is the radiance that a white Lambertian surface (k_d = 1, BRDF
/// 1/pi) facing the light reflects. Physically the irradiance at normal incidence is
/// E = pi * diffuse; the BRDF lift multiplies by pi accordingly (see shade/shading).
template <std::floating_point T>
struct light_sample {
    using scalar_type = T;

    vec3<T> l{0, 0, 1};          ///< unit direction from the shaded point toward the light
    T distance = infinity<T>;    ///< distance to the sampled light point (+inf: directional)
    rgb<T> ambient{0, 0, 0};     ///< ambient colour I_a, already scaled by intensity
    rgb<T> diffuse{0, 0, 0};     ///< diffuse colour I_d, scaled by intensity, falloff, cone
    rgb<T> specular{0, 0, 0};    ///< specular colour I_s, scaled like diffuse
};

} // namespace shade
