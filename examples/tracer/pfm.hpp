#pragma once
// Writing a radiance image as a Portable Float Map (.pfm): linear RGB, 32-bit floats,
// no tone mapping, so the numbers a render produced can be read back exactly (to float).

#include <cstdint>
#include <cstring>
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

} // namespace tracer
