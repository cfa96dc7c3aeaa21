#pragma once
// shade::toon: a cel shader that quantises the diffuse and specular factors into bands.

#include <cmath>
#include <concepts>
#include <string>

#include <glm/geometric.hpp>

#include <shade/core/error.hpp>
#include <shade/core/math.hpp>
#include <shade/core/surface_point.hpp>
#include <shade/core/types.hpp>
#include <shade/light/light_sample.hpp>
#include <shade/shading/shader.hpp>

namespace shade {

/// Parameters of shade::toon. Colours are linear RGB reflectances.
template <std::floating_point T>
struct toon_params {
    rgb<T> diffuse{T(0.8), T(0.8), T(0.8)}; ///< k_d, per channel >= 0
    rgb<T> specular{1, 1, 1};              ///< k_s, per channel >= 0
    rgb<T> ambient{0, 0, 0};               ///< k_a, per channel >= 0
    T shininess = T(32);                   ///< Blinn-Phong exponent s, > 0
    int diffuse_levels = 4;                ///< number of diffuse bands, >= 2
    int specular_levels = 3;               ///< number of specular bands, >= 2
};

/// x in [0, 1] quantised to `levels` equally spaced values {0, 1/(L-1), ..., 1}:
///   q(x) = min(floor(x * L), L - 1) / (L - 1)
/// so [0, 1/L) -> 0, [1/L, 2/L) -> 1/(L-1), ..., [(L-1)/L, 1] -> 1; x outside [0, 1] is
/// clamped first. Exactly L distinct outputs.
template <std::floating_point T>
[[nodiscard]] inline T quantize(T x, int levels) noexcept {
    const T l = T(levels);
    const T x_clamped = x < T(0) ? T(0) : (x > T(1) ? T(1) : x);
    const T band = std::fmin(std::floor(x_clamped * l), l - T(1));
    return band / (l - T(1));
}

/// A toon (cel) shader. For a light sample with direction l, the classic terms
///   d = max(n.l, 0)                                  (Lambert factor)
///   s = max(n.h, 0)^shininess if n.l > 0, else 0     (Blinn-Phong factor, h = (l+v)/|l+v|;
///                                                     Blinn 1977, "Models of Light
///                                                     Reflection for Computer Synthesized
///                                                     Pictures", SIGGRAPH)
/// are quantised into bands with shade::quantize, giving
///   shade = k_a I_a + k_d I_d quantize(d, diffuse_levels) + k_s I_s quantize(s, specular_levels)
/// in light_sample (classic) units. Defaults: 4 diffuse levels {0, 1/3, 2/3, 1} and 3
/// specular levels {0, 1/2, 1}. The light's falloff stays continuous (it is in I_d, I_s);
/// only the angular factors are banded.
template <std::floating_point T>
class toon {
public:
    using scalar_type = T;

    /// A toon shader with parameters p. Throws shade::invalid_parameter naming "diffuse",
    /// "specular", "ambient", "shininess", "diffuse_levels" or "specular_levels".
    explicit toon(const toon_params<T>& p = {}) : p_(p) {
        (void)require_non_negative("diffuse", p.diffuse);
        (void)require_non_negative("specular", p.specular);
        (void)require_non_negative("ambient", p.ambient);
        (void)require_positive("shininess", p.shininess);
        if (p.diffuse_levels < 2)
            throw invalid_parameter("diffuse_levels", "must be >= 2",
                                    std::to_string(p.diffuse_levels));
        if (p.specular_levels < 2)
            throw invalid_parameter("specular_levels", "must be >= 2",
                                    std::to_string(p.specular_levels));
    }

    /// The parameters.
    [[nodiscard]] const toon_params<T>& params() const noexcept { return p_; }

    /// The quantised diffuse factor quantize(max(n.l, 0), diffuse_levels).
    [[nodiscard]] T diffuse_factor(const vec3<T>& n, const vec3<T>& l) const noexcept {
        return quantize(clamped_dot(n, l), p_.diffuse_levels);
    }

    /// The quantised specular factor quantize(max(n.h, 0)^shininess, specular_levels), 0
    /// when n.l <= 0 or l = -v (no half vector).
    [[nodiscard]] T specular_factor(const vec3<T>& n, const vec3<T>& l,
                                    const vec3<T>& v) const noexcept {
        if (!(glm::dot(n, l) > T(0))) return T(0);
        const vec3<T> h_sum = l + v;
        const T h_length = glm::length(h_sum);
        // l = -v leaves no half vector (0/0); treat as no highlight.
        if (!(h_length > T(0))) return T(0);
        const T n_dot_h = clamped_dot(n, vec3<T>(h_sum / h_length));
        return quantize(std::pow(n_dot_h, p_.shininess), p_.specular_levels);
    }

    /// Radiance toward v (see the class comment).
    [[nodiscard]] rgb<T> shade(const surface_point<T>& at, const vec3<T>& v,
                               const light_sample<T>& s) const {
        const vec3<T>& n = at.n();
        // Each light colour is scaled by its factor in [0, 1] first: k_d * I_d may
        // overflow to inf for large valid values, and inf times a factor 0 would be NaN.
        return p_.ambient * s.ambient + p_.diffuse * (s.diffuse * diffuse_factor(n, s.l)) +
               p_.specular * (s.specular * specular_factor(n, s.l, v));
    }

private:
    toon_params<T> p_;
};

} // namespace shade
