#pragma once
// A small raster canvas for the example programs' plots (BRDF lobes, white-furnace
// curves): anti-aliased lines, filled rectangles and ASCII text (stb_easy_font), drawn
// into a linear-RGB buffer and encoded to an sRGB image at the end.

#include <string_view>
#include <vector>

#include <shade/core/types.hpp>

#include "support/image.hpp"

namespace shade::examples {

/// A width x height canvas of linear RGB, (0, 0) the top-left corner, y down.
class canvas {
public:
    /// A canvas filled with `background`. Throws std::invalid_argument for sizes <= 0.
    canvas(int width, int height, rgb<float> background);

    [[nodiscard]] int width() const noexcept { return width_; }
    [[nodiscard]] int height() const noexcept { return height_; }

    /// A line from (x0, y0) to (x1, y1) of the given width in pixels, anti-aliased by the
    /// pixel's distance to the segment (coverage falls off linearly over one pixel).
    void line(float x0, float y0, float x1, float y1, rgb<float> colour, float width = 1.5f);

    /// A polyline through consecutive points.
    void polyline(const std::vector<vec2<float>>& points, rgb<float> colour, float width = 1.5f);

    /// An axis-aligned filled rectangle [x0, x1) x [y0, y1).
    void fill_rect(float x0, float y0, float x1, float y1, rgb<float> colour);

    /// ASCII text with its top-left corner at (x, y), `scale` times stb_easy_font's
    /// 6-pixel-high glyphs.
    void text(float x, float y, std::string_view s, rgb<float> colour, float scale = 2.0f);

    /// The pixel colour (linear RGB) at column x, row y.
    [[nodiscard]] rgb<float> at(int x, int y) const;

    /// The canvas as an 8-bit sRGB image (linear values clamped to [0, 1]).
    [[nodiscard]] image to_image() const;

private:
    void blend(int x, int y, rgb<float> colour, float alpha);

    int width_;
    int height_;
    std::vector<rgb<float>> pixels_;
};

} // namespace shade::examples
