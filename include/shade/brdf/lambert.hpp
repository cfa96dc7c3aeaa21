#pragma once
// shade::lambert: the ideal diffuse reflector.

#include <concepts>
#include <optional>

#include <glm/geometric.hpp>

#include <shade/brdf/brdf.hpp>
#include <shade/brdf/detail/sampling.hpp>
#include <shade/core/error.hpp>
#include <shade/core/math.hpp>
#include <shade/core/surface_point.hpp>
#include <shade/core/types.hpp>

namespace shade {

/// Lambertian (ideal diffuse) reflection.
///
/// Lambert 1760, "Photometria" (the cosine law); written as the constant BRDF R/pi in
/// Pharr, Jakob, Humphreys 2016, "Physically Based Rendering", 3rd ed., sec. 8.3
/// "Lambertian Reflection":
///
///     f(l, v) = k_d / pi          (1/sr, for l and v above the surface; 0 otherwise)
///
/// k_d is the diffuse reflectance (albedo), per channel. Lit by shade::lit (which computes
/// pi f I (n·l)), this reproduces the classic diffuse term k_d I_d (n·l) exactly.
///
/// Reciprocal: yes (constant). Energy conserving: yes iff k_d <= 1 in every channel (the
/// directional albedo is exactly k_d for every view).
///
/// Sampling (shade::sampled_brdf): the cosine density n·l / pi (Malley's method,
/// shade::square_to_cosine_hemisphere), proportional to f |n·l|, so every sample's weight
/// is exactly k_d; uc is not used.
template <std::floating_point T>
class lambert {
public:
    using scalar_type = T;

    /// A Lambertian surface of diffuse reflectance k_d. Throws shade::invalid_parameter
    /// naming "k_d" unless every channel is finite and >= 0. (k_d > 1 is accepted but
    /// reflects more energy than it receives.)
    explicit lambert(const rgb<T>& k_d) : k_d_(require_non_negative("k_d", k_d)) {}

    /// Unchecked: the caller guarantees k_d is finite and >= 0 per channel.
    constexpr lambert(unchecked_t, const rgb<T>& k_d) noexcept : k_d_(k_d) {}

    /// The diffuse reflectance k_d.
    [[nodiscard]] constexpr const rgb<T>& k_d() const noexcept { return k_d_; }

    /// BRDF value in 1/sr without the cosine: k_d / pi if n·l > 0 and n·v > 0, else 0.
    [[nodiscard]] rgb<T> f(const vec3<T>& l, const vec3<T>& v,
                           const surface_point<T>& at) const noexcept {
        detail::assert_unit_directions(l, v, at);
        const T n_dot_l = glm::dot(at.n(), l);
        const T n_dot_v = glm::dot(at.n(), v);
        if (!(n_dot_l > T(0)) || !(n_dot_v > T(0))) return rgb<T>(0);
        return k_d_ * inv_pi<T>;
    }

    /// The density (1/sr) with which sample() draws l: n·l / pi, 0 unless n·l > 0 and n·v > 0.
    [[nodiscard]] T pdf(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) const noexcept {
        return detail::cosine_brdf_pdf(l, v, at);
    }

    /// Draws l with the cosine density from u (uc is not used); nullopt when v is not above
    /// the surface or l falls on the horizon.
    [[nodiscard]] std::optional<brdf_sample<T>> sample(const vec3<T>& v, T /*uc*/, const vec2<T>& u,
                                                       const surface_point<T>& at) const noexcept {
        return detail::sample_cosine_brdf(v, u, at, [this](const vec3<T>&) { return rgb<T>(k_d_ * inv_pi<T>); });
    }

private:
    rgb<T> k_d_;
};

} // namespace shade
