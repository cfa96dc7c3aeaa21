#pragma once
// The triangle_batch kernel compiled for AVX (8 floats or 4 doubles per step) for the
// run-time dispatch of x86-64 builds without -mavx and the baseline kernel it falls back
// to (detail/cpu.hpp chooses between them). Nothing here exists on other targets.

#include <concepts>
#include <cstddef>

#include <shade/geometry/detail/cpu.hpp>
#include <shade/geometry/detail/triangle_batch_kernel.hpp>
#include <shade/geometry/detail/triangle_batch_vector.hpp>

#if defined(__GNUC__) && defined(__x86_64__)
namespace shade::detail {

/// The kernel with 32-byte steps (8 floats or 4 doubles), compiled for AVX whatever the
/// flags of the including file: the x86-64 baseline (SSE2) holds only 4 floats per step.
/// Called only where the CPU and the OS support AVX (cpu_has_avx). Without FMA (AVX does
/// not imply it) every lane performs the same IEEE operations as the SSE2 and scalar
/// forms, so the results are the same bits. Batch: triangle_batch or vertex_batch.
template <template <class, std::size_t> class Batch, std::floating_point T, std::size_t N>
[[gnu::target("avx")]] [[nodiscard]] triangle_batch_hits<T, N>
intersect_batch_avx(const ray<T>& r, const Batch<T, N>& batch, culling cull) noexcept {
    return intersect_batch<vector_lanes<T, step_bytes<T, N, 32>()>>(r, batch, cull);
}

/// The baseline kernel as a function of its own, so that shade::intersect stays a small
/// dispatcher that jumps to one kernel or the other.
template <template <class, std::size_t> class Batch, std::floating_point T, std::size_t N>
[[gnu::noinline]] [[nodiscard]] triangle_batch_hits<T, N>
intersect_batch_baseline(const ray<T>& r, const Batch<T, N>& batch, culling cull) noexcept {
    return intersect_batch<default_lanes<T, N>>(r, batch, cull);
}

} // namespace shade::detail
#endif
