// Ray/triangle intersection: shade's three scalar algorithms against GLM 0.9.9.8's
// glm::intersectRayTriangle at three hit rates, and the SoA batch (one ray against 8 or
// 16 triangles) against the same GLM test, per test. See bench/support.hpp for names,
// counters and the callgrind mode; script/bench turns the output into docs/benchmarks.md.
//
// Data: precomputed (ray, triangle) pairs, 512 in float (68 bytes a pair) and 256 in double
// (136 bytes), about 35 KB either way, so that they stay in a 48 KiB L1 data cache and the
// loop measures the arithmetic, not memory. Every variant of a group runs over the same
// arrays. Each group also runs its pairs in a random order ("_shuffled") and, at 50 %
// hits, from a 64 MiB set in a random order ("_memory"): see bench/support.hpp,
// random_order.

#include <array>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <string>
#include <vector>

#define GLM_ENABLE_EXPERIMENTAL
#include <glm/gtx/intersect.hpp>

#include <benchmark/benchmark.h>

#include <shade/core/random.hpp>
#include <shade/geometry/triangle.hpp>
#include <shade/geometry/triangle_batch.hpp>

#include "support.hpp"

namespace {

using shade_bench::outcome;

// Pairs per data set: the same number of bytes for float and double.
template <class T>
constexpr std::size_t pair_count = 512 * sizeof(float) / sizeof(T);

template <class T>
using v3 = shade::vec3<T>;

template <class T>
struct pair_data {
    std::vector<shade::ray<T>> rays;
    std::vector<shade::triangle<T>> tris;
};

template <class T>
v3<T> random_in_cube(shade::rng& g, T half_width) {
    return v3<T>(T(2) * g.uniform<T>() - T(1), T(2) * g.uniform<T>() - T(1),
                 T(2) * g.uniform<T>() - T(1)) *
           half_width;
}

// Barycentrics (b1, b2) of a point clearly inside (margin 0.05 from every edge) or
// clearly outside (0.05 to 0.5 beyond one of the three edges, chosen at random) the
// triangle, so that every algorithm, GLM's epsilons included, agrees on the outcome.
template <class T>
std::pair<T, T> random_barycentrics(shade::rng& g, bool inside) {
    for (;;) {
        const T b1 = T(-0.5) + T(2) * g.uniform<T>();
        const T b2 = T(-0.5) + T(2) * g.uniform<T>();
        const T b0 = T(1) - b1 - b2;
        const T lowest = std::min(b0, std::min(b1, b2));
        if (inside ? lowest >= T(0.05) : (lowest <= T(-0.05) && lowest >= T(-0.5)))
            return {b1, b2};
    }
}

// Random triangles (vertices within 1 of a centre in [-2, 2]^3) and rays from 2 to 6 away
// aimed at a point of the triangle's plane inside it with probability hit_fraction.
template <class T>
pair_data<T> make_pairs(double hit_fraction, std::uint64_t seed, std::size_t count = pair_count<T>) {
    shade::rng g(seed);
    pair_data<T> data;
    for (std::size_t i = 0; i < count; ++i) {
        const v3<T> centre = random_in_cube<T>(g, T(2));
        const shade::triangle<T> tri{centre + random_in_cube<T>(g, T(1)),
                                     centre + random_in_cube<T>(g, T(1)),
                                     centre + random_in_cube<T>(g, T(1))};
        const bool inside = g.uniform<double>() < hit_fraction;
        const auto [b1, b2] = random_barycentrics<T>(g, inside);
        const v3<T> target = tri.v0 + b1 * (tri.v1 - tri.v0) + b2 * (tri.v2 - tri.v0);
        const v3<T> offset = random_in_cube<T>(g, T(1));
        const T length = glm::length(offset);
        const v3<T> origin = target + offset * ((T(2) + T(4) * g.uniform<T>()) / std::max(length, T(0.1)));
        data.rays.push_back(shade::ray<T>{origin, target - origin});
        data.tris.push_back(tri);
    }
    return data;
}

// One test of each routine, reduced to the same outcome record. find_intersection is the
// lean test (t, barycentrics, front face), the same job GLM does; intersect also builds
// the full record (hit point and unit normal), which a renderer needs once per ray.
template <class Algorithm, class T>
outcome<T> run_shade(const shade::ray<T>& r, const shade::triangle<T>& tri) {
    const auto x = shade::find_intersection<Algorithm>(r, tri);
    if (!x) return {};
    return {1, x->t, x->barycentric.y, x->barycentric.z};
}

template <class Algorithm, class T>
outcome<T> run_shade_record(const shade::ray<T>& r, const shade::triangle<T>& tri) {
    const auto h = shade::intersect<Algorithm>(r, tri);
    if (!h) return {};
    // The point and normal are kept too, so that they are computed.
    benchmark::DoNotOptimize(h->p);
    benchmark::DoNotOptimize(h->n);
    return {1, h->t, h->barycentric.y, h->barycentric.z};
}

// GLM with the t > 0 check it lacks (it reports hits behind the origin), so that it does
// the same job as shade's routines. GLM's own epsilon on det stays.
template <class T>
outcome<T> run_glm(const shade::ray<T>& r, const shade::triangle<T>& tri) {
    glm::vec<2, T> bary;
    T distance;
    if (glm::intersectRayTriangle(r.origin, r.direction, tri.v0, tri.v1, tri.v2, bary, distance) &&
        distance > T(0))
        return {1, distance, bary.x, bary.y};
    return {};
}

template <class T, class Run>
double hit_rate(const pair_data<T>& data, Run run) {
    std::size_t hits = 0;
    for (std::size_t i = 0; i < data.rays.size(); ++i) hits += static_cast<std::size_t>(run(data.rays[i], data.tris[i]).hit);
    return static_cast<double>(hits) / static_cast<double>(data.rays.size());
}

// Every pair in storage order, or in `order` when one is given (a permutation of the
// pairs: bench/support.hpp, random_order).
template <class T, class Run>
void add_pairs(const std::string& name, const pair_data<T>& data, Run run,
               const std::vector<std::uint32_t>* order = nullptr) {
    shade_bench::add(
        name, double(data.rays.size()),
        [&data, run, order] {
            if (order == nullptr) {
                for (std::size_t i = 0; i < data.rays.size(); ++i) {
                    outcome<T> o = run(data.rays[i], data.tris[i]);
                    benchmark::DoNotOptimize(o);
                }
            } else {
                for (const std::uint32_t i : *order) {
                    outcome<T> o = run(data.rays[i], data.tris[i]);
                    benchmark::DoNotOptimize(o);
                }
            }
        },
        hit_rate(data, run));
}

// Pairs per "_memory" data set: more bytes than the last-level cache holds.
template <class T>
constexpr std::size_t memory_pair_count =
    shade_bench::beyond_cache_bytes / (sizeof(shade::ray<T>) + sizeof(shade::triangle<T>));

// The variants of one scalar group, over data in `order` (nullptr: storage order).
template <class T>
void add_scalar_group(const std::string& group, const pair_data<T>& data, const std::vector<std::uint32_t>* order) {
    add_pairs<T>(group + "glm", data, run_glm<T>, order);
    add_pairs<T>(group + "moller_trumbore", data, run_shade<shade::moller_trumbore, T>, order);
    add_pairs<T>(group + "plane_then_areas", data, run_shade<shade::plane_then_areas, T>, order);
    add_pairs<T>(group + "watertight", data, run_shade<shade::watertight, T>, order);
    add_pairs<T>(group + "moller_trumbore_record", data, run_shade_record<shade::moller_trumbore, T>, order);
}

template <class T>
void register_scalar(const char* type) {
    // Static storage: the benchmarks refer to the data while they run.
    static const std::array<pair_data<T>, 3> sets{make_pairs<T>(0.0, 11), make_pairs<T>(0.5, 12),
                                                  make_pairs<T>(1.0, 13)};
    const char* rates[3] = {"hit0", "hit50", "hit100"};
    for (std::size_t k = 0; k < 3; ++k) {
        add_scalar_group<T>(std::string("triangle/") + type + "/" + rates[k] + "/", sets[k], nullptr);
    }
    if (!shade_bench::with_order_variants()) return;
    // The same pairs in a random order, and (at 50 % hits) a set larger than the
    // last-level cache, in a random order.
    static const auto shuffled = shade_bench::random_order(pair_count<T>, 14);
    for (std::size_t k = 0; k < 3; ++k)
        add_scalar_group<T>(std::string("triangle/") + type + "/" + rates[k] + "_shuffled/", sets[k], &shuffled);
    static const pair_data<T> many = make_pairs<T>(0.5, 15, memory_pair_count<T>);
    static const auto memory_order = shade_bench::random_order(memory_pair_count<T>, 16);
    add_scalar_group<T>(std::string("triangle/") + type + "/hit50_memory/", many, &memory_order);
}

// ---- batch: one ray against 16 triangles placed along it ------------------------------

constexpr std::size_t lanes = 16;
template <class T>
constexpr std::size_t ray_count = pair_count<T> / lanes;

template <class T>
struct batch_data {
    pair_data<T> pairs; // pair i: ray i / 16 and triangle i
    std::vector<shade::triangle_batch<T, 8>> batches8;   // 2 per ray
    std::vector<shade::triangle_batch<T, 16>> batches16; // 1 per ray
};

// 32 rays; along each, 16 random triangles at t = 1 .. 16 that the ray pierces inside
// (probability hit_fraction) or beside an edge.
template <class T>
batch_data<T> make_batches(double hit_fraction, std::uint64_t seed, std::size_t rays = ray_count<T>) {
    shade::rng g(seed);
    batch_data<T> data;
    for (std::size_t k = 0; k < rays; ++k) {
        const v3<T> origin = random_in_cube<T>(g, T(4));
        v3<T> direction = random_in_cube<T>(g, T(1));
        direction /= std::max(glm::length(direction), T(0.1));
        const shade::ray<T> r{origin, direction};
        std::array<shade::triangle<T>, lanes> tris;
        for (std::size_t j = 0; j < lanes; ++j) {
            shade::triangle<T> tri{random_in_cube<T>(g, T(1)), random_in_cube<T>(g, T(1)),
                                   random_in_cube<T>(g, T(1))};
            const bool inside = g.uniform<double>() < hit_fraction;
            const auto [b1, b2] = random_barycentrics<T>(g, inside);
            const v3<T> target = tri.v0 + b1 * (tri.v1 - tri.v0) + b2 * (tri.v2 - tri.v0);
            const v3<T> shift = r.at(T(j + 1)) - target;
            tri = {tri.v0 + shift, tri.v1 + shift, tri.v2 + shift};
            tris[j] = tri;
            data.pairs.rays.push_back(r);
            data.pairs.tris.push_back(tri);
        }
        data.batches8.emplace_back(std::span<const shade::triangle<T>>(tris.data(), 8));
        data.batches8.emplace_back(std::span<const shade::triangle<T>>(tris.data() + 8, 8));
        data.batches16.emplace_back(std::span<const shade::triangle<T>>(tris.data(), 16));
    }
    return data;
}

template <class T, std::size_t N>
double batch_hit_rate(const shade::ray<T>* rays, const std::vector<shade::triangle_batch<T, N>>& batches,
                      std::size_t per_ray) {
    std::size_t hits = 0;
    for (std::size_t b = 0; b < batches.size(); ++b) hits += shade::intersect(rays[(b / per_ray) * lanes], batches[b]).count();
    return static_cast<double>(hits) / static_cast<double>(batches.size() * N);
}

// One ray against each of data's batches of N (per_ray of them per ray), in storage order
// or, when `order` is given, rays in that order (a permutation of the rays).
template <class T, std::size_t N>
void add_batches(const std::string& name, const batch_data<T>& data,
                 const std::vector<shade::triangle_batch<T, N>>& batches, const std::vector<std::uint32_t>* order) {
    constexpr std::size_t per_ray = lanes / N;
    shade_bench::add(
        name, double(batches.size() * N),
        [&data, &batches, order] {
            if (order == nullptr) {
                for (std::size_t b = 0; b < batches.size(); ++b) {
                    auto all = shade::intersect(data.pairs.rays[(b / per_ray) * lanes], batches[b]);
                    benchmark::DoNotOptimize(all);
                }
            } else {
                for (const std::uint32_t k : *order) {
                    for (std::size_t j = 0; j < per_ray; ++j) {
                        auto all = shade::intersect(data.pairs.rays[k * lanes], batches[k * per_ray + j]);
                        benchmark::DoNotOptimize(all);
                    }
                }
            }
        },
        batch_hit_rate<T, N>(data.pairs.rays.data(), batches, per_ray));
}

// The variants of one batch group; with an order, the scalar ones visit the pairs of
// each ray in that ray order too.
template <class T>
void add_batch_group(const std::string& group, const batch_data<T>& data, const std::vector<std::uint32_t>* order) {
    std::vector<std::uint32_t>* pair_order = nullptr;
    if (order != nullptr) {
        static std::deque<std::vector<std::uint32_t>> keep; // lives as long as the benchmarks
        std::vector<std::uint32_t> pairs;
        for (const std::uint32_t k : *order)
            for (std::size_t j = 0; j < lanes; ++j) pairs.push_back(static_cast<std::uint32_t>(k * lanes + j));
        keep.push_back(std::move(pairs));
        pair_order = &keep.back();
    }
    add_pairs<T>(group + "glm", data.pairs, run_glm<T>, pair_order);
    add_pairs<T>(group + "moller_trumbore", data.pairs, run_shade<shade::moller_trumbore, T>, pair_order);
    add_batches<T, 8>(group + "batch8", data, data.batches8, order);
    add_batches<T, 16>(group + "batch16", data, data.batches16, order);
}

template <class T>
void register_batch(const char* type) {
    static const std::array<batch_data<T>, 3> sets{make_batches<T>(0.0, 21), make_batches<T>(0.5, 22),
                                                   make_batches<T>(1.0, 23)};
    const char* rates[3] = {"hit0", "hit50", "hit100"};
    for (std::size_t k = 0; k < 3; ++k)
        add_batch_group<T>(std::string("triangle_batch/") + type + "/" + rates[k] + "/", sets[k], nullptr);
    if (!shade_bench::with_order_variants()) return;
    // Rays in a random order over the same data, and (50 % hits) over a set larger than
    // the last-level cache.
    static const auto shuffled = shade_bench::random_order(ray_count<T>, 24);
    for (std::size_t k = 0; k < 3; ++k)
        add_batch_group<T>(std::string("triangle_batch/") + type + "/" + rates[k] + "_shuffled/", sets[k], &shuffled);
    // Bytes per ray: 16 pairs, 2 batches of 8 and one of 16.
    constexpr std::size_t ray_bytes = lanes * (sizeof(shade::ray<T>) + sizeof(shade::triangle<T>)) +
                                      2 * sizeof(shade::triangle_batch<T, 8>) + sizeof(shade::triangle_batch<T, 16>);
    constexpr std::size_t memory_rays = shade_bench::beyond_cache_bytes / ray_bytes;
    static const batch_data<T> many = make_batches<T>(0.5, 25, memory_rays);
    static const auto memory_order = shade_bench::random_order(memory_rays, 26);
    add_batch_group<T>(std::string("triangle_batch/") + type + "/hit50_memory/", many, &memory_order);
}

// ---- the machine's vector throughput: the batch kernel's arithmetic bound ------------
//
// The kernel does 18 multiplications and 14 additions per lane before it decides hit or
// miss (triangle_batch.hpp). Here: the time of one vector multiplication or addition when
// nothing but their throughput limits it (12 independent chains of a multiply and an add,
// enough to cover the 4-cycle latencies of two ports), for the vectors the batch uses on
// this CPU: 32 bytes (AVX, batches of 8 floats) and 64 bytes (AVX-512F, 16 floats).
// bench/report.py divides the batch's time per test by 32 such operations / lanes.

#if defined(__GNUC__) && defined(__x86_64__)
constexpr std::size_t vector_chains = 12;
constexpr std::size_t vector_steps = 256; // per iteration: 12 x 256 x 2 vector operations

template <std::size_t Bytes>
using float_vector [[gnu::vector_size(Bytes)]] = float;

template <std::size_t Bytes>
[[gnu::always_inline]] inline void vector_ops(float* out) {
    using V = float_vector<Bytes>;
    // Factors read through volatile, so the compiler cannot evaluate the loop at compile
    // time (nor reorder it: floating-point arithmetic is not associative).
    static volatile float factor = 0.999999f, offset = 1e-7f;
    V acc[vector_chains];
    V m, c;
    for (std::size_t i = 0; i < Bytes / 4; ++i) {
        m[i] = factor;
        c[i] = offset;
    }
    for (std::size_t j = 0; j < vector_chains; ++j)
        for (std::size_t i = 0; i < Bytes / 4; ++i) acc[j][i] = float(j + i);
    for (std::size_t k = 0; k < vector_steps; ++k) {
        for (std::size_t j = 0; j < vector_chains; ++j) {
            acc[j] = acc[j] * m; // two statements: clang++ contracts only within one
            acc[j] = acc[j] + c;
        }
    }
    for (std::size_t j = 0; j < vector_chains; ++j) out[j] = acc[j][0];
}

// Compiled for AVX (which has no FMA) and for AVX-512F with contraction off (g++; clang++
// contracts only within an expression), so the multiply and the add stay two
// instructions, as in the batch kernel.
[[gnu::target("avx")]] [[gnu::noinline]] void vector_ops_avx(float* out) { vector_ops<32>(out); }
#if !defined(__clang__)
#pragma GCC push_options
#pragma GCC optimize("fp-contract=off")
#endif
[[gnu::target("avx512f")]] [[gnu::noinline]] void vector_ops_avx512(float* out) { vector_ops<64>(out); }
#if !defined(__clang__)
#pragma GCC pop_options
#endif

void register_vector_ops() {
    constexpr double ops = double(vector_chains * vector_steps * 2);
    __builtin_cpu_init();
    if (__builtin_cpu_supports("avx"))
        shade_bench::add("machine/float/vector_op/avx", ops, [] {
            float out[vector_chains];
            vector_ops_avx(out);
            benchmark::DoNotOptimize(out);
        });
    if (__builtin_cpu_supports("avx512f"))
        shade_bench::add("machine/float/vector_op/avx512f", ops, [] {
            float out[vector_chains];
            vector_ops_avx512(out);
            benchmark::DoNotOptimize(out);
        });
}
#else
void register_vector_ops() {}
#endif

const bool registered = [] {
    // Which form of the batch kernel runs here (the build's target, or AVX selected at run
    // time); bench/report.py prints it with the machine description.
    benchmark::AddCustomContext("triangle_batch_kernel", shade::triangle_batch_kernel());
    register_scalar<float>("float");
    register_scalar<double>("double");
    register_batch<float>("float");
    register_batch<double>("double");
    register_vector_ops();
    return true;
}();

} // namespace
