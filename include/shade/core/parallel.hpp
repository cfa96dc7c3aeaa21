#pragma once
// shade::parallel_executor: how a caller lends shade threads without shade including
// <thread> (about 50,000 preprocessed lines). Work that can run in parallel (the build of a
// shade::bvh or shade::triangle_bvh) takes an executor: a callable run(n, task) that calls
// task(i) once for every i in [0, n), in any order, on any threads (the caller's among
// them, or not), and returns when all n calls have returned. shade never calls run from
// inside a task, and its tasks write disjoint data, so they need no locks; what they
// compute does not depend on the executor (the same result whatever the threads).
// A task may throw only what allocation throws (std::bad_alloc); an executor should then
// let the other calls finish and rethrow one exception from run.
//
// Usage (std::thread, TBB or OpenMP alike):
//     const auto threads = [](std::size_t n, const shade::parallel_task& task) {
//         #pragma omp parallel for
//         for (std::ptrdiff_t i = 0; i < std::ptrdiff_t(n); ++i) task(std::size_t(i));
//     };
//     const shade::triangle_bvh<float> mesh(tris, shade::bvh_width::automatic, threads);
// shade::serial_executor is the plain loop (the default).

#include <concepts>
#include <cstddef>
#include <type_traits>

namespace shade {

/// One loop body of a parallel loop, by reference (it neither owns nor copies the
/// callable it was made from, which must outlive it): task(i) runs that body for index i.
class parallel_task {
public:
    template <class F>
        requires(!std::same_as<std::remove_cvref_t<F>, parallel_task> && std::invocable<const F&, std::size_t>)
    explicit parallel_task(const F& body) noexcept
        : body_(&body), call_([](const void* b, std::size_t i) { (*static_cast<const F*>(b))(i); }) {}

    /// Runs the body for index i.
    void operator()(std::size_t i) const { call_(body_, i); }

private:
    const void* body_;
    void (*call_)(const void*, std::size_t);
};

/// An executor: run(n, task) calls task(i) for each i in [0, n) exactly once, possibly
/// concurrently, and returns after the last one (see the top of this header).
template <class E>
concept parallel_executor = std::invocable<E&, std::size_t, const parallel_task&>;

/// The executor of one thread: task(0), task(1), ... in order, on the caller's thread.
struct serial_executor {
    void operator()(std::size_t n, const parallel_task& task) const {
        for (std::size_t i = 0; i < n; ++i) task(i);
    }
};

namespace detail {

/// An executor by reference (any parallel_executor E, which must outlive it), so that
/// non-template code can take one.
class executor_ref {
public:
    template <parallel_executor E>
        requires(!std::same_as<std::remove_cvref_t<E>, executor_ref>)
    explicit executor_ref(E& run) noexcept
        : run_(const_cast<std::remove_const_t<E>*>(&run)), call_([](void* e, std::size_t n, const parallel_task& t) { (*static_cast<E*>(e))(n, t); }),
          serial_(std::same_as<std::remove_cvref_t<E>, serial_executor>) {}

    /// Whether it refers to a shade::serial_executor: then the work may take a path made
    /// for one thread (whose result must be the same as the parallel path's).
    [[nodiscard]] bool serial() const noexcept { return serial_; }

    /// Runs body(i) for every i in [0, n) through the executor.
    template <class F>
    void operator()(std::size_t n, const F& body) const {
        if (n == 0) return;
        const parallel_task task(body);
        call_(run_, n, task);
    }

private:
    void* run_;
    void (*call_)(void*, std::size_t, const parallel_task&);
    bool serial_;
};

} // namespace detail

} // namespace shade
