#include "support/cli.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <atomic>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <exception>
#include <fcntl.h>
#include <mutex>
#include <unistd.h>

namespace shade::examples {

namespace {

/// The concatenation of the parts, appended one by one. (g++ 12 at -O3 reports a false
/// -Wrestrict overlap, GCC bug 105329, for `"literal" + std::string` chains.)
template <class... Parts>
std::string concat(const Parts&... parts) {
    std::string s;
    (s.append(std::string_view(parts)), ...);
    return s;
}

} // namespace

int run_cli(std::string_view program, const std::function<int()>& body, int failure_status) {
    const std::string name(program);
    try {
        return body();
    } catch (const usage_error& e) {
        std::fprintf(stderr, "%s: %s\n(try --help)\n", name.c_str(), e.what());
        return exit_usage_error;
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "%s: out of memory\n", name.c_str());
        return failure_status;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: %s\n", name.c_str(), e.what());
        return failure_status;
    }
}

namespace detail {

namespace {

template <std::integral I>
std::string integer_text(I x) {
    std::array<char, 24> buffer{};
    const auto [end, ec] = std::to_chars(buffer.data(), buffer.data() + buffer.size(), x);
    return ec == std::errc() ? std::string(buffer.data(), end) : std::string("?");
}

} // namespace

std::string integer_range(std::intmax_t min, std::intmax_t max) {
    return concat("[", integer_text(min), ", ", integer_text(max), "]");
}

std::string integer_range(std::uintmax_t min, std::uintmax_t max) {
    return concat("[", integer_text(min), ", ", integer_text(max), "]");
}

void throw_not_whole(std::string_view option, std::string_view text, const std::string& range) {
    throw usage_error("option " + std::string(option) + " needs a whole number in " + range + ", got '" +
                      std::string(text) + "'");
}

void throw_out_of_range(std::string_view option, std::string_view text, const std::string& range) {
    throw usage_error("option " + std::string(option) + " must be in " + range + ", got " + std::string(text));
}

} // namespace detail

namespace {

std::string shortest(double x) {
    std::array<char, 32> buffer{};
    const auto [end, ec] = std::to_chars(buffer.data(), buffer.data() + buffer.size(), x);
    return ec == std::errc() ? std::string(buffer.data(), end) : std::string("?");
}

} // namespace

double parse_real(std::string_view option, std::string_view text, double min, double max, lower_limit kind) {
    const std::string range =
        concat(kind == lower_limit::exclusive ? "(" : "[", shortest(min), ", ", shortest(max), "]");
    double value = 0;
    const char* const last = text.data() + text.size();
    const auto [end, ec] = std::from_chars(text.data(), last, value);
    // A number too large for a double ("1e400") is out of range; a NaN is no number.
    if (ec == std::errc::result_out_of_range && end == last) detail::throw_out_of_range(option, text, range);
    if (ec != std::errc() || end != last || std::isnan(value)) {
        throw usage_error("option " + std::string(option) + " needs a number in " + range + ", got '" +
                          std::string(text) + "'");
    }
    const bool above_min = kind == lower_limit::exclusive ? value > min : value >= min;
    if (!above_min || !(value <= max) || !std::isfinite(value)) detail::throw_out_of_range(option, text, range);
    return value;
}

bool command_line::next() noexcept {
    if (index_ + 1 >= argc_) return false;
    current_ = argv_[++index_];
    option_ = {};
    value_ = {};
    return true;
}

bool command_line::option(std::string_view name) {
    if (current_ != name) return false;
    if (index_ + 1 >= argc_) throw usage_error("option " + std::string(name) + " needs a value");
    option_ = name;
    value_ = argv_[++index_];
    return true;
}

std::string command_line::non_empty_text() const {
    if (value_.empty()) throw usage_error("option " + std::string(option_) + " needs a non-empty value");
    return std::string(value_);
}

void command_line::unknown() const {
    if (is_option()) throw usage_error("unknown option '" + std::string(current_) + "'");
    throw usage_error("unexpected argument '" + std::string(current_) + "'");
}

void check_limit(std::string_view what, std::uint64_t value, std::uint64_t limit) {
    if (value > limit)
        throw usage_error(std::string(what) + " is " + std::to_string(value) + ", more than the limit of " +
                          std::to_string(limit));
}

std::string output_format(std::string_view option, const std::filesystem::path& path,
                          std::initializer_list<std::string_view> supported) {
    std::string extension = path.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    for (const std::string_view s : supported)
        if (extension == s) return extension;
    std::string list;
    for (const std::string_view s : supported) list = concat(list, list.empty() ? "" : ", ", s);
    const std::string problem =
        extension.empty() ? std::string("no file extension") : concat("unsupported format '", extension, "'");
    throw usage_error(concat("option ", option, ": cannot write '", path.string(), "': ", problem, " (supported: ",
                             list, ")"));
}

