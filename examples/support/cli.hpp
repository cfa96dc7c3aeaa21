#pragma once
// Command lines and output files of the example programs: one way to read options, check
// numbers against their allowed range, and write outputs so that a failed or interrupted
// run never leaves a half-written file under the requested name.
//
//   namespace ex = shade::examples;
//   int main(int argc, char** argv) {
//       return ex::run_cli("trace", [&] {
//           ex::command_line args(argc, argv);
//           while (args.next()) {
//               if (args.flag("--quiet")) quiet = true;
//               else if (args.option("--width")) width = args.integer(1, 16384);
//               else if (args.option("--out")) out = args.path();
//               else args.unknown();                 // "unknown option '--bogus'"
//           }
//           ex::output_file png(out);                // checks the path before any work
//           ...render...
//           ex::save_png(png.temporary(), image);
//           png.commit();                            // renamed over `out` only now
//           return 0;
//       });
//   }
//
// Errors are exceptions: usage_error for a bad command line or output path (run_cli prints
// "<program>: <message>" and "(try --help)" and returns 2), any other std::exception for a
// failure while working (printed as "<program>: <message>", status 1).

#include <charconv>
#include <concepts>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <initializer_list>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>
#include <type_traits>

namespace shade::examples {

/// A bad command line or output path, found before any work is done. run_cli prints its
/// message and returns exit status 2.
struct usage_error : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// Exit status for a usage error (bad option, value out of range, unwritable output path).
inline constexpr int exit_usage_error = 2;
/// Exit status for a failure while working (an exception other than usage_error).
inline constexpr int exit_failure = 1;

/// Runs `body` (returning the exit status) and turns its exceptions into a message on
/// stderr and a non-zero status: usage_error -> "<program>: <message>\n(try --help)",
/// status 2; any other std::exception (std::bad_alloc included) -> "<program>: <message>",
/// status `failure_status` (1 unless the program gives 1 another meaning).
int run_cli(std::string_view program, const std::function<int()>& body, int failure_status = exit_failure);

/// `text` as an integer of type I in [min, max]. Throws usage_error
/// "option <option> needs a whole number in [min, max], got '<text>'" if it is not one
/// (empty, trailing characters, a fraction), and
/// "option <option> must be in [min, max], got <text>" if it is a whole number outside
/// the range, however many digits it has.
template <std::integral I>
[[nodiscard]] I parse_integer(std::string_view option, std::string_view text, I min, I max);

namespace detail {
/// "[min, max]", the range an integer option accepts, as parse_integer's messages show it.
[[nodiscard]] std::string integer_range(std::intmax_t min, std::intmax_t max);
[[nodiscard]] std::string integer_range(std::uintmax_t min, std::uintmax_t max);
[[noreturn]] void throw_not_whole(std::string_view option, std::string_view text, const std::string& range);
[[noreturn]] void throw_out_of_range(std::string_view option, std::string_view text, const std::string& range);
} // namespace detail

template <std::integral I>
I parse_integer(std::string_view option, std::string_view text, I min, I max) {
    // Widened to the largest type of I's signedness, so one compiled function formats
    // every I's range.
    using widest = std::conditional_t<std::is_signed_v<I>, std::intmax_t, std::uintmax_t>;
    const std::string range = detail::integer_range(widest(min), widest(max));
    I value{};
    const char* const last = text.data() + text.size();
    const auto [end, ec] = std::from_chars(text.data(), last, value);
    // from_chars reports a whole number too large for I as result_out_of_range, with
    // `end` past its digits: out of range, not "not a number".
    if (ec == std::errc::result_out_of_range && end == last) detail::throw_out_of_range(option, text, range);
    if (ec != std::errc() || end != last) detail::throw_not_whole(option, text, range);
    if (value < min || value > max) detail::throw_out_of_range(option, text, range);
    return value;
}

/// Whether parse_real's lower limit is allowed ([min, max]) or not ((min, max]).
enum class lower_limit { inclusive, exclusive };

/// `text` as a finite double in [min, max] (or (min, max] with lower_limit::exclusive).
/// Throws usage_error "option <option> needs a number in <range>, got '<text>'" if it is not
/// a number, and "option <option> must be in <range>, got <text>" if it is a number outside
/// the range (infinity, or a value that overflows a double, included). NaN is not a number
/// here.
[[nodiscard]] double parse_real(std::string_view option, std::string_view text, double min, double max,
                                lower_limit kind = lower_limit::inclusive);

/// Walks the arguments argv[1..argc) once. In the loop body the current argument is
/// compared with each known switch (flag) or option taking a value (option); the value
/// is then read, checked, with integer, real, text or path. Anything that matches
/// nothing is either a positional argument (is_option() false) or unknown().
class command_line {
public:
    command_line(int argc, char** argv) noexcept : argc_(argc), argv_(argv) {}

    /// Moves to the next argument; false when there is none.
    bool next() noexcept;

