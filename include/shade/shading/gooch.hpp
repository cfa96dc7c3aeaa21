#pragma once
// shade::gooch: Gooch cool-to-warm shading for technical illustration.

#include <cmath>
#include <concepts>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <shade/core/error.hpp>
#include <shade/core/math.hpp>
#include <shade/core/surface_point.hpp>
#include <shade/core/types.hpp>
#include <shade/light/light_sample.hpp>
#include <shade/shading/shader.hpp>

namespace shade {

/// Parameters of shade::gooch; defaults are the values suggested in the paper
/// (b = y = 0.4, alpha = 0.2, beta = 0.6).
template <std::floating_point T>
struct gooch_params {
    rgb<T> diffuse{T(0.75), T(0.75), T(0.75)}; ///< object colour k_d, >= 0
    rgb<T> blue{0, 0, T(0.4)};                 ///< k_blue = (0, 0, b), >= 0
    rgb<T> yellow{T(0.4), T(0.4), 0};          ///< k_yellow = (y, y, 0), >= 0
    T alpha = T(0.2);                          ///< share of k_d in the cool tone, >= 0
    T beta = T(0.6);                           ///< share of k_d in the warm tone, >= 0
    rgb<T> highlight{0, 0, 0};                 ///< highlight colour k_s, >= 0 (0: none)
    T shininess = T(32);                       ///< Phong highlight exponent, > 0
};

/// Gooch shading. Gooch, Gooch, Shirley, Cohen 1998, "A Non-Photorealistic Lighting Model
/// for Automatic Technical Illustration", SIGGRAPH, Section 4 (tone-based shading of matte
/// objects):
///
///   k_cool = k_blue + alpha k_d,      k_warm = k_yellow + beta k_d
///   t = (1 + n.l) / 2                 (unclamped n.l: the back side gets the cool tone)
///   tone = t k_warm + (1 - t) k_cool
///
/// The paper prints the weight (1 + l.n)/2 on k_cool; its text and figures make the
/// surfaces facing the light warm, which with shade's l (pointing TOWARD the light) is the
/// weight on k_warm written here (also Akenine-Moeller et al. 2018, Real-Time Rendering
/// 4th ed., Section 5.1). So l = n gives k_warm and l = -n gives k_cool.
///
/// With a light sample: shade = tone * I_d + k_s * I_s * max(r.v, 0)^shininess, the
/// optional highlight being Phong's (Phong 1975, "Illumination for Computer Generated
/// Pictures", CACM 18(6); r = 2 (n.l) n - l) where n.l > 0, as the paper adds it. The
/// ambient colour is not used: the cool tone plays its role. A white light of colour 1
/// reproduces the paper's tone exactly.
template <std::floating_point T>
class gooch {
public:
    using scalar_type = T;

    /// A Gooch shader with parameters p. Throws shade::invalid_parameter naming
    /// "diffuse", "blue", "yellow", "alpha", "beta", "highlight" or "shininess".
    explicit gooch(const gooch_params<T>& p = {}) : p_(p) {
        (void)require_non_negative("diffuse", p.diffuse);
        (void)require_non_negative("blue", p.blue);
        (void)require_non_negative("yellow", p.yellow);
        (void)require_non_negative("alpha", p.alpha);
        (void)require_non_negative("beta", p.beta);
        (void)require_non_negative("highlight", p.highlight);
        (void)require_positive("shininess", p.shininess);
        k_cool_ = p.blue + p.alpha * p.diffuse;
        k_warm_ = p.yellow + p.beta * p.diffuse;
        // Each member is finite, but the tones may overflow; an infinite tone weighted by
        // t = 0 would give NaN in shade().
        if (!is_finite(k_cool_))
            throw invalid_parameter("alpha", "times diffuse plus blue must be finite",
                                    detail::to_text(p.alpha));
        if (!is_finite(k_warm_))
            throw invalid_parameter("beta", "times diffuse plus yellow must be finite",
                                    detail::to_text(p.beta));
    }

    /// The parameters.
    [[nodiscard]] const gooch_params<T>& params() const noexcept { return p_; }
    /// k_cool = k_blue + alpha k_d.
    [[nodiscard]] const rgb<T>& cool() const noexcept { return k_cool_; }
    /// k_warm = k_yellow + beta k_d.
    [[nodiscard]] const rgb<T>& warm() const noexcept { return k_warm_; }

    /// The cool-to-warm tone for unit n and l (see the class comment).
    [[nodiscard]] rgb<T> tone(const vec3<T>& n, const vec3<T>& l) const noexcept {
        T t = (T(1) + glm::dot(n, l)) * T(0.5);
        // Rounding can push n.l of unit vectors a few ulps past +-1; keep t a weight.
        t = t < T(0) ? T(0) : (t > T(1) ? T(1) : t);
        return t * k_warm_ + (T(1) - t) * k_cool_;
    }

    /// Radiance toward v (see the class comment).
    [[nodiscard]] rgb<T> shade(const surface_point<T>& at, const vec3<T>& v,
                               const light_sample<T>& s) const {
        const vec3<T>& n = at.n();
        rgb<T> out = tone(n, s.l) * s.diffuse;
        const T n_dot_l = glm::dot(n, s.l);
        if (n_dot_l > T(0) && p_.highlight != rgb<T>(0)) {
            const vec3<T> r = T(2) * n_dot_l * n - s.l;
            // The factor in [0, 1] scales the light first: k_s * I_s may overflow to inf
            // for large valid values, and inf times a factor 0 would be NaN.
            // r.v of unit vectors can round a few ulps past 1, and (1 + ulp)^shininess
            // overflows to inf for a large valid shininess (then inf x 0 = NaN): clamp to 1.
            const T r_dot_v = glm::min(clamped_dot(r, v), T(1));
            out += p_.highlight * (s.specular * std::pow(r_dot_v, p_.shininess));
        }
        return out;
    }

private:
    gooch_params<T> p_;
    rgb<T> k_cool_{0, 0, 0};
    rgb<T> k_warm_{0, 0, 0};
};

} // namespace shade
