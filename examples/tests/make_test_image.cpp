// make_test_image: writes the small PNG and PFM images the compare tool's tests use, so no
// binary test images are committed.
//
//   make_test_image OUT.png WIDTH HEIGHT base|altered|black
//   make_test_image OUT.pfm WIDTH HEIGHT hdr1|hdr2
//
// base:    a gradient (R rises left to right, G top to bottom, B = 128), with an 8x8 white
//          patch (255,255,255) at column 0, row 0 and an 8x8 black patch at column 8, row 0.
// altered: base with the red channel inverted (255 - R) in the bottom-right quarter, a
//          large, visible change there and none elsewhere.
// black:   every pixel (0, 0, 0) (what a Delta E heat map of identical images must be).
// hdr1, hdr2: every pixel linear (1, 1, 1) or (2, 2, 2), as a PFM (linear radiance).

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <string_view>

#include "support/image.hpp"
#include "tracer/pfm.hpp"

int main(int argc, char** argv) {
    try {
        if (argc != 5) {
            std::fputs("usage: make_test_image OUT.png WIDTH HEIGHT base|altered|black\n"
                       "       make_test_image OUT.pfm WIDTH HEIGHT hdr1|hdr2\n",
                       stderr);
            return 2;
        }
        const int width = std::stoi(argv[2]);
        const int height = std::stoi(argv[3]);
        const std::string_view pattern = argv[4];
        if (pattern == "hdr1" || pattern == "hdr2") {
            tracer::radiance_image hdr;
            hdr.width = width;
            hdr.height = height;
            hdr.pixels.assign(std::size_t(width) * std::size_t(height), tracer::rgb(pattern == "hdr1" ? 1 : 2));
            tracer::save_pfm(argv[1], hdr);
            return 0;
        }
        if (pattern != "base" && pattern != "altered" && pattern != "black") {
            std::fprintf(stderr, "make_test_image: unknown pattern '%s'\n", argv[4]);
            return 2;
        }
        auto img = shade::examples::image::filled(width, height);
        if (pattern != "black") {
            for (int y = 0; y < height; ++y)
                for (int x = 0; x < width; ++x) {
                    const auto r = static_cast<std::uint8_t>(width > 1 ? x * 255 / (width - 1) : 0);
                    const auto g = static_cast<std::uint8_t>(height > 1 ? y * 255 / (height - 1) : 0);
                    shade::srgb8 p{r, g, 128};
                    if (y < 8 && x < 8) p = {255, 255, 255};
                    else if (y < 8 && x < 16) p = {0, 0, 0};
                    if (pattern == "altered" && 2 * x >= width && 2 * y >= height)
                        p.r = static_cast<std::uint8_t>(255 - p.r);
                    img.set(x, y, p);
                }
        }
        shade::examples::save_png(argv[1], img);
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "make_test_image: error: %s\n", e.what());
        return 2;
    }
}