// ---- temporary files removed on SIGINT, SIGTERM and SIGHUP ----
//
// The registry is a fixed table of path buffers, so that the signal handler touches only
// memory that exists for the whole program and calls only unlink (async-signal-safe,
// POSIX.1-2017 section 2.4.3). A slot is filled before its flag is set and its flag cleared
// before the slot is reused; the handler reads a slot only while its flag is set.

namespace {

constexpr std::size_t max_temporaries = 16;
constexpr std::size_t max_path = 4096;

struct registry {
    std::array<std::array<char, max_path>, max_temporaries> paths{};
    std::array<std::atomic<bool>, max_temporaries> used{};
    std::mutex mutex; // between threads registering files; never taken by the handler
    bool handlers_installed = false;
};

registry& temporaries() {
    static registry r;
    return r;
}

extern "C" void remove_temporaries_and_die(int signal_number) {
    registry& r = temporaries();
    for (std::size_t i = 0; i < max_temporaries; ++i)
        if (r.used[i].load()) ::unlink(r.paths[i].data());
    std::signal(signal_number, SIG_DFL);
    std::raise(signal_number);
}

// Registers a temporary path; -1 if it does not fit (then only SIGKILL-like behaviour:
// the file may stay after a signal, the target is still never half-written).
int register_temporary(const std::filesystem::path& p) {
    registry& r = temporaries();
    const std::string& s = p.native();
    if (s.size() + 1 > max_path) return -1;
    const std::lock_guard lock(r.mutex);
    if (!r.handlers_installed) {
        for (const int sig : {SIGINT, SIGTERM, SIGHUP}) {
            struct sigaction action {};
            action.sa_handler = remove_temporaries_and_die;
            sigemptyset(&action.sa_mask);
            struct sigaction previous {};
            // A signal the caller chose to ignore stays ignored.
            if (sigaction(sig, nullptr, &previous) == 0 && previous.sa_handler == SIG_IGN) continue;
            sigaction(sig, &action, nullptr);
        }
        r.handlers_installed = true;
    }
    for (std::size_t i = 0; i < max_temporaries; ++i) {
        if (r.used[i].load()) continue;
        std::memcpy(r.paths[i].data(), s.c_str(), s.size() + 1);
        r.used[i].store(true);
        return int(i);
    }
    return -1;
}

void unregister_temporary(int slot) {
    if (slot >= 0) temporaries().used[std::size_t(slot)].store(false);
}

} // namespace

output_file::output_file(std::filesystem::path target) : target_(std::move(target)) {
    namespace fs = std::filesystem;
    if (target_.empty()) throw usage_error("the output path is empty");
    const std::string shown = concat("'", target_.string(), "'");
    if (!target_.has_filename()) throw usage_error("output path " + shown + " names a directory, not a file");
    std::error_code ec;
    if (fs::is_directory(target_, ec)) throw usage_error("output path " + shown + " is a directory");
    const fs::path directory = target_.parent_path().empty() ? fs::path(".") : target_.parent_path();
    if (!fs::exists(directory, ec))
        throw usage_error("cannot write " + shown + ": directory '" + directory.string() + "' does not exist");
    if (!fs::is_directory(directory, ec))
        throw usage_error("cannot write " + shown + ": '" + directory.string() + "' is not a directory");

    static std::atomic<unsigned> counter{0};
    const std::string base = target_.filename().string() + ".partial-" + std::to_string(::getpid()) + "-";
    for (int attempt = 0; attempt < 100; ++attempt) {
        const fs::path candidate = target_.parent_path() / (base + std::to_string(counter.fetch_add(1)));
        const int fd = ::open(candidate.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd >= 0) {
            ::close(fd);
            temporary_ = candidate;
            slot_ = register_temporary(temporary_);
            return;
        }
        if (errno != EEXIST) throw usage_error("cannot write " + shown + ": " + std::strerror(errno));
    }
    throw usage_error("cannot write " + shown + ": no free temporary name '" + base + "N'");
}

output_file::~output_file() {
    if (!committed_) {
        std::error_code ec;
        std::filesystem::remove(temporary_, ec);
    }
    unregister_temporary(slot_);
}

void output_file::commit() {
    if (committed_) return;
    std::error_code ec;
    std::filesystem::rename(temporary_, target_, ec);
    if (ec) throw std::runtime_error("cannot write '" + target_.string() + "': " + ec.message());
    committed_ = true;
    unregister_temporary(slot_);
    slot_ = -1;
}

} // namespace shade::examples
