// Tests of the example programs' plotting canvas (examples/support/canvas.hpp).

#include <string>

#include <doctest/doctest.h>

#include "support/canvas.hpp"

namespace {

bool inked(const shade::examples::canvas& c, int x, int y) { return c.at(x, y).x < 0.5f; }

} // namespace

TEST_CASE("canvas::text draws every segment of a glyph, also the last ones of a short string") {
    // stb_easy_font's "0" is six quads (384 bytes of vertices): top and bottom bars, the
    // left bar x in [0, 1), a two-quad slash, and last the right bar x in [3, 4), y in
    // [1, 6). A buffer sized by the average bytes per character (~270) cut off the right
    // bar. At scale 2 from (10, 10) the right bar covers x in [16, 18), y in [12, 22).
    shade::examples::canvas c(40, 30, {1, 1, 1});
    c.text(10, 10, "0", {0, 0, 0}, 2.0f);
    CHECK(inked(c, 10, 15)); // left bar
    CHECK(inked(c, 17, 15)); // right bar (the last quad)
    CHECK_FALSE(inked(c, 5, 15));
    // A long string: its last glyph is complete too.
    shade::examples::canvas wide(700, 20, {1, 1, 1});
    const std::string s(100, '0');
    wide.text(0, 0, s, {0, 0, 0}, 1.0f);
    // stb_easy_font advances 5 pixels per "0" (4 wide + 1 space): the last one starts at 495.
    CHECK(inked(wide, 495 + 3, 3));
}

TEST_CASE("canvas rejects non-positive sizes") {
    CHECK_THROWS_AS(shade::examples::canvas(0, 5, {0, 0, 0}), std::invalid_argument);
    CHECK_THROWS_AS(shade::examples::canvas(5, -1, {0, 0, 0}), std::invalid_argument);
}
