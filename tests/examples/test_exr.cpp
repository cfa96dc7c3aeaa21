// tracer::save_exr / load_exr: a small image written and read back through OpenEXR keeps
// every value to the bit of its float rounding (32-bit float channels, not half), rows in
// order, and failures name the file.

#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>

#include <doctest/doctest.h>

#include "examples/errors.hpp"

#include "tracer/exr.hpp"

namespace {

using tracer::real;
using tracer::rgb;

using examples_test::error_of;

} // namespace

TEST_CASE("exr: a 5x3 image reads back exactly as 32-bit floats, rows in order") {
    tracer::radiance_image image;
    image.width = 5;
    image.height = 3;
    // Values no half-float can hold: 1 + 2^-20 (half has 10 mantissa bits, so it rounds to
    // 1), 1e5 (above half's largest finite 65504), 1e-30 (below its smallest subnormal
    // 2^-24, so 0); plus 0.1 and pi, which need float's rounding, and a distinct value per
    // pixel and channel so a swapped row, column or channel shows.
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const real i = real(y * image.width + x);
            image.pixels.push_back(rgb(1 + std::ldexp(1.0, -20) + i, 0.1 * (i + 1), 3.141592653589793 * i + 1e-30));
        }
    image.pixels[7] = rgb(1e5, 1e-30, 0);
    const std::string path = "exr_test_roundtrip.exr";
    tracer::save_exr(path, image);
    const auto back = tracer::load_exr(path);
    REQUIRE(back.width == 5);
    REQUIRE(back.height == 3);
    int mismatches = 0;
    for (std::size_t i = 0; i < image.pixels.size(); ++i)
        for (int k = 0; k < 3; ++k)
            mismatches += back.pixels[i][k] != real(static_cast<float>(image.pixels[i][k]));
    CHECK(mismatches == 0);
    // Not what a half channel would give back.
    CHECK(back.pixels[0].x == real(1 + std::ldexp(1.0f, -20)));
    CHECK(back.pixels[7].x == real(1e5f));
    CHECK(back.pixels[7].y == real(1e-30f));
    std::remove(path.c_str());
}

TEST_CASE("exr: failures name the file") {
    const tracer::radiance_image one{1, 1, {rgb(1)}};
    const std::string write_error = error_of([&] { tracer::save_exr("no_such_directory/out.exr", one); });
    CHECK(write_error.rfind("cannot write EXR 'no_such_directory/out.exr': ", 0) == 0);

    const std::string missing = error_of([] { (void)tracer::load_exr("no_such_image.exr"); });
    CHECK(missing.rfind("cannot read EXR 'no_such_image.exr': ", 0) == 0);

    const std::string text_path = "exr_test_not_exr.exr";
    std::ofstream(text_path) << "not an OpenEXR file\n";
    const std::string not_exr = error_of([&] { (void)tracer::load_exr(text_path); });
    CHECK(not_exr.rfind("cannot read EXR 'exr_test_not_exr.exr': ", 0) == 0);
    std::remove(text_path.c_str());
}
