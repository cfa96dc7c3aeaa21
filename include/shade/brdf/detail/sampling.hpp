#pragma once
// Internal pieces the reflection models' sample() and pdf() share: the cosine lobe in
// world space, mirror reflection, and the choice between two lobes with one number uc.

#include <concepts>
#include <optional>

#include <glm/geometric.hpp>

#include <shade/brdf/brdf.hpp>
#include <shade/core/math.hpp>
#include <shade/core/sampling.hpp>
#include <shade/core/surface_point.hpp>
#include <shade/core/types.hpp>

namespace shade::detail {

/// A world-space direction drawn with the cosine density n·l / pi about at.n()
/// (square_to_cosine_hemisphere in the shading frame). It can lie on the horizon (n·l = 0
/// at the rim of the disk, or by rounding); callers drop it there.
template <std::floating_point T>
[[nodiscard]] inline vec3<T> sample_cosine_lobe(const vec2<T>& u, const surface_point<T>& at) noexcept {
    return at.shading.to_world(square_to_cosine_hemisphere(u));
}

/// The cosine density n·l / pi (1/sr) of sample_cosine_lobe, for n·l > 0.
template <std::floating_point T>
[[nodiscard]] constexpr T cosine_lobe_pdf(T n_dot_l) noexcept {
    return n_dot_l * inv_pi<T>;
}

/// The pdf() of a BRDF sampled with the cosine lobe alone: n·l / pi, 0 unless n·l > 0 and
/// n·v > 0.
template <std::floating_point T>
[[nodiscard]] inline T cosine_brdf_pdf(const vec3<T>& l, const vec3<T>& v, const surface_point<T>& at) noexcept {
    const T n_dot_l = glm::dot(at.n(), l);
    if (!(n_dot_l > T(0)) || !(glm::dot(at.n(), v) > T(0))) return T(0);
    return cosine_lobe_pdf(n_dot_l);
}

/// The sample() of a BRDF sampled with the cosine lobe alone: l from u, f = f_at(l) (the
/// BRDF's f(l, v, at)); nullopt when v is not above the surface or l falls on the horizon.
template <std::floating_point T, class F>
[[nodiscard]] inline std::optional<brdf_sample<T>> sample_cosine_brdf(const vec3<T>& v, const vec2<T>& u,
                                                                      const surface_point<T>& at, F&& f_at) {
    if (!(glm::dot(at.n(), v) > T(0))) return std::nullopt;
    const vec3<T> l = sample_cosine_lobe(u, at);
    const T n_dot_l = glm::dot(at.n(), l);
    if (!(n_dot_l > T(0))) return std::nullopt;
    return make_brdf_sample(l, f_at(l), cosine_lobe_pdf(n_dot_l), n_dot_l);
}

/// w mirrored about the unit vector m: 2 (w·m) m - w (unit when w and m are).
template <std::floating_point T>
[[nodiscard]] inline vec3<T> reflect_about(const vec3<T>& w, const vec3<T>& m) noexcept {
    return T(2) * glm::dot(w, m) * m - w;
}

/// The mean of the three channels: the scalar a mixture weighs a lobe's albedo by.
template <std::floating_point T>
[[nodiscard]] constexpr T mean_channel(const vec3<T>& c) noexcept {
    return (c.x + c.y + c.z) / T(3);
}

/// The probability of choosing the second of two lobes whose albedo estimates are
/// w_first and w_second (both >= 0): w_second / (w_first + w_second), and 1/2 when both are
/// 0 (the model is black; any choice gives f = 0).
template <std::floating_point T>
[[nodiscard]] constexpr T second_lobe_probability(T w_first, T w_second) noexcept {
    const T sum = w_first + w_second;
    return sum > T(0) ? w_second / sum : T(0.5);
}

/// The density of a two-lobe mixture that draws the second lobe with probability p:
/// (1 - p) pdf_first + p pdf_second, with a lobe of probability 0 contributing exactly 0
/// (its density may be infinite where it is never drawn).
template <std::floating_point T>
[[nodiscard]] constexpr T mixture_pdf(T p, T pdf_first, T pdf_second) noexcept {
    return (p < T(1) ? (T(1) - p) * pdf_first : T(0)) + (p > T(0) ? p * pdf_second : T(0));
}

} // namespace shade::detail
