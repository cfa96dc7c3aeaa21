#include "support/progress.hpp"

#include <algorithm>
#include <cstdio>
#include <utility>

#if defined(__unix__) || defined(__APPLE__)
#include <unistd.h>
#endif

namespace shade::examples {

bool stderr_is_terminal() noexcept {
#if defined(__unix__) || defined(__APPLE__)
    return isatty(STDERR_FILENO) == 1;
#else
    return false;
#endif
}

progress::progress(std::string program, std::uint64_t total, bool enabled)
    : program_(std::move(program)), total_(total), start_(std::chrono::steady_clock::now()) {
    if (enabled && stderr_is_terminal()) drawer_ = std::thread([this] { draw_loop(); });
}

progress::~progress() {
    stop_.store(true);
    if (drawer_.joinable()) drawer_.join();
}

void progress::draw_loop() {
    constexpr int width = 40;
    bool shown = false;
    while (!stop_.load()) {
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
        const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
        if (elapsed < 1.0) continue;
        shown = true;
        const std::uint64_t done = std::min(done_.load(std::memory_order_relaxed), total_);
        const double fraction = total_ == 0 ? 1.0 : double(done) / double(total_);
        const int filled = static_cast<int>(width * fraction);
        std::fprintf(stderr, "\r%s: [%-*.*s] %3d%% %.1fs", program_.c_str(), width, filled,
                     "########################################", static_cast<int>(100 * fraction), elapsed);
        std::fflush(stderr);
    }
    if (shown) {
        std::fprintf(stderr, "\r%*s\r", static_cast<int>(program_.size()) + width + 20, "");
        std::fflush(stderr);
    }
}

} // namespace shade::examples
