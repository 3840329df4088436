// PNG output through stb_image_write (Debian libstb-dev); this file holds the stb implementation.
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>

#include <stdexcept>

#include "cga/gpu/render.hpp"

namespace cga::gpu {

void write_png(const Image& image, const std::string& path) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgba.size() != static_cast<std::size_t>(image.width) * image.height * 4)
    throw std::runtime_error("cga::gpu::write_png: " + path + ": image of " + std::to_string(image.width) + "x" +
                             std::to_string(image.height) + " with " + std::to_string(image.rgba.size()) + " bytes");
  if (!stbi_write_png(path.c_str(), image.width, image.height, 4, image.rgba.data(), image.width * 4))
    throw std::runtime_error("cga::gpu::write_png: cannot write " + path);
}

}  // namespace cga::gpu