    /// The current argument.
    [[nodiscard]] std::string_view current() const noexcept { return current_; }

    /// True when the current argument looks like an option ("-x", "--x"), not a positional
    /// argument or a lone "-".
    [[nodiscard]] bool is_option() const noexcept { return current_.size() > 1 && current_[0] == '-'; }

    /// True when the current argument is the switch `name` (an option without a value).
    [[nodiscard]] bool flag(std::string_view name) const noexcept { return current_ == name; }

    /// True when the current argument is the option `name`, whose value (the next
    /// argument) it then consumes. Throws usage_error "option <name> needs a value" when
    /// the arguments end there.
    bool option(std::string_view name);

    /// The value of the option just matched, as given (possibly empty).
    [[nodiscard]] std::string_view text() const noexcept { return value_; }
    /// The value as a non-empty string. Throws usage_error "option <name> needs a
    /// non-empty value" for "".
    [[nodiscard]] std::string non_empty_text() const;
    /// The value as an output path: non-empty (usage_error otherwise).
    [[nodiscard]] std::filesystem::path path() const { return non_empty_text(); }
    /// The value as an integer in [min, max] (parse_integer).
    template <std::integral I>
    [[nodiscard]] I integer(I min, I max) const {
        return parse_integer<I>(option_, value_, min, max);
    }
    /// The value as a finite number in [min, max] or (min, max] (parse_real).
    [[nodiscard]] double real(double min, double max, lower_limit kind = lower_limit::inclusive) const {
        return parse_real(option_, value_, min, max, kind);
    }

    /// Throws usage_error "unknown option '<current>'" (or "unexpected argument '<current>'"
    /// for a positional argument).
    [[noreturn]] void unknown() const;

private:
    int argc_;
    char** argv_;
    int index_ = 0;
    std::string_view current_;
    std::string_view option_;
    std::string_view value_;
};

/// Throws usage_error "<what> is <value>, more than the limit of <limit>" when
/// value > limit. For limits on products (pixels = width x height, samples = pixels x
/// spp) computed in 64 bits before anything of that size is allocated.
void check_limit(std::string_view what, std::uint64_t value, std::uint64_t limit);

/// The format of the output path given with `option`, from its extension: returns the
/// extension lower-cased with its dot (".png") when it is one of `supported` (lower-case,
/// with their dots). Otherwise throws usage_error "option <option>: cannot write '<path>':
/// unsupported format '<ext>' (supported: .png, .pfm, .exr)", or "...: no file extension
/// (supported: ...)": called before any work and before output_file creates anything, so
/// a refused path leaves no file.
[[nodiscard]] std::string output_format(std::string_view option, const std::filesystem::path& path,
                                        std::initializer_list<std::string_view> supported);

/// An output file written atomically. The constructor checks the target path before any
/// work is done (non-empty, not a directory, in an existing directory) and creates an
/// empty temporary file next to it, "<name>.partial-<pid>-<n>" in the same directory, so an
/// unwritable directory fails at once; all of these throw usage_error naming the path.
/// The program writes to temporary(); commit() renames it over the target, which is atomic
/// on POSIX file systems: the target is either the old file (or absent) or the complete
/// new one. An output_file destroyed without commit() (an exception, an early return)
/// removes its temporary file, and so does SIGINT, SIGTERM or SIGHUP arriving while it
/// exists (the handler removes every registered temporary file, then dies by the signal as
/// before). Only SIGKILL or a crash can leave a ".partial-" file behind, never a
/// half-written target.
class output_file {
public:
    explicit output_file(std::filesystem::path target);
    output_file(const output_file&) = delete;
    output_file& operator=(const output_file&) = delete;
    ~output_file();

    /// The path to write to.
    [[nodiscard]] const std::filesystem::path& temporary() const noexcept { return temporary_; }
    /// The path given.
    [[nodiscard]] const std::filesystem::path& target() const noexcept { return target_; }

    /// Renames temporary() to target(). Throws std::runtime_error "cannot write '<target>':
    /// <reason>" if that fails (the temporary file is then removed by the destructor).
    void commit();

    /// Opens temporary() for writing as a C stream, calls write(stream), closes it and
    /// commit()s: the whole of writing a generated file. Throws std::runtime_error
    /// "cannot write <temporary>" if the stream cannot be opened or closed (the stream is
    /// closed, and the temporary file removed, if write throws).
    template <class Write>
    void write_stream(Write&& write) {
        std::FILE* f = std::fopen(temporary_.c_str(), "w");
        if (!f) throw std::runtime_error("cannot write " + temporary_.string());
        try {
            write(f);
        } catch (...) {
            std::fclose(f);
            throw;
        }
        if (std::fclose(f) != 0) throw std::runtime_error("cannot write " + temporary_.string());
        commit();
    }

private:
    std::filesystem::path target_;
    std::filesystem::path temporary_;
    int slot_ = -1;
    bool committed_ = false;
};

} // namespace shade::examples
