// Text labels burnt into pictures: a built-in 5x7 pixel font (capitals, digits and a little punctuation;
// lower case is drawn in capitals) so that every PNG the demo and the tests write says what it shows
// (method, path, pose) without a font library. Works on any 8-bit interleaved pixel buffer (RGB or RGBA).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "cga/gpu/render.hpp"

namespace cga::gpu {

// Glyph cell: 5x7 pixels plus one column and two rows of spacing, times `scale`.
inline constexpr int kGlyphWidth = 6, kGlyphHeight = 9;

// Width in pixels of `text` drawn at `scale` (one line; no wrapping).
int label_width(std::string_view text, int scale = 2);

// Draws `text` with its top-left corner at (x, y) on a band of `background` one glyph cell high (clipped to the
// picture); characters without a glyph are drawn as '?'. `pixels` holds width x height pixels of `channels`
// bytes (3 or 4; a 4th channel is set to 255), rows top to bottom.
void draw_label(std::span<std::uint8_t> pixels, int width, int height, int channels, int x, int y,
                std::string_view text, int scale = 2, std::array<std::uint8_t, 3> ink = {20, 20, 20},
                std::array<std::uint8_t, 3> background = {255, 255, 255});

// The same on an Image of this library (RGBA).
void draw_label(Image& image, int x, int y, std::string_view text, int scale = 2,
                std::array<std::uint8_t, 3> ink = {20, 20, 20}, std::array<std::uint8_t, 3> background = {255, 255, 255});

// The picture below a white band holding `lines`: the first at scale 2, the others at scale 1, each wrapped at
// spaces to the picture's width. The band has room for at least `min_rows` rows at scale 1 (pictures meant to
// be compared side by side get the same band, so their pictures line up).
Image with_caption(const Image& picture, std::span<const std::string> lines, int min_rows = 0);

}  // namespace cga::gpu
