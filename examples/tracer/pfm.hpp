#pragma once
// Radiance images as Portable Float Maps (.pfm): linear RGB, 32-bit floats, no tone
// mapping, so the numbers a render produced can be read back exactly (to float). The format
// (Paul Debevec's HDR Shop PFM description): a text header "PF" (colour) or "Pf" (grey),
// width and height, and a scale whose sign gives the byte order (negative: little-endian);
// then width x height pixels of float32, rows from the BOTTOM of the image up.

#include <cmath>
#include <cstdint>
#include <cstring>
#include <iterator>
#include <limits>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "render.hpp"

namespace tracer {

/// Writes `image` to `path` as a colour PFM: the header "PF\n<width> <height>\n-1.0\n"
/// (a negative scale means little-endian data), then width x height x 3 float32 values,
/// rows from the BOTTOM of the image up, as the format defines (Paul Debevec's HDR
/// Shop PFM description). Throws std::runtime_error when the file cannot be written.
inline void save_pfm(const std::filesystem::path& path, const radiance_image& image) {
    std::ofstream out(path, std::ios::binary);
    if (!out) throw std::runtime_error("cannot open '" + path.string() + "' for writing");
    const std::string header = "PF\n" + std::to_string(image.width) + " " + std::to_string(image.height) + "\n-1.0\n";
    out.write(header.data(), std::streamsize(header.size()));
    std::vector<unsigned char> row(std::size_t(image.width) * 3 * sizeof(float));
    for (int y = image.height - 1; y >= 0; --y) {
        for (int x = 0; x < image.width; ++x) {
            const rgb& c = image.at(x, y);
            for (int k = 0; k < 3; ++k) {
                const float value = static_cast<float>(c[k]);
                std::uint32_t bits;
                std::memcpy(&bits, &value, sizeof bits);
                unsigned char* dst = &row[(std::size_t(x) * 3 + std::size_t(k)) * 4];
                for (int b = 0; b < 4; ++b) dst[b] = static_cast<unsigned char>(bits >> (8 * b));
            }
        }
        out.write(reinterpret_cast<const char*>(row.data()), std::streamsize(row.size()));
    }
    if (!out.flush()) throw std::runtime_error("cannot write '" + path.string() + "'");
}

/// Reads a PFM file, colour ("PF") or grey ("Pf", replicated to R = G = B), in either byte
/// order, into a radiance image (rows from the top), each value multiplied by the
/// magnitude of the header's scale. Throws std::runtime_error
/// "cannot read PFM '<path>': <reason>" when the file is missing, its header is not a PFM
/// header, its size is not positive or above 2^28 pixels, its scale is 0 or not a number,
/// or the file holds fewer bytes than the pixels need.
inline radiance_image load_pfm(const std::filesystem::path& path) {
    const auto fail = [&](const std::string& reason) -> void {
        throw std::runtime_error("cannot read PFM '" + path.string() + "': " + reason);
    };
    std::ifstream in(path, std::ios::binary);
    if (!in) fail("cannot open the file");
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::size_t pos = 0;
    const auto is_space = [](char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; };
    // The next whitespace-separated header token.
    const auto token = [&]() -> std::string {
        while (pos < bytes.size() && is_space(bytes[pos])) ++pos;
        const std::size_t begin = pos;
        while (pos < bytes.size() && !is_space(bytes[pos]) && pos - begin < 64) ++pos;
        return bytes.substr(begin, pos - begin);
    };
    const std::string magic = token();
    if (magic != "PF" && magic != "Pf") fail("not a PFM file (no \"PF\" or \"Pf\" header)");
    const int channels = magic == "PF" ? 3 : 1;
    const auto whole = [&](const std::string& text, const char* what) -> long long {
        std::size_t used = 0;
        long long value = 0;
        try {
            value = std::stoll(text, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (used == 0 || used != text.size()) fail(std::string("bad ") + what + " '" + text + "' in the header");
        return value;
    };
    const long long width = whole(token(), "width");
    const long long height = whole(token(), "height");
    if (width <= 0 || height <= 0 || width * height > (1ll << 28))
        fail("bad size " + std::to_string(width) + "x" + std::to_string(height) + " (at most 2^28 pixels)");
    const std::string scale_text = token();
    double scale = 0;
    try {
        std::size_t used = 0;
        scale = std::stod(scale_text, &used);
        if (used != scale_text.size()) scale = 0;
    } catch (const std::exception&) {
        scale = 0;
    }
    if (!(scale != 0) || !std::isfinite(scale)) fail("bad scale '" + scale_text + "' in the header");
    ++pos; // the single whitespace character that ends the header
    const bool little_endian = scale < 0;
    const real magnitude = std::abs(scale); // the scale's magnitude multiplies every value
    const std::size_t count = std::size_t(width) * std::size_t(height) * std::size_t(channels);
    if (pos > bytes.size() || bytes.size() - pos < count * 4)
        fail("the file ends before its " + std::to_string(width) + "x" + std::to_string(height) + " pixels");
    radiance_image image;
    image.width = int(width);
    image.height = int(height);
    image.pixels.assign(std::size_t(width) * std::size_t(height), rgb(0));
    const auto value = [&](std::size_t index) {
        const auto* b = reinterpret_cast<const unsigned char*>(bytes.data() + pos + 4 * index);
        std::uint32_t bits = 0;
        for (int k = 0; k < 4; ++k)
            bits |= std::uint32_t(b[little_endian ? k : 3 - k]) << (8 * k);
        float f;
        std::memcpy(&f, &bits, sizeof f);
        return real(f) * magnitude;
    };
    for (int y = 0; y < image.height; ++y) {
        const std::size_t row = std::size_t(image.height - 1 - y) * std::size_t(width); // stored bottom-up
        for (int x = 0; x < image.width; ++x) {
            const std::size_t first = (row + std::size_t(x)) * std::size_t(channels);
            rgb& c = image.pixels[std::size_t(y) * std::size_t(width) + std::size_t(x)];
            c = channels == 3 ? rgb(value(first), value(first + 1), value(first + 2)) : rgb(value(first));
        }
    }
    return image;
}

} // namespace tracer
