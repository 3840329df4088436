// Pictures: a posed character per method and the twist strip are rendered headless, written as PNG, read
// back from the file, and are not blank; the strip shows the candy-wrapper difference between lbs and
// cga-motors as fewer drawn pixels in the middle of the lbs panel.
#include <catch2/catch.hpp>

#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>

#include <filesystem>
#include <string>

#include "cga/gpu/render.hpp"
#include "cga/gpu/skinning.hpp"
#include "cga/io/loader.hpp"
#include "cga/testing/character_poser.hpp"
#include "cga/testing/twist_strip.hpp"

using namespace cga;
using namespace cga::gpu;

namespace {

std::string model(const char* rel) { return std::string(CGA_MODELS_DIR) + "/" + rel; }

// Writes, reads the file back with stb_image and checks it is the same picture and not all background.
void check_png(const Image& image, const std::string& path) {
  write_png(image, path);
  REQUIRE(std::filesystem::exists(path));
  int w = 0, h = 0, channels = 0;
  stbi_uc* data = stbi_load(path.c_str(), &w, &h, &channels, 4);
  REQUIRE(data != nullptr);
  Image back;
  back.width = w, back.height = h;
  back.rgba.assign(data, data + static_cast<std::size_t>(w) * h * 4);
  stbi_image_free(data);
  CHECK(w == image.width);
  CHECK(h == image.height);
  CHECK(back.rgba == image.rgba);
  const std::size_t drawn = back.count_pixels_unlike(kClearColour);
  INFO(path << ": " << drawn << " of " << w * h << " pixels drawn");
  CHECK(drawn > static_cast<std::size_t>(w) * h / 50);  // at least 2 % of the picture is the model
  CHECK(drawn < static_cast<std::size_t>(w) * h);        // and some background is left
}

// Drawn pixels in columns [x0, x1) of rows [y0, y1).
std::size_t drawn_in(const Image& im, int x0, int x1, int y0, int y1) {
  std::size_t n = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x)
      if (im.pixel(x, y) != kClearColour) ++n;
  return n;
}

}  // namespace

TEST_CASE("a posed character renders to a PNG per method") {
  Context ctx;
  const Character ch = load_character(model("X/BCN_Epileptic.X"));
  REQUIRE(!ch.clips.empty());
  const Clip& clip = ch.clips.front();
  const float t = 0.5f * clip.duration;
  cga::testing::CharacterPoser poser(ch);
  for (SkinningMethod method : kAllSkinningMethods) {
    const Image im = render_posed_character(ctx, ch, poser.pose(clip, t, method), method, 256, 256);
    check_png(im, std::string(CGA_GPU_PICTURES_DIR) + "/bcn_" + shader_method_name(method) + ".png");
  }
}

TEST_CASE("the twist strip shows the candy wrapper of lbs and not of cga-motors") {
  Context ctx;
  constexpr int kPanel = 160, kHeight = 240, kGap = 4;
  const Image strip = render_twist_strip(ctx, 3.14159265f, kPanel, kHeight);
  constexpr int kPanels = static_cast<int>(kSkinningMethodCount);
  REQUIRE(strip.width == kPanels * kPanel + (kPanels - 1) * kGap);
  REQUIRE(strip.height == kHeight);
  check_png(strip, std::string(CGA_GPU_PICTURES_DIR) + "/twist_strip.png");
  // Panels in the method table's order: lbs, dqs, cga-points, cga-motors, cga-log. The middle band of rows
  // holds the twisted joint.
  auto middle = [&](int panel) {
    const int x0 = panel * (kPanel + kGap);
    return drawn_in(strip, x0, x0 + kPanel, kHeight * 2 / 5, kHeight * 3 / 5);
  };
  INFO("drawn pixels in the middle band: lbs " << middle(0) << ", dqs " << middle(1) << ", cga-points "
                                               << middle(2) << ", cga-motors " << middle(3) << ", cga-log "
                                               << middle(4));
  CHECK(middle(0) < 0.75 * middle(3));
  CHECK(middle(2) < 0.75 * middle(3));
  CHECK(middle(1) > 0.9 * middle(3));
  CHECK(middle(4) > 0.9 * middle(3));
}

TEST_CASE("render_meshes refuses bad input") {
  Context ctx;
  const float p[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const std::uint32_t bad[3] = {0, 1, 3};
  const DrawMesh m{p, {}, bad, {1, 0, 0}};
  CHECK_THROWS_AS(render_meshes(ctx, std::span<const DrawMesh>(&m, 1), Camera{}, 64, 64), std::invalid_argument);
  const std::uint32_t good[3] = {0, 1, 2};
  const DrawMesh ok{p, {}, good, {1, 0, 0}};
  CHECK_THROWS_AS(render_meshes(ctx, std::span<const DrawMesh>(&ok, 1), Camera{}, 0, 64), std::invalid_argument);
  const Image im = render_meshes(ctx, std::span<const DrawMesh>(&ok, 1), Camera{}, 64, 64);
  CHECK(im.count_pixels_unlike(kClearColour) > 0);
}
