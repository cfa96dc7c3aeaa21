#pragma once
// A progress line for the example programs' long runs, drawn on stderr only when stderr is
// a terminal (in a log file or a pipe a redrawn line would only add carriage returns).
//
//   ex::progress bar("properties", rows.size(), !quiet);
//   for (...) { ...work...; bar.advance(); }   // advance() may be called from any thread
//
// The line, "[#####      ]  42% 12.3s", appears once the work has taken 1 s (short runs
// print nothing), is redrawn every 100 ms by a thread of the bar's own, and is erased when
// the bar is destroyed, so the program's own messages start on a clean line.

#include <atomic>
#include <chrono>
#include <cstdint>
#include <string>
#include <thread>

namespace shade::examples {

/// True when stderr is a terminal.
[[nodiscard]] bool stderr_is_terminal() noexcept;

class progress {
public:
    /// A bar for `total` steps (0 is allowed: the bar then shows 100%). Nothing is drawn
    /// unless `enabled` and stderr is a terminal.
    progress(std::string program, std::uint64_t total, bool enabled);
    progress(const progress&) = delete;
    progress& operator=(const progress&) = delete;
    /// Stops the drawing thread and erases the line if one was drawn.
    ~progress();

    /// Records `steps` more steps done. Thread-safe.
    void advance(std::uint64_t steps = 1) noexcept { done_.fetch_add(steps, std::memory_order_relaxed); }

private:
    void draw_loop();

    std::string program_;
    std::uint64_t total_;
    std::atomic<std::uint64_t> done_{0};
    std::atomic<bool> stop_{false};
    std::chrono::steady_clock::time_point start_;
    std::thread drawer_;
};

} // namespace shade::examples
