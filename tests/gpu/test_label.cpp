// The captions of the pictures (cga/gpu/label.hpp): glyphs land where the font says, lower case is drawn as
// upper case, characters without a glyph as '?', with_caption() keeps the picture below its band, and bad
// buffers are refused. No GL context needed.
#include <catch2/catch.hpp>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "cga/gpu/label.hpp"

using namespace cga::gpu;

namespace {

constexpr std::array<std::uint8_t, 3> kInk{20, 20, 20}, kPaper{255, 255, 255};

std::vector<std::uint8_t> drawn(const std::string& text, int w = 40, int h = 12) {
  std::vector<std::uint8_t> px(static_cast<std::size_t>(w) * h * 3, 128);
  draw_label(px, w, h, 3, 0, 0, text, 1, kInk, kPaper);
  return px;
}

bool ink_at(const std::vector<std::uint8_t>& px, int w, int x, int y) {
  const std::size_t at = (static_cast<std::size_t>(y) * w + x) * 3;
  return px[at] == kInk[0] && px[at + 1] == kInk[1] && px[at + 2] == kInk[2];
}

}  // namespace

TEST_CASE("a label's glyphs follow the font, on a band of background") {
  const std::vector<std::uint8_t> px = drawn("A");
  // The text starts half a cell in (3 pixels) and one row down; 'A' is .###. / #...# / ... / #...#.
  CHECK_FALSE(ink_at(px, 40, 3, 1));
  CHECK(ink_at(px, 40, 4, 1));
  CHECK(ink_at(px, 40, 3, 2));
  CHECK(ink_at(px, 40, 7, 7));
  CHECK_FALSE(ink_at(px, 40, 5, 5));  // inside the A, below the bar
  // The band: one cell (6 + 6 pixels for one glyph plus the margins) by 9 rows of background; 128 beyond it.
  CHECK(px[(0 * 40 + 0) * 3] == 255);
  CHECK(px[(8 * 40 + 11) * 3] == 255);
  CHECK(px[(0 * 40 + 12) * 3] == 128);
  CHECK(px[(9 * 40 + 0) * 3] == 128);
  CHECK(label_width("AB", 2) == 24);
}

TEST_CASE("lower case is drawn in capitals, characters without a glyph as '?'") {
  CHECK(drawn("cga-motors 0.5") == drawn("CGA-MOTORS 0.5"));
  CHECK(drawn("~") == drawn("?"));
  CHECK(drawn("B") != drawn("8"));
}

TEST_CASE("with_caption puts a band on top and keeps the picture below it") {
  Image pic;
  pic.width = 120, pic.height = 10;
  pic.rgba.assign(static_cast<std::size_t>(pic.width) * pic.height * 4, 7);
  const std::string lines[] = {"title", "a second line long enough to wrap at the picture's width"};
  const Image out = with_caption(pic, lines);
  CHECK(out.width == pic.width);
  const int band = out.height - pic.height;
  CHECK(band == 9 + 2 * 9 + 3 * 9);  // margins, the title at scale 2, the second line wrapped into 3 rows
  CHECK(std::equal(pic.rgba.begin(), pic.rgba.end(), out.rgba.begin() + static_cast<std::ptrdiff_t>(band) * out.width * 4));
  CHECK(out.count_pixels_unlike({255, 255, 255, 255}) > pic.rgba.size() / 4);  // ink and the picture
  CHECK(with_caption(pic, lines, 10).height == pic.height + 9 + 10 * 9);
}

TEST_CASE("draw_label refuses a buffer that does not hold the picture") {
  std::vector<std::uint8_t> px(10);
  CHECK_THROWS_AS(draw_label(px, 4, 4, 3, 0, 0, "A"), std::invalid_argument);
  std::vector<std::uint8_t> ok(4 * 4 * 2);
  CHECK_THROWS_AS(draw_label(ok, 4, 4, 2, 0, 0, "A"), std::invalid_argument);
  std::vector<std::uint8_t> fine(4 * 4 * 4);
  CHECK_NOTHROW(draw_label(fine, 4, 4, 4, -50, 100, "clipped away"));
}
