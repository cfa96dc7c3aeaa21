#pragma once
// support::thread_executor: a shade::parallel_executor on std::thread, for the examples,
// the tests and the benchmarks (the library itself includes no <thread>; see
// shade/core/parallel.hpp). It keeps threads - 1 helper threads for its lifetime (started
// by the constructor, stopped by the destructor); each run(n, task) wakes them and works on
// the caller's thread too; the caller takes indices from the front and the helpers from
// the back until none is left, so unequal tasks balance, and successive runs over the
// same data in index order give each thread about the same part of it (which then stays
// in that core's caches). Between runs a helper first polls for the next
// one for a while (spin_time, yielding its core between polls) and then sleeps on a
// condition variable, so that the many short runs of one build pay neither a thread start
// nor, mostly, a wake-up (a sleeping helper joins a run tens of microseconds late). The
// poll is bounded by time, not by a number of yields: a yield on an idle core takes
// 0.2-0.6 us depending on the machine. A run while another is under way on the same executor (from a
// task, or from another thread) runs its tasks in order on its caller's thread. An
// exception from a task is kept (the first one) and rethrown by run once every thread has
// stopped working on that run.
//
// Usage:
//     const support::thread_executor threads;          // std::thread::hardware_concurrency()
//     const shade::triangle_bvh<float> mesh(tris, shade::bvh_width::automatic, threads);

#include <atomic>
#include <chrono>
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
    /// How long a helper polls for the next run before it sleeps, and the caller for the
    /// helpers that joined a run before it sleeps: longer than the serial steps between
    /// the runs of a small build (a few tens of microseconds).
    static constexpr std::chrono::microseconds spin_time{200};

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
        // (Runs of 2^31 tasks or more, beyond what the halves of `taken` count, too.)
        if (n == 1 || s.helpers == 0 || n >= (std::size_t(1) << 31) ||
            !s.busy.compare_exchange_strong(idle, true, std::memory_order_acquire)) {
            run_here(n, task);
            return;
        }
        {
            const std::lock_guard<std::mutex> lock(s.mutex);
            s.task = &task;
            s.n = n;
            s.taken.store(0, std::memory_order_relaxed);
            s.error = nullptr;
            s.open.store(true, std::memory_order_seq_cst);
            s.generation.fetch_add(1, std::memory_order_release);
        }
        s.wake.notify_all();
        s.work(true);
        // Closed: a helper that wakes from now on leaves without touching the run; those
        // that joined it are waited for (each is working on a task or about to find none).
        s.open.store(false, std::memory_order_seq_cst);
        poll([&] { return s.joined.load(std::memory_order_seq_cst) == 0; });
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
        // Indices taken: from the front (low half), by the caller, and from the back (high
        // half), by the helpers.
        std::atomic<std::uint64_t> taken{0};
        const shade::parallel_task* task = nullptr;
        std::size_t n = 0;
        unsigned helpers = 0;
        std::mutex error_mutex;
        std::exception_ptr error;

        /// Runs tasks until none is left, taking each from the front (the caller) or the
        /// back: a take is good while front and back together stay within n.
        void work(bool front) {
            const std::uint64_t step = front ? 1 : std::uint64_t(1) << 32;
            for (;;) {
                const std::uint64_t t = taken.fetch_add(step, std::memory_order_relaxed);
                const std::uint64_t f = t & 0xffff'ffffu, b = t >> 32;
                if (f + b >= n) return;
                const std::size_t i = front ? f : n - 1 - b;
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
                poll(started);
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
                if (open.load(std::memory_order_seq_cst)) work(false);
                if (joined.fetch_sub(1, std::memory_order_seq_cst) == 1) {
                    const std::lock_guard<std::mutex> lock(mutex);
                    done.notify_one();
                }
            }
        }
    };

    /// Polls ready(), yielding between polls, until it holds or spin_time has passed.
    template <class F>
    static void poll(const F& ready) {
        const auto until = std::chrono::steady_clock::now() + spin_time;
        for (int i = 0; !ready(); ++i) {
            // The clock read every 8 polls: a poll is a fraction of a microsecond.
            if (i % 8 == 7 && std::chrono::steady_clock::now() > until) return;
            std::this_thread::yield();
        }
    }

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
