#pragma once
// support::thread_executor: a shade::parallel_executor on std::thread, for the examples,
// the tests and the benchmarks (the library itself includes no <thread>; see
// shade/core/parallel.hpp). It keeps threads - 1 helper threads for its lifetime (started
// by the constructor, stopped by the destructor); each run(n, task) wakes them and works on
// the caller's thread too; every thread takes the next index from a shared counter until
// none is left, so unequal tasks balance. Between runs a helper first polls for the next
// one for a moment (spin_polls, with std::this_thread::yield) and then sleeps on a
// condition variable, so that the many short runs of one build pay neither a thread start
// nor, mostly, a wake-up. A run while another is under way on the same executor (from a
// task, or from another thread) runs its tasks in order on its caller's thread. An
// exception from a task is kept (the first one) and rethrown by run once every thread has
// stopped working on that run.
//
// Usage:
//     const support::thread_executor threads;          // std::thread::hardware_concurrency()
//     const shade::triangle_bvh<float> mesh(tris, shade::bvh_width::automatic, threads);

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <memory>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

#include <shade/core/parallel.hpp>

namespace support {

class thread_executor {
public:
    /// Polls (each a yield) of a helper for the next run before it sleeps, and of the
    /// caller for the helpers that joined a run before it sleeps.
    static constexpr int spin_polls = 50;

    /// Runs on `threads` threads (the caller's included); 0: as many as the hardware has.
    /// Fewer if the system refuses to start more.
    explicit thread_executor(unsigned threads = 0)
        : threads_(threads != 0 ? threads : (std::thread::hardware_concurrency() != 0 ? std::thread::hardware_concurrency() : 1u)),
          state_(std::make_unique<state>()) {
        helpers_.reserve(threads_ - 1);
        try {
            for (unsigned t = 1; t < threads_; ++t) helpers_.emplace_back([s = state_.get()] { s->helper(); });
        } catch (const std::system_error&) {
            // No more threads to be had: those started and the caller's do the work.
        }
        state_->helpers = static_cast<unsigned>(helpers_.size());
    }
    thread_executor(const thread_executor&) = delete;
    thread_executor& operator=(const thread_executor&) = delete;
    ~thread_executor() {
        {
            const std::lock_guard<std::mutex> lock(state_->mutex);
            state_->stop.store(true, std::memory_order_relaxed);
        }
        state_->wake.notify_all();
        for (std::thread& t : helpers_) t.join();
    }

    /// The number of threads run uses, the caller's included.
    [[nodiscard]] unsigned threads() const noexcept { return threads_; }

    void operator()(std::size_t n, const shade::parallel_task& task) const {
        if (n == 0) return;
        state& s = *state_;
        bool idle = false;
        if (n == 1 || s.helpers == 0 || !s.busy.compare_exchange_strong(idle, true, std::memory_order_acquire)) {
            run_here(n, task);
            return;
        }
        {
            const std::lock_guard<std::mutex> lock(s.mutex);
            s.task = &task;
            s.n = n;
            s.next.store(0, std::memory_order_relaxed);
            s.error = nullptr;
            s.open.store(true, std::memory_order_seq_cst);
            s.generation.fetch_add(1, std::memory_order_release);
        }
        s.wake.notify_all();
        s.work();
        // Closed: a helper that wakes from now on leaves without touching the run; those
        // that joined it are waited for (each is working on a task or about to find none).
        s.open.store(false, std::memory_order_seq_cst);
        for (int i = 0; i < spin_polls && s.joined.load(std::memory_order_seq_cst) != 0; ++i) std::this_thread::yield();
        if (s.joined.load(std::memory_order_seq_cst) != 0) {
            std::unique_lock<std::mutex> lock(s.mutex);
            s.done.wait(lock, [&] { return s.joined.load(std::memory_order_seq_cst) == 0; });
        }
        std::exception_ptr error = s.error;
        s.task = nullptr;
        s.busy.store(false, std::memory_order_release);
        if (error) std::rethrow_exception(error);
    }

private:
    /// What the caller and the helpers share.
    struct state {
        std::mutex mutex;              // guards the sleeps and the start of a run
        std::condition_variable wake;  // helpers: a run started (or stop)
        std::condition_variable done;  // caller: the helpers that joined the run left it
        std::atomic<bool> busy{false}; // a run is under way
        std::atomic<bool> stop{false};
        std::atomic<bool> open{false}; // helpers may join the run under way
        std::atomic<std::uint64_t> generation{0}; // runs started
        std::atomic<unsigned> joined{0};          // helpers working on the run
        std::atomic<std::size_t> next{0};         // the next index to take
        const shade::parallel_task* task = nullptr;
        std::size_t n = 0;
        unsigned helpers = 0;
        std::mutex error_mutex;
        std::exception_ptr error;

        void work() {
            for (std::size_t i; (i = next.fetch_add(1, std::memory_order_relaxed)) < n;) {
                try {
                    (*task)(i);
                } catch (...) {
                    const std::lock_guard<std::mutex> lock(error_mutex);
                    if (!error) error = std::current_exception();
                }
            }
        }

        void helper() {
            std::uint64_t seen = 0;
            for (;;) {
                const auto started = [&] {
                    return generation.load(std::memory_order_acquire) != seen || stop.load(std::memory_order_relaxed);
                };
                for (int i = 0; i < spin_polls && !started(); ++i) std::this_thread::yield();
                if (!started()) {
                    std::unique_lock<std::mutex> lock(mutex);
                    wake.wait(lock, started);
                }
                if (stop.load(std::memory_order_relaxed)) return;
                seen = generation.load(std::memory_order_acquire);
                // Joins the run unless the caller closed it (then the caller may be setting
                // up the next one: task and n are not to be read). Joining before looking
                // (both sequentially consistent) means the caller, which closes before it
                // counts, either waits for this helper or was seen closing by it.
                joined.fetch_add(1, std::memory_order_seq_cst);
                if (open.load(std::memory_order_seq_cst)) work();
                if (joined.fetch_sub(1, std::memory_order_seq_cst) == 1) {
                    const std::lock_guard<std::mutex> lock(mutex);
                    done.notify_one();
                }
            }
        }
    };

    /// The tasks in order on the caller's thread, the first exception rethrown at the end.
    static void run_here(std::size_t n, const shade::parallel_task& task) {
        std::exception_ptr error;
        for (std::size_t i = 0; i < n; ++i) {
            try {
                task(i);
            } catch (...) {
                if (!error) error = std::current_exception();
            }
        }
        if (error) std::rethrow_exception(error);
    }

    unsigned threads_;
    std::unique_ptr<state> state_;
    std::vector<std::thread> helpers_;
};

} // namespace support
