// Tests of the example programs' command-line and output-file helper
// (examples/support/cli.hpp).

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include "support/cli.hpp"

namespace ex = shade::examples;
namespace fs = std::filesystem;

namespace {

std::string message_of(auto&& call) {
    try {
        call();
    } catch (const ex::usage_error& e) {
        return e.what();
    }
    return "(no usage_error)";
}

std::string contents(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// A fresh empty directory under the system's temporary directory.
fs::path scratch_directory(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / ("shade_test_cli_" + name);
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

std::vector<fs::path> files_in(const fs::path& dir) {
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(dir)) files.push_back(entry.path().filename());
    return files;
}

} // namespace

TEST_CASE("parse_integer: a value inside the range, its ends included") {
    CHECK(ex::parse_integer("--n", "1", 1, 10) == 1);
    CHECK(ex::parse_integer("--n", "10", 1, 10) == 10);
    CHECK(ex::parse_integer("--n", "-3", -5, 10) == -3);
    CHECK(ex::parse_integer<std::uint64_t>("--seed", "18446744073709551615", 0, UINT64_MAX) == UINT64_MAX);
}

TEST_CASE("parse_integer: a whole number outside the range names the range, however long it is") {
    CHECK(message_of([] { (void)ex::parse_integer("--width", "0", 1, 16384); }) ==
          "option --width must be in [1, 16384], got 0");
    CHECK(message_of([] { (void)ex::parse_integer("--width", "16385", 1, 16384); }) ==
          "option --width must be in [1, 16384], got 16385");
    // Too large for int: from_chars says result_out_of_range, which is a range error too.
    CHECK(message_of([] { (void)ex::parse_integer("--width", "99999999999", 1, 16384); }) ==
          "option --width must be in [1, 16384], got 99999999999");
    CHECK(message_of([] { (void)ex::parse_integer("--width", "-99999999999", 1, 16384); }) ==
          "option --width must be in [1, 16384], got -99999999999");
}

TEST_CASE("parse_integer: text that is no whole number says so") {
    for (const char* text : {"", "wide", "12x", "1.5", " 3", "0x10"})
        CHECK(message_of([&] { (void)ex::parse_integer("--spp", text, 1, 9); }) ==
              "option --spp needs a whole number in [1, 9], got '" + std::string(text) + "'");
    // An unsigned option given a negative number.
    CHECK(message_of([] { (void)ex::parse_integer<std::uint64_t>("--seed", "-1", 0, 5); }) ==
          "option --seed needs a whole number in [0, 5], got '-1'");
}

TEST_CASE("parse_real: range ends, exclusive lower limit, infinity, overflow and NaN") {
    CHECK(ex::parse_real("--x", "0.5", 0, 1) == 0.5);
    CHECK(ex::parse_real("--x", "0", 0, 1) == 0);
    CHECK(ex::parse_real("--x", "1", 0, 1, ex::lower_limit::exclusive) == 1);
    CHECK(message_of([] { (void)ex::parse_real("--exposure", "0", 0, 1e6, ex::lower_limit::exclusive); }) ==
          "option --exposure must be in (0, 1e+06], got 0");
    CHECK(message_of([] { (void)ex::parse_real("--x", "1.5", 0, 1); }) == "option --x must be in [0, 1], got 1.5");
    CHECK(message_of([] { (void)ex::parse_real("--x", "inf", 0, 1); }) == "option --x must be in [0, 1], got inf");
    CHECK(message_of([] { (void)ex::parse_real("--x", "1e400", 0, 1); }) == "option --x must be in [0, 1], got 1e400");
    CHECK(message_of([] { (void)ex::parse_real("--x", "nan", 0, 1); }) == "option --x needs a number in [0, 1], got 'nan'");
    CHECK(message_of([] { (void)ex::parse_real("--x", "1,5", 0, 1); }) == "option --x needs a number in [0, 1], got '1,5'");
}

TEST_CASE("command_line: switches, options with values, unknown options and missing values") {
    std::vector<std::string> words = {"prog", "--quiet", "--n", "7", "--out", "a.png"};
    std::vector<char*> argv;
    for (auto& w : words) argv.push_back(w.data());
    ex::command_line args(int(argv.size()), argv.data());
    bool quiet = false;
    int n = 0;
    fs::path out;
    while (args.next()) {
        if (args.flag("--quiet")) quiet = true;
        else if (args.option("--n")) n = args.integer(1, 9);
        else if (args.option("--out")) out = args.path();
        else args.unknown();
    }
    CHECK(quiet);
    CHECK(n == 7);
    CHECK(out == "a.png");

    // An unknown option last on the line is unknown, not "needs a value": the value is
    // taken only once the option is known.
    const auto parse_all = [](std::vector<std::string> w) {
        std::vector<char*> v;
        for (auto& s : w) v.push_back(s.data());
        ex::command_line a(int(v.size()), v.data());
        while (a.next()) {
            if (a.option("--out")) (void)a.path();
            else a.unknown();
        }
    };
    CHECK(message_of([&] { parse_all({"prog", "--bogus"}); }) == "unknown option '--bogus'");
    CHECK(message_of([&] { parse_all({"prog", "stray"}); }) == "unexpected argument 'stray'");
    CHECK(message_of([&] { parse_all({"prog", "--out"}); }) == "option --out needs a value");
    CHECK(message_of([&] { parse_all({"prog", "--out", ""}); }) == "option --out needs a non-empty value");
}

TEST_CASE("check_limit: a product above its limit names both") {
    CHECK_NOTHROW(ex::check_limit("pixels", 100, 100));
    CHECK(message_of([] { ex::check_limit("pixels", 101, 100); }) == "pixels is 101, more than the limit of 100");
}

TEST_CASE("output_file: the target appears only at commit, complete") {
    const fs::path dir = scratch_directory("commit");
    const fs::path target = dir / "out.txt";
    {
        ex::output_file out(target);
        // The temporary file exists from construction on, under another name.
        CHECK(fs::exists(out.temporary()));
        CHECK(out.temporary() != target);
        CHECK(out.temporary().parent_path() == dir);
        CHECK(out.temporary().filename().string().starts_with("out.txt.partial-"));
        CHECK_FALSE(fs::exists(target));
        std::ofstream(out.temporary()) << "complete";
        CHECK_FALSE(fs::exists(target));
        out.commit();
    }
    CHECK(contents(target) == "complete");
    CHECK(files_in(dir) == std::vector<fs::path>{"out.txt"});
    fs::remove_all(dir);
}

TEST_CASE("output_file: without commit, an existing target keeps its bytes and no temporary file stays") {
    const fs::path dir = scratch_directory("abandon");
    const fs::path target = dir / "out.txt";
    std::ofstream(target) << "old";
    try {
        ex::output_file out(target);
        std::ofstream(out.temporary()) << "half";
        throw std::runtime_error("failed while working");
    } catch (const std::runtime_error&) {
    }
    CHECK(contents(target) == "old");
    CHECK(files_in(dir) == std::vector<fs::path>{"out.txt"});
    fs::remove_all(dir);
}

TEST_CASE("output_file: bad paths fail at construction, naming the path") {
    const fs::path dir = scratch_directory("bad");
    CHECK(message_of([] { ex::output_file out(""); }) == "the output path is empty");
    CHECK(message_of([&] { ex::output_file out(dir / "missing" / "x.png"); }) ==
          "cannot write '" + (dir / "missing" / "x.png").string() + "': directory '" + (dir / "missing").string() +
              "' does not exist");
    CHECK(message_of([&] { ex::output_file out(dir); }) == "output path '" + dir.string() + "' is a directory");
    std::ofstream(dir / "file") << "x";
    CHECK(message_of([&] { ex::output_file out(dir / "file" / "x.png"); }) ==
          "cannot write '" + (dir / "file" / "x.png").string() + "': '" + (dir / "file").string() +
              "' is not a directory");
    CHECK(files_in(dir) == std::vector<fs::path>{"file"});
    fs::remove_all(dir);
}

TEST_CASE("output_format: the extension chooses the format; others are refused naming the supported ones") {
    CHECK(ex::output_format("--out", "render.png", {".png", ".pfm", ".exr"}) == ".png");
    CHECK(ex::output_format("--out", "dir.v2/render.EXR", {".png", ".pfm", ".exr"}) == ".exr");
    CHECK(ex::output_format("--out", "a.pfm", {".png", ".pfm", ".exr"}) == ".pfm");
    CHECK(message_of([] { (void)ex::output_format("--out", "x.jpg", {".png", ".pfm", ".exr"}); }) ==
          "option --out: cannot write 'x.jpg': unsupported format '.jpg' (supported: .png, .pfm, .exr)");
    CHECK(message_of([] { (void)ex::output_format("--out", "wf.txt", {".png"}); }) ==
          "option --out: cannot write 'wf.txt': unsupported format '.txt' (supported: .png)");
    // A dot in a directory name is no extension.
    CHECK(message_of([] { (void)ex::output_format("--out", "out.d/plot", {".png"}); }) ==
          "option --out: cannot write 'out.d/plot': no file extension (supported: .png)");
}

TEST_CASE("parse_integer: range messages for the widest types") {
    CHECK(message_of([] { (void)ex::parse_integer<std::int64_t>("--n", "x", INT64_MIN, INT64_MAX); }) ==
          "option --n needs a whole number in [-9223372036854775808, 9223372036854775807], got 'x'");
    CHECK(message_of([] { (void)ex::parse_integer<std::uint64_t>("--n", "-1", 0, UINT64_MAX); }) ==
          "option --n needs a whole number in [0, 18446744073709551615], got '-1'");
    CHECK(message_of([] { (void)ex::parse_integer<unsigned char>("--n", "300", 1, 200); }) ==
          "option --n must be in [1, 200], got 300");
}
