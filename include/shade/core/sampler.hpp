#pragma once
// Samplers: where a renderer's random numbers come from, one sample of one pixel at a time.
// shade::sampler is the contract; shade::independent_sampler draws independent uniform
// numbers (PCG32), and shade::sobol_sampler (shade/core/sobol.hpp) Owen-scrambled Sobol
// points, which integrate smooth integrands with far less error at the same sample count.
//
//   shade::sobol_sampler<double> s(seed);
//   for each pixel (x, y), for each sample index i:
//       s.start_pixel_sample(x, y, i);
//       const auto film = s.next_2d();      // dimension 0: position in the pixel
//       const auto light = s.next_1d();     // dimension 1: which light
//       ...                                 // one call per decision, in the same order
//
// The k-th call after start_pixel_sample is "dimension k" of that sample; a sampler gives
// every (pixel, dimension) its own well-distributed sequence over the sample indices, so
// each decision of a path must be drawn by the same call in every sample.

#include <concepts>
#include <cstdint>

#include <shade/core/random.hpp>
#include <shade/core/scalar.hpp>
#include <shade/core/types.hpp>

namespace shade {

/// S is a sampler: `s.start_pixel_sample(x, y, index)` starts sample `index` of pixel
/// (x, y); then `s.next_1d()` returns a number in [0, 1) and `s.next_2d()` a pair in
/// [0, 1)^2, each call the next dimension of that sample.
template <class S>
concept sampler = has_scalar_type<S> && requires(S& s, std::uint32_t i) {
    s.start_pixel_sample(i, i, i);
    { s.next_1d() } -> std::same_as<typename S::scalar_type>;
    { s.next_2d() } -> std::same_as<vec2<typename S::scalar_type>>;
};

namespace detail {

/// SplitMix64's output function (Steele, Lea, Flood 2014, "Fast Splittable Pseudorandom
/// Number Generators", OOPSLA): a bijective 64-bit mix in which every input bit affects
/// every output bit. Used to derive seeds from (seed, pixel, dimension).
[[nodiscard]] constexpr std::uint64_t mix64(std::uint64_t z) noexcept {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

/// A hash of a seed and up to three values, through mix64.
[[nodiscard]] constexpr std::uint64_t hash_seed(std::uint64_t seed, std::uint64_t a, std::uint64_t b = 0,
                                                std::uint64_t c = 0) noexcept {
    std::uint64_t h = mix64(seed + 0x9e3779b97f4a7c15ULL);
    h = mix64(h ^ a);
    h = mix64(h ^ (b + 0x632be59bd9b4e019ULL));
    return mix64(h ^ (c + 0x8cb92ba72f3d8dd7ULL));
}

} // namespace detail

/// Independent uniform numbers: every dimension of every sample from a PCG32 stream of
/// its own pixel sample (seeded by the sampler's seed, the pixel and the sample index), so
/// the numbers do not depend on the order in which pixels or samples are rendered. The
/// baseline against which stratified and low-discrepancy samplers are measured.
template <std::floating_point T>
class independent_sampler {
public:
    using scalar_type = T;

    explicit independent_sampler(std::uint64_t seed = 0) noexcept : seed_(seed) {}

    /// Starts sample `index` of pixel (x, y).
    void start_pixel_sample(std::uint32_t x, std::uint32_t y, std::uint32_t index) noexcept {
        random_ = rng(detail::hash_seed(seed_, x, y), index);
    }

    /// The next dimension: a uniform number in [0, 1).
    [[nodiscard]] T next_1d() noexcept { return random_.uniform<T>(); }

    /// The next dimension: a uniform pair in [0, 1)^2.
    [[nodiscard]] vec2<T> next_2d() noexcept {
        const T a = random_.uniform<T>();
        const T b = random_.uniform<T>();
        return {a, b};
    }

private:
    std::uint64_t seed_;
    rng random_{};
};

} // namespace shade
