// The 5x7 pixel font of label.hpp and the drawing of a label. Each glyph is seven rows of five bits (bit 4 the
// leftmost pixel); the comment beside it shows the rows ('#' ink), so a glyph can be read and fixed by eye.
#include "cga/gpu/label.hpp"

#include <algorithm>
#include <cctype>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace cga::gpu {
namespace {

struct Glyph {
  char c;
  std::array<std::uint8_t, 7> rows;
};

constexpr Glyph kGlyphs[] = {
    {' ', {0, 0, 0, 0, 0, 0, 0}},
    {'A', {0x0e, 0x11, 0x11, 0x1f, 0x11, 0x11, 0x11}},  // .###. #...# #...# ##### #...# #...# #...#
    {'B', {0x1e, 0x11, 0x11, 0x1e, 0x11, 0x11, 0x1e}},  // ####. #...# #...# ####. #...# #...# ####.
    {'C', {0x0e, 0x11, 0x10, 0x10, 0x10, 0x11, 0x0e}},  // .###. #...# #.... #.... #.... #...# .###.
    {'D', {0x1e, 0x11, 0x11, 0x11, 0x11, 0x11, 0x1e}},  // ####. #...# #...# #...# #...# #...# ####.
    {'E', {0x1f, 0x10, 0x10, 0x1e, 0x10, 0x10, 0x1f}},  // ##### #.... #.... ####. #.... #.... #####
    {'F', {0x1f, 0x10, 0x10, 0x1e, 0x10, 0x10, 0x10}},  // ##### #.... #.... ####. #.... #.... #....
    {'G', {0x0e, 0x11, 0x10, 0x17, 0x11, 0x11, 0x0f}},  // .###. #...# #.... #.### #...# #...# .####
    {'H', {0x11, 0x11, 0x11, 0x1f, 0x11, 0x11, 0x11}},  // #...# #...# #...# ##### #...# #...# #...#
    {'I', {0x0e, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0e}},  // .###. ..#.. ..#.. ..#.. ..#.. ..#.. .###.
    {'J', {0x07, 0x02, 0x02, 0x02, 0x02, 0x12, 0x0c}},  // ..### ...#. ...#. ...#. ...#. #..#. .##..
    {'K', {0x11, 0x12, 0x14, 0x18, 0x14, 0x12, 0x11}},  // #...# #..#. #.#.. ##... #.#.. #..#. #...#
    {'L', {0x10, 0x10, 0x10, 0x10, 0x10, 0x10, 0x1f}},  // #.... #.... #.... #.... #.... #.... #####
    {'M', {0x11, 0x1b, 0x15, 0x15, 0x11, 0x11, 0x11}},  // #...# ##.## #.#.# #.#.# #...# #...# #...#
    {'N', {0x11, 0x11, 0x19, 0x15, 0x13, 0x11, 0x11}},  // #...# #...# ##..# #.#.# #..## #...# #...#
    {'O', {0x0e, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0e}},  // .###. #...# #...# #...# #...# #...# .###.
    {'P', {0x1e, 0x11, 0x11, 0x1e, 0x10, 0x10, 0x10}},  // ####. #...# #...# ####. #.... #.... #....
    {'Q', {0x0e, 0x11, 0x11, 0x11, 0x15, 0x12, 0x0d}},  // .###. #...# #...# #...# #.#.# #..#. .##.#
    {'R', {0x1e, 0x11, 0x11, 0x1e, 0x14, 0x12, 0x11}},  // ####. #...# #...# ####. #.#.. #..#. #...#
    {'S', {0x0f, 0x10, 0x10, 0x0e, 0x01, 0x01, 0x1e}},  // .#### #.... #.... .###. ....# ....# ####.
    {'T', {0x1f, 0x04, 0x04, 0x04, 0x04, 0x04, 0x04}},  // ##### ..#.. ..#.. ..#.. ..#.. ..#.. ..#..
    {'U', {0x11, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0e}},  // #...# #...# #...# #...# #...# #...# .###.
    {'V', {0x11, 0x11, 0x11, 0x11, 0x11, 0x0a, 0x04}},  // #...# #...# #...# #...# #...# .#.#. ..#..
    {'W', {0x11, 0x11, 0x11, 0x15, 0x15, 0x15, 0x0a}},  // #...# #...# #...# #.#.# #.#.# #.#.# .#.#.
    {'X', {0x11, 0x11, 0x0a, 0x04, 0x0a, 0x11, 0x11}},  // #...# #...# .#.#. ..#.. .#.#. #...# #...#
    {'Y', {0x11, 0x11, 0x0a, 0x04, 0x04, 0x04, 0x04}},  // #...# #...# .#.#. ..#.. ..#.. ..#.. ..#..
    {'Z', {0x1f, 0x01, 0x02, 0x04, 0x08, 0x10, 0x1f}},  // ##### ....# ...#. ..#.. .#... #.... #####
    {'0', {0x0e, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0e}},  // .###. #...# #..## #.#.# ##..# #...# .###.
    {'1', {0x04, 0x0c, 0x04, 0x04, 0x04, 0x04, 0x0e}},  // ..#.. .##.. ..#.. ..#.. ..#.. ..#.. .###.
    {'2', {0x0e, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1f}},  // .###. #...# ....# ...#. ..#.. .#... #####
    {'3', {0x1e, 0x01, 0x01, 0x0e, 0x01, 0x01, 0x1e}},  // ####. ....# ....# .###. ....# ....# ####.
    {'4', {0x02, 0x06, 0x0a, 0x12, 0x1f, 0x02, 0x02}},  // ...#. ..##. .#.#. #..#. ##### ...#. ...#.
    {'5', {0x1f, 0x10, 0x1e, 0x01, 0x01, 0x11, 0x0e}},  // ##### #.... ####. ....# ....# #...# .###.
    {'6', {0x0e, 0x10, 0x10, 0x1e, 0x11, 0x11, 0x0e}},  // .###. #.... #.... ####. #...# #...# .###.
    {'7', {0x1f, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08}},  // ##### ....# ...#. ..#.. .#... .#... .#...
    {'8', {0x0e, 0x11, 0x11, 0x0e, 0x11, 0x11, 0x0e}},  // .###. #...# #...# .###. #...# #...# .###.
    {'9', {0x0e, 0x11, 0x11, 0x0f, 0x01, 0x01, 0x0e}},  // .###. #...# #...# .#### ....# ....# .###.
    {'-', {0x00, 0x00, 0x00, 0x0e, 0x00, 0x00, 0x00}},  // ..... ..... ..... .###. ..... ..... .....
    {'.', {0x00, 0x00, 0x00, 0x00, 0x00, 0x0c, 0x0c}},  // ..... ..... ..... ..... ..... .##.. .##..
    {',', {0x00, 0x00, 0x00, 0x00, 0x00, 0x04, 0x08}},  // ..... ..... ..... ..... ..... ..#.. .#...
    {':', {0x00, 0x0c, 0x0c, 0x00, 0x0c, 0x0c, 0x00}},  // ..... .##.. .##.. ..... .##.. .##.. .....
    {'/', {0x01, 0x01, 0x02, 0x04, 0x08, 0x10, 0x10}},  // ....# ....# ...#. ..#.. .#... #.... #....
    {'=', {0x00, 0x00, 0x1f, 0x00, 0x1f, 0x00, 0x00}},  // ..... ..... ##### ..... ##### ..... .....
    {'(', {0x02, 0x04, 0x08, 0x08, 0x08, 0x04, 0x02}},  // ...#. ..#.. .#... .#... .#... ..#.. ...#.
    {')', {0x08, 0x04, 0x02, 0x02, 0x02, 0x04, 0x08}},  // .#... ..#.. ...#. ...#. ...#. ..#.. .#...
    {'%', {0x19, 0x19, 0x02, 0x04, 0x08, 0x13, 0x13}},  // ##..# ##..# ...#. ..#.. .#... #..## #..##
    {'\'', {0x04, 0x04, 0x00, 0x00, 0x00, 0x00, 0x00}},  // ..#.. ..#.. ..... ..... ..... ..... .....
    {'+', {0x00, 0x04, 0x04, 0x1f, 0x04, 0x04, 0x00}},  // ..... ..#.. ..#.. ##### ..#.. ..#.. .....
    {'_', {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x1f}},  // ..... ..... ..... ..... ..... ..... #####
    {'?', {0x0e, 0x11, 0x01, 0x02, 0x04, 0x00, 0x04}},  // .###. #...# ....# ...#. ..#.. ..... ..#..
    {'|', {0x04, 0x04, 0x04, 0x04, 0x04, 0x04, 0x04}},  // ..#.. ..#.. ..#.. ..#.. ..#.. ..#.. ..#..
    {';', {0x00, 0x0c, 0x0c, 0x00, 0x0c, 0x04, 0x08}},  // ..... .##.. .##.. ..... .##.. ..#.. .#...
    {'!', {0x04, 0x04, 0x04, 0x04, 0x04, 0x00, 0x04}},  // ..#.. ..#.. ..#.. ..#.. ..#.. ..... ..#..
    {'[', {0x0e, 0x08, 0x08, 0x08, 0x08, 0x08, 0x0e}},  // .###. .#... .#... .#... .#... .#... .###.
    {']', {0x0e, 0x02, 0x02, 0x02, 0x02, 0x02, 0x0e}},  // .###. ...#. ...#. ...#. ...#. ...#. .###.
    {'*', {0x00, 0x04, 0x15, 0x0e, 0x15, 0x04, 0x00}},  // ..... ..#.. #.#.# .###. #.#.# ..#.. .....
    {'<', {0x02, 0x04, 0x08, 0x10, 0x08, 0x04, 0x02}},  // ...#. ..#.. .#... #.... .#... ..#.. ...#.
    {'>', {0x08, 0x04, 0x02, 0x01, 0x02, 0x04, 0x08}},  // .#... ..#.. ...#. ....# ...#. ..#.. .#...
    {'\"', {0x0a, 0x0a, 0x00, 0x00, 0x00, 0x00, 0x00}},  // .#.#. .#.#. ..... ..... ..... ..... .....
};

const Glyph& glyph(char c) {
  const char upper = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  for (const Glyph& g : kGlyphs)
    if (g.c == upper) return g;
  for (const Glyph& g : kGlyphs)
    if (g.c == '?') return g;
  return kGlyphs[0];
}

}  // namespace

