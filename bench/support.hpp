#pragma once
// Shared helpers of the benchmarks in bench/*.cpp: registration with names that
// bench/report.py groups into tables, counters it reads, the fixed-iteration mode and the
// callgrind markers used by `script/bench --callgrind`.
//
// Naming: "<group>/<variant>", e.g. "triangle/float/hit50/glm". Everything before the
// last '/' is the group: the variants of one group run on the same data in the same
// binary, and bench/report.py computes their ratios to the group's baseline variant.
//
// Counters (in the JSON output): ops_per_iter, the number of operations (intersection
// tests, BRDF evaluations) one benchmark iteration performs, so that time per operation =
// time per iteration / ops_per_iter; hit_rate, for intersection benchmarks, the fraction
// of those tests that hit, measured with the benchmarked routine itself on the same data.
//
// Fixed iterations: when the environment variable SHADE_BENCH_ITERATIONS is a positive
// number, every benchmark runs exactly that many iterations (for callgrind, where time
// means nothing). Under valgrind --tool=callgrind, each benchmark zeroes the counters
// just before its timed loop and dumps them right after it, with the benchmark's name as
// the dump's description, so bench/report.py can divide the instructions of exactly
// that loop by iterations x ops_per_iter.

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <numeric>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <benchmark/benchmark.h>

#if __has_include(<valgrind/callgrind.h>)
#include <valgrind/callgrind.h>
#define SHADE_BENCH_CALLGRIND 1
#else
#define SHADE_BENCH_CALLGRIND 0
#endif

namespace shade_bench {

/// The fixed iteration count from SHADE_BENCH_ITERATIONS, or 0 (let Google Benchmark
/// choose) when it is unset or not a positive number.
inline benchmark::IterationCount fixed_iterations() {
    const char* text = std::getenv("SHADE_BENCH_ITERATIONS");
    if (text == nullptr) return 0;
    const long long n = std::atoll(text);
    return n > 0 ? static_cast<benchmark::IterationCount>(n) : 0;
}

/// Registers the benchmark `name` whose every iteration calls body() once, performing
/// ops_per_iter operations. hit_rate < 0 means "not an intersection benchmark"; counters
/// are further (name, value) pairs for the JSON output.
template <class Body>
void add(const std::string& name, double ops_per_iter, Body body, double hit_rate = -1.0,
         std::vector<std::pair<std::string, double>> counters = {}) {
    auto* b = benchmark::RegisterBenchmark(
        name.c_str(), [name, ops_per_iter, hit_rate, body, counters](benchmark::State& state) mutable {
#if SHADE_BENCH_CALLGRIND
            CALLGRIND_ZERO_STATS;
#endif
            for (auto _ : state) body();
#if SHADE_BENCH_CALLGRIND
            CALLGRIND_DUMP_STATS_AT(name.c_str());
#endif
            state.counters["ops_per_iter"] = ops_per_iter;
            if (hit_rate >= 0.0) state.counters["hit_rate"] = hit_rate;
            for (const auto& [counter, value] : counters) state.counters[counter] = value;
        });
    if (const benchmark::IterationCount n = fixed_iterations(); n > 0) b->Iterations(n);
}

/// The visiting orders of an intersection benchmark. Its pairs in storage order, as the
/// first groups run them, repeat the same hit/miss sequence every iteration, which the
/// branch predictor learns: that flatters every test that branches. So each benchmark
/// also runs its pairs in a random order (group suffix "_shuffled", the same L1-resident
/// data) and from a set larger than the last-level cache, in a random order ("_memory":
/// every test waits for memory as a renderer's incoherent rays do).
inline std::vector<std::uint32_t> random_order(std::size_t n, std::uint64_t seed) {
    std::vector<std::uint32_t> order(n);
    std::iota(order.begin(), order.end(), std::uint32_t(0));
    std::mt19937_64 g(seed);
    for (std::size_t i = n; i > 1; --i) {
        const auto j = static_cast<std::size_t>(g() % i); // Fisher-Yates
        std::swap(order[i - 1], order[j]);
    }
    return order;
}

/// Bytes of the "_memory" data sets: twice the 32 MiB last-level cache of the machine
/// the benchmarks are written for, so no iteration finds its pairs in any cache.
inline constexpr std::size_t beyond_cache_bytes = std::size_t(64) << 20;

/// True when the shuffled and memory variants are registered: not under callgrind's fixed
/// iterations, where instruction counts do not depend on order or caches and a 64 MiB set
/// would take minutes to simulate.
inline bool with_order_variants() { return fixed_iterations() == 0; }

/// What every intersection benchmark keeps of one test, whatever the routine returns: hit
/// or not, t and two barycentric coordinates (or zeros). Passing this same small record to
/// benchmark::DoNotOptimize gives every routine the same observable work.
template <class T>
struct outcome {
    int hit = 0;
    T t = T(0);
    T u = T(0);
    T v = T(0);
};

/// Google Benchmark's main with random interleaving switched on unless the command line
/// sets it: every repetition of every benchmark runs as its own instance, in random order,
/// so a variant and its baseline share the machine's slow and fast moments.
inline int main(int argc, char** argv) {
    std::vector<char*> args(argv, argv + argc);
    static char interleave[] = "--benchmark_enable_random_interleaving=true";
    bool given = false;
    for (int i = 1; i < argc; ++i)
        given = given || std::strncmp(argv[i], "--benchmark_enable_random_interleaving", 38) == 0;
    if (!given) args.insert(args.begin() + 1, interleave);
    int n = static_cast<int>(args.size());
    benchmark::Initialize(&n, args.data());
    if (benchmark::ReportUnrecognizedArguments(n, args.data())) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}

} // namespace shade_bench
