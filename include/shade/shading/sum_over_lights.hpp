#pragma once
// shade::sum_over_lights: the radiance a shader (or BRDF) reflects from a whole list of
// lights, with optional shadow-ray visibility and stratified sampling of area lights.

#include <array>
#include <concepts>
#include <cstddef>
#include <iterator>
#include <tuple>
#include <type_traits>
#include <utility>

#include <shade/core/sampling.hpp>
#include <shade/core/surface_point.hpp>
#include <shade/core/types.hpp>
#include <shade/light/light.hpp>
#include <shade/light/light_sample.hpp>
#include <shade/shading/shader.hpp>

namespace shade {

/// The default visibility callback: every light sample is unoccluded.
struct always_visible {
    template <std::floating_point T>
    [[nodiscard]] constexpr bool operator()(const light_sample<T>& sample) const noexcept {
        (void)sample;
        return true;
    }
};

namespace detail {

/// The result of a visibility callback as a per-channel transmittance: bool -> 1 or 0,
/// a scalar -> that value in every channel, an rgb -> itself.
template <std::floating_point T, class R>
[[nodiscard]] rgb<T> transmittance_of(const R& r) {
    if constexpr (std::same_as<R, bool>) {
        return rgb<T>(r ? T(1) : T(0));
    } else if constexpr (std::is_arithmetic_v<R>) {
        return rgb<T>(static_cast<T>(r));
    } else {
        return rgb<T>(r);
    }
}

/// One light sample, attenuated by the visibility callback, shaded by s. The callback is
/// asked only when the sample brings directional light (a shadow ray toward a light that
/// does not reach p would be wasted); it scales the diffuse and specular colours, never
/// the ambient one (ambient light is by definition not shadowed).
template <class S, class Visibility>
[[nodiscard]] rgb<scalar_of<S>> shade_visible(const S& s, const surface_point<scalar_of<S>>& at,
                                              const vec3<scalar_of<S>>& v,
                                              light_sample<scalar_of<S>> sample,
                                              Visibility& visible) {
    using T = scalar_of<S>;
    const rgb<T> zero(0);
    if (sample.diffuse != zero || sample.specular != zero) {
        const rgb<T> tau = transmittance_of<T>(visible(std::as_const(sample)));
        sample.diffuse *= tau;
        sample.specular *= tau;
    }
    return shade_of(s, at, v, sample);
}

/// Callable with anything; only probes for a member visit(f) (light_holder).
struct any_argument {
    template <class X>
    void operator()(const X&) const noexcept {}
};

/// A light that holds one of several light types and calls f(concrete light) from
/// l.visit(f), as shade::any_light does.
template <class L>
concept light_holder = requires(const L& l, any_argument f) { l.visit(f); };

/// The contribution of one light: one sample for a delta light, the average of the
/// n x n stratified samples for any other. A light_holder is dispatched once, and its
/// held light sampled directly (the same samples, without a dispatch per sample).
template <class S, light L, class Visibility, class Jitter>
[[nodiscard]] rgb<scalar_of<S>> light_contribution(const S& s, const surface_point<scalar_of<S>>& at,
                                                   const vec3<scalar_of<S>>& v, const L& l,
                                                   Visibility& visible, int n, Jitter& jitter) {
    using T = scalar_of<S>;
    static_assert(std::same_as<scalar_of<L>, T>, "the lights and the shader must share a scalar type");
    if constexpr (light_holder<L>) {
        return l.visit([&](const auto& held) -> rgb<T> {
            return light_contribution(s, at, v, held, visible, n, jitter);
        });
    } else {
        if (l.is_delta()) return shade_visible(s, at, v, l.sample(at.p, vec2<T>(T(0.5))), visible);
        // The samples are drawn a few at a time before they are shaded: each is independent
        // of the others, so the processor overlaps their latencies (a square root and
        // divisions per sample), which a shadow ray between two samples would prevent. The
        // draws, the visibility calls and the additions keep their order.
        constexpr int batch = 8;
        std::array<light_sample<T>, batch> samples;
        rgb<T> sum(0);
        const int count = n * n;
        for (int first = 0; first < count; first += batch) {
            const int size = count - first < batch ? count - first : batch;
            for (int k = 0; k < size; ++k) {
                const int i = (first + k) % n;
                const int j = (first + k) / n;
                samples[std::size_t(k)] = l.sample(at.p, stratified_u<T>(i, j, n, jitter(i, j)));
            }
            for (int k = 0; k < size; ++k) sum += shade_visible(s, at, v, samples[std::size_t(k)], visible);
        }
        return sum / (T(n) * T(n));
    }
}

/// Lights is a range of lights (std::vector<any_light<T>>, std::span, ...): what
/// std::ranges::input_range<const Lights> and light<std::ranges::range_value_t<const
/// Lights>> say, written with <iterator>'s range access and iterator concepts (which
/// define those two) instead of the far larger <ranges>.
template <class Lights>
concept light_range =
    requires(const Lights& ls) {
        { std::ranges::begin(ls) } -> std::input_iterator;
        { std::ranges::end(ls) } -> std::sentinel_for<decltype(std::ranges::begin(ls))>;
    } && light<std::iter_value_t<decltype(std::ranges::begin(std::declval<const Lights&>()))>>;

/// Lights is a std::tuple (or pair/array) of lights, possibly of different types.
template <class Lights>
concept light_tuple = !light_range<Lights> && requires { std::tuple_size<Lights>::value; };

} // namespace detail

/// The radiance that shader (or BRDF) s reflects toward v at the surface point `at` from
/// all `lights`: the sum over the lights of shade_of(s, at, v, sample), ambient terms
/// included (each light's ambient colour contributes once).
///
///   * `lights`: a range of lights (e.g. std::vector<any_light<T>>, std::span of
///     point_light<T>) or a std::tuple of lights of any types satisfying shade::light.
///   * `visible(sample)`: the shadow-ray callback, called with each light sample that
///     carries direct light (a ray from at.p along sample.l, up to sample.distance, +inf
///     for directional lights). It returns bool (unoccluded?), a scalar transmittance in
///     [0,1], or an rgb transmittance; the sample's diffuse and specular colours are
///     multiplied by it. Default: shade::always_visible.
///   * `samples_per_side`: an area light (is_delta() false) is sampled on an
///     n x n stratified grid, n = samples_per_side, and the n^2 results are averaged
///     (the estimator of shade::area_light). Throws shade::invalid_parameter naming
///     "samples_per_side" if < 1.
///   * `jitter(i, j)`: the position in [0,1)^2 inside stratum (i, j); default
///     shade::cell_centre (a deterministic grid; pass a random jitter for jittered
///     stratification).
///
/// For a BRDF s the lift is shade::lit without ambient (shade_of); pass lit{brdf, k_a} to
/// include an ambient reflectance. Returns linear RGB radiance in light_sample units.
template <shader_or_brdf S, class Lights, class Visibility = always_visible,
          class Jitter = cell_centre<scalar_of<S>>>
    requires detail::light_range<Lights> || detail::light_tuple<Lights>
[[nodiscard]] rgb<scalar_of<S>> sum_over_lights(const S& s, const surface_point<scalar_of<S>>& at,
                                                const vec3<scalar_of<S>>& v, const Lights& lights,
                                                Visibility&& visible = {},
                                                int samples_per_side = 4, Jitter&& jitter = {}) {
    using T = scalar_of<S>;
    const int n = detail::require_samples_per_side(samples_per_side);
    rgb<T> sum(0);
    if constexpr (detail::light_range<Lights>) {
        for (const auto& l : lights)
            sum += detail::light_contribution(s, at, v, l, visible, n, jitter);
    } else {
        std::apply(
            [&](const auto&... l) {
                ((sum += detail::light_contribution(s, at, v, l, visible, n, jitter)), ...);
            },
            lights);
    }
    return sum;
}

} // namespace shade
