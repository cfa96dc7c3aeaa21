// tracer::save_pfm / load_pfm: what the tracer writes reads back to the bit of its float
// rounding; files in the other byte order, grey files and scaled files read as the PFM
// description defines them; malformed files fail naming the file.

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include "examples/errors.hpp"

#include "tracer/pfm.hpp"

namespace {

using tracer::real;
using tracer::rgb;
namespace fs = std::filesystem;

using examples_test::error_of;

fs::path scratch(const std::string& name) { return fs::temp_directory_path() / ("shade_test_pfm_" + name); }

void write_bytes(const fs::path& path, const std::string& header, const std::vector<float>& values, bool big_endian) {
    std::ofstream out(path, std::ios::binary);
    out << header;
    for (const float v : values) {
        std::uint32_t bits;
        std::memcpy(&bits, &v, sizeof bits);
        for (int b = 0; b < 4; ++b) {
            const int shift = big_endian ? 8 * (3 - b) : 8 * b;
            out.put(static_cast<char>((bits >> shift) & 0xff));
        }
    }
}

} // namespace

TEST_CASE("pfm: a 4x3 image reads back exactly as 32-bit floats, rows in order") {
    tracer::radiance_image image;
    image.width = 4;
    image.height = 3;
    for (int i = 0; i < 12; ++i) image.pixels.push_back(rgb(0.1 * i, 1e5 + i, 3.141592653589793 * i + 1e-30));
    const fs::path path = scratch("roundtrip.pfm");
    tracer::save_pfm(path, image);
    const auto back = tracer::load_pfm(path);
    REQUIRE(back.width == 4);
    REQUIRE(back.height == 3);
    for (std::size_t i = 0; i < image.pixels.size(); ++i)
        for (int k = 0; k < 3; ++k) CHECK(back.pixels[i][k] == real(static_cast<float>(image.pixels[i][k])));
    fs::remove(path);
}

TEST_CASE("pfm: big-endian (positive scale), grey and scaled files") {
    // 2x2 colour, big-endian, scale +1: bottom row stored first, so the file's first pixel
    // is the image's bottom-left (x 0, y 1).
    const fs::path big = scratch("big.pfm");
    write_bytes(big, "PF\n2 2\n1.0\n", {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12}, true);
    const auto b = tracer::load_pfm(big);
    CHECK(b.at(0, 1) == rgb(1, 2, 3));
    CHECK(b.at(1, 1) == rgb(4, 5, 6));
    CHECK(b.at(0, 0) == rgb(7, 8, 9));
    CHECK(b.at(1, 0) == rgb(10, 11, 12));
    // Grey ("Pf"), little-endian with scale -0.5: each value times |scale|, replicated.
    const fs::path grey = scratch("grey.pfm");
    write_bytes(grey, "Pf\n3 1\n-0.5\n", {2, 4, 8}, false);
    const auto g = tracer::load_pfm(grey);
    CHECK(g.width == 3);
    CHECK(g.at(0, 0) == rgb(1));
    CHECK(g.at(2, 0) == rgb(4));
    fs::remove(big);
    fs::remove(grey);
}

TEST_CASE("pfm: malformed files fail naming the file and the reason") {
    const fs::path path = scratch("bad.pfm");
    const std::string prefix = "cannot read PFM '" + path.string() + "': ";
    write_bytes(path, "P6\n2 2\n255\n", {}, false);
    CHECK(error_of([&] { (void)tracer::load_pfm(path); }) == prefix + "not a PFM file (no \"PF\" or \"Pf\" header)");
    write_bytes(path, "PF\n2 0\n-1.0\n", {}, false);
    CHECK(error_of([&] { (void)tracer::load_pfm(path); }) == prefix + "bad size 2x0 (at most 2^28 pixels)");
    write_bytes(path, "PF\n2 x\n-1.0\n", {}, false);
    CHECK(error_of([&] { (void)tracer::load_pfm(path); }) == prefix + "bad height 'x' in the header");
    write_bytes(path, "PF\n2 2\n0\n", {}, false);
    CHECK(error_of([&] { (void)tracer::load_pfm(path); }) == prefix + "bad scale '0' in the header");
    write_bytes(path, "PF\n2 2\n-1.0\n", {1, 2, 3}, false);
    CHECK(error_of([&] { (void)tracer::load_pfm(path); }) == prefix + "the file ends before its 2x2 pixels");
    fs::remove(path);
    CHECK(error_of([&] { (void)tracer::load_pfm(path); }) == prefix + "cannot open the file");
}
