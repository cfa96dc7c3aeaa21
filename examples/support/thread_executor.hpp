#pragma once
// support::thread_executor: a shade::parallel_executor on std::thread, for the examples,
// the tests and the benchmarks (the library itself includes no <thread>; see
// shade/core/parallel.hpp). Each run(n, task) starts up to threads - 1 threads and works
// on the caller's thread too; every thread takes the next index from a shared counter
// until none is left, so unequal tasks balance. An exception from a task is kept (the
// first one) and rethrown by run once every thread has stopped.
//
// Usage:
//     const support::thread_executor threads;          // std::thread::hardware_concurrency()
//     const shade::triangle_bvh<float> mesh(tris, shade::bvh_width::automatic, threads);

#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

#include <shade/core/parallel.hpp>

namespace support {

class thread_executor {
public:
    /// Runs on `threads` threads (the caller's included); 0: as many as the hardware has.
    explicit thread_executor(unsigned threads = 0)
        : threads_(threads != 0 ? threads : (std::thread::hardware_concurrency() != 0 ? std::thread::hardware_concurrency() : 1u)) {}

    /// The number of threads run uses, the caller's included.
    [[nodiscard]] unsigned threads() const noexcept { return threads_; }

    void operator()(std::size_t n, const shade::parallel_task& task) const {
        if (n == 0) return;
        std::atomic<std::size_t> next{0};
        std::exception_ptr error;
        std::mutex error_mutex;
        const auto work = [&] {
            for (std::size_t i; (i = next.fetch_add(1, std::memory_order_relaxed)) < n;) {
                try {
                    task(i);
                } catch (...) {
                    const std::lock_guard<std::mutex> lock(error_mutex);
                    if (!error) error = std::current_exception();
                }
            }
        };
        const std::size_t helpers = n < threads_ ? n - 1 : threads_ - 1;
        std::vector<std::thread> pool;
        pool.reserve(helpers);
        try {
            for (std::size_t t = 0; t < helpers; ++t) pool.emplace_back(work);
        } catch (const std::system_error&) {
            // No more threads to be had: those started and this one do the rest.
        }
        work();
        for (std::thread& t : pool) t.join();
        if (error) std::rethrow_exception(error);
    }

private:
    unsigned threads_;
};

} // namespace support
