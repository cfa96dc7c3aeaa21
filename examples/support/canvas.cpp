#include "support/canvas.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <stb/stb_easy_font.h>

#include <glm/geometric.hpp>

#include <shade/color/srgb.hpp>

namespace shade::examples {

canvas::canvas(int width, int height, rgb<float> background) : width_(width), height_(height) {
    if (width <= 0 || height <= 0)
        throw std::invalid_argument("canvas size must be positive, got " + std::to_string(width) +
                                    "x" + std::to_string(height));
    pixels_.assign(std::size_t(width) * std::size_t(height), background);
}

void canvas::blend(int x, int y, rgb<float> colour, float alpha) {
    if (x < 0 || y < 0 || x >= width_ || y >= height_ || !(alpha > 0)) return;
    auto& p = pixels_[std::size_t(y) * std::size_t(width_) + std::size_t(x)];
    const float a = std::min(alpha, 1.0f);
    p = p * (1.0f - a) + colour * a;
}

void canvas::line(float x0, float y0, float x1, float y1, rgb<float> colour, float width) {
    const vec2<float> a(x0, y0);
    const vec2<float> b(x1, y1);
    const vec2<float> ab = b - a;
    const float len2 = glm::dot(ab, ab);
    const float half = width * 0.5f;
    const int xmin = int(std::floor(std::min(x0, x1) - half - 1));
    const int xmax = int(std::ceil(std::max(x0, x1) + half + 1));
    const int ymin = int(std::floor(std::min(y0, y1) - half - 1));
    const int ymax = int(std::ceil(std::max(y0, y1) + half + 1));
    for (int y = std::max(ymin, 0); y <= std::min(ymax, height_ - 1); ++y) {
        for (int x = std::max(xmin, 0); x <= std::min(xmax, width_ - 1); ++x) {
            const vec2<float> p(float(x) + 0.5f, float(y) + 0.5f);
            // Distance from the pixel centre to the segment (a point when len2 == 0).
            const float t = len2 > 0 ? std::clamp(glm::dot(p - a, ab) / len2, 0.0f, 1.0f) : 0.0f;
            const float d = glm::length(p - (a + t * ab));
            blend(x, y, colour, half + 0.5f - d);
        }
    }
}

void canvas::polyline(const std::vector<vec2<float>>& points, rgb<float> colour, float width) {
    for (std::size_t i = 1; i < points.size(); ++i)
        line(points[i - 1].x, points[i - 1].y, points[i].x, points[i].y, colour, width);
}

void canvas::fill_rect(float x0, float y0, float x1, float y1, rgb<float> colour) {
    for (int y = std::max(int(std::floor(y0)), 0); y < std::min(int(std::ceil(y1)), height_); ++y)
        for (int x = std::max(int(std::floor(x0)), 0); x < std::min(int(std::ceil(x1)), width_); ++x)
            blend(x, y, colour, 1.0f);
}

void canvas::text(float x, float y, std::string_view s, rgb<float> colour, float scale) {
    std::string copy(s);
    // stb_easy_font emits one quad (4 vertices of 16 bytes) per glyph segment and silently
    // stops when the buffer is full; ~270 bytes per character is only its average (a "0"
    // has 6 quads, 384 bytes). So grow the buffer until the last call left room for
    // another quad, i.e. nothing was cut off.
    constexpr std::size_t quad_bytes = 64;
    std::vector<char> buffer(copy.size() * 300 + quad_bytes);
    unsigned char rgba[4] = {255, 255, 255, 255};
    int quads = 0;
    for (;;) {
        quads = stb_easy_font_print(0, 0, copy.data(), rgba, buffer.data(), int(buffer.size()));
        if (std::size_t(quads + 1) * quad_bytes <= buffer.size()) break;
        buffer.resize(2 * buffer.size());
    }
    const auto* v = reinterpret_cast<const float*>(buffer.data());
    for (int q = 0; q < quads; ++q) {
        // Each vertex: x, y, z (floats) and 4 colour bytes = 4 floats' worth.
        const float qx0 = v[q * 16 + 0];
        const float qy0 = v[q * 16 + 1];
        const float qx1 = v[q * 16 + 8];
        const float qy1 = v[q * 16 + 9];
        fill_rect(x + qx0 * scale, y + qy0 * scale, x + qx1 * scale, y + qy1 * scale, colour);
    }
}

rgb<float> canvas::at(int x, int y) const {
    return pixels_[std::size_t(y) * std::size_t(width_) + std::size_t(x)];
}

image canvas::to_image() const {
    image out = image::filled(width_, height_);
    for (int y = 0; y < height_; ++y)
        for (int x = 0; x < width_; ++x) out.set(x, y, encode_srgb8(at(x, y)));
    return out;
}

} // namespace shade::examples
