#pragma once
// 8-bit RGB images and PNG input/output for the example programs (through Debian's stb
// headers, compiled once in stb_implementation.cpp).
//
// An image is width x height pixels, row-major from the top row, three bytes per pixel in
// the order R, G, B, holding encoded sRGB code values (what a PNG stores). Errors (a file
// that cannot be opened or decoded or written, a pixel buffer of the wrong size) throw
// std::runtime_error whose message names the file and the reason.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <vector>

#include <shade/color/srgb.hpp>

namespace shade::examples {

/// An 8-bit sRGB image: pixels.size() == 3 * width * height, row-major, top row first,
/// R, G, B bytes per pixel.
struct image {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> pixels;

    /// An image of the given size filled with `fill`. Throws std::invalid_argument unless
    /// width and height are > 0.
    static image filled(int width, int height, srgb8 fill = {0, 0, 0});

    /// The pixel at column x, row y (0, 0 = top left). Precondition: inside the image.
    [[nodiscard]] srgb8 at(int x, int y) const noexcept {
        const std::size_t i = offset(x, y);
        return {pixels[i], pixels[i + 1], pixels[i + 2]};
    }

    /// Sets the pixel at column x, row y. Precondition: inside the image.
    void set(int x, int y, srgb8 p) noexcept {
        const std::size_t i = offset(x, y);
        pixels[i] = p.r;
        pixels[i + 1] = p.g;
        pixels[i + 2] = p.b;
    }

private:
    [[nodiscard]] std::size_t offset(int x, int y) const noexcept {
        return 3 * (std::size_t(y) * std::size_t(width) + std::size_t(x));
    }
};

/// Reads an image file (PNG, or any other format stb_image reads: JPEG, BMP, TGA, ...)
/// as 8-bit RGB: grey is replicated to R = G = B, alpha is dropped, 16-bit channels are
/// reduced to 8 bits. Throws std::runtime_error "cannot read image '<path>': <reason>" if
/// the file cannot be opened or decoded.
[[nodiscard]] image load_image(const std::filesystem::path& path);

/// Writes `img` as an 8-bit RGB PNG. Throws std::runtime_error
/// "cannot write image '<path>': <reason>" if the image is malformed (non-positive size,
/// pixel buffer of the wrong length) or the file cannot be written.
void save_png(const std::filesystem::path& path, const image& img);

} // namespace shade::examples