int label_width(std::string_view text, int scale) { return static_cast<int>(text.size()) * kGlyphWidth * scale; }

void draw_label(std::span<std::uint8_t> pixels, int width, int height, int channels, int x, int y,
                std::string_view text, int scale, std::array<std::uint8_t, 3> ink,
                std::array<std::uint8_t, 3> background) {
  if ((channels != 3 && channels != 4) || width < 0 || height < 0 || scale < 1 ||
      pixels.size() < static_cast<std::size_t>(width) * height * channels)
    throw std::invalid_argument("cga::gpu::draw_label: " + std::to_string(width) + "x" + std::to_string(height) +
                                "x" + std::to_string(channels) + " pixels in " + std::to_string(pixels.size()) +
                                " bytes, scale " + std::to_string(scale));
  const auto put = [&](int px, int py, const std::array<std::uint8_t, 3>& colour) {
    if (px < 0 || py < 0 || px >= width || py >= height) return;
    std::uint8_t* p = &pixels[(static_cast<std::size_t>(py) * width + px) * channels];
    std::copy(colour.begin(), colour.end(), p);
    if (channels == 4) p[3] = 255;
  };
  // The band: one cell high, one cell column of margin before and after the text.
  const int band_w = label_width(text, scale) + kGlyphWidth * scale, band_h = kGlyphHeight * scale;
  for (int by = 0; by < band_h; ++by)
    for (int bx = 0; bx < band_w; ++bx) put(x + bx, y + by, background);
  int pen = x + (kGlyphWidth * scale) / 2;
  for (char c : text) {
    const Glyph& g = glyph(c);
    for (int row = 0; row < 7; ++row)
      for (int col = 0; col < 5; ++col)
        if (g.rows[row] & (0x10 >> col))
          for (int sy = 0; sy < scale; ++sy)
            for (int sx = 0; sx < scale; ++sx) put(pen + col * scale + sx, y + (1 + row) * scale + sy, ink);
    pen += kGlyphWidth * scale;
  }
}

