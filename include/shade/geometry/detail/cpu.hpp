#pragma once
// The CPU test behind run-time choices on x86-64 (the triangle batch's AVX kernel, the
// hierarchies' nodes of eight children). Nothing here exists on other targets.

#if defined(__GNUC__) && defined(__x86_64__)
namespace shade::detail {

/// True when this CPU and its OS support AVX (libgcc's or compiler-rt's CPU model, which
/// also checks that the OS saves the 256-bit registers). Detected on the first call, in a
/// function-local static, so that including this header adds no static initialiser.
[[nodiscard]] inline bool cpu_has_avx() noexcept {
    static const bool has = [] {
        __builtin_cpu_init();
        return __builtin_cpu_supports("avx") != 0;
    }();
    return has;
}

} // namespace shade::detail
#endif