void draw_label(Image& image, int x, int y, std::string_view text, int scale, std::array<std::uint8_t, 3> ink,
                std::array<std::uint8_t, 3> background) {
  draw_label(image.rgba, image.width, image.height, 4, x, y, text, scale, ink, background);
}

Image with_caption(const Image& picture, std::span<const std::string> lines, int min_rows) {
  // Wrap: as many words as fit in the width (a word longer than a line is cut by the picture's edge).
  std::vector<std::pair<std::string, int>> rows;  // text, scale
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const int scale = i == 0 ? 2 : 1;
    const std::size_t fit = static_cast<std::size_t>(std::max(1, picture.width / (kGlyphWidth * scale) - 1));
    std::string row, word;
    const auto flush_word = [&] {
      if (word.empty()) return;
      if (!row.empty() && row.size() + 1 + word.size() > fit) rows.emplace_back(row, scale), row.clear();
      row += (row.empty() ? "" : " ") + word;
      word.clear();
    };
    for (char c : lines[i] + " ") {
      if (c == ' ') flush_word();
      else word += c;
    }
    if (!row.empty()) rows.emplace_back(row, scale);
  }
  int band = kGlyphHeight;  // a half-cell above and below at scale 2
  int scale_1_rows = 0;
  for (const auto& [text, scale] : rows) band += kGlyphHeight * scale, scale_1_rows += scale;
  band += kGlyphHeight * std::max(0, min_rows - scale_1_rows);
  Image out;
  out.width = picture.width, out.height = picture.height + band;
  out.rgba.assign(static_cast<std::size_t>(out.width) * out.height * 4, 255);
  std::copy(picture.rgba.begin(), picture.rgba.end(), out.rgba.begin() + static_cast<std::ptrdiff_t>(out.width) * band * 4);
  for (int x = 0; x < out.width; ++x)  // a grey rule between the caption and the picture
    std::fill_n(&out.rgba[(static_cast<std::size_t>(band - 1) * out.width + x) * 4], 3, std::uint8_t{190});
  int y = kGlyphHeight / 2;
  for (const auto& [text, scale] : rows) {
    draw_label(out, 0, y, text, scale);
    y += kGlyphHeight * scale;
  }
  return out;
}

}  // namespace cga::gpu
