// Image files: PFM (linear float, unclamped) and PNG (8-bit sRGB of the clamped mean).
#pragma once

#include <string>
#include <vector>

#include "core/scene/display8.h"
#include "core/scene/math.h"
#include "core/render/render.h"

namespace phonglab {

// A linear RGB image, row-major from the top-left.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<glm::vec3> pixels;
  glm::vec3& at(int x, int y) { return pixels[static_cast<std::size_t>(y) * width + x]; }
  const glm::vec3& at(int x, int y) const { return pixels[static_cast<std::size_t>(y) * width + x]; }
};

// The accumulator's per-pixel means (what a render shows) as a float image.
Image mean_image(const Accumulator& accum);


// Encodes as PFM: "PF\n<w> <h>\n-1.0\n", then float32 little-endian rows bottom to top.
std::string encode_pfm(const Image& image);
// 8-bit sRGB PNG of clamp(image, 0, 1).
std::string encode_png_srgb(const Image& image);

// Writes `image` to `path` (format from the extension: .pfm or .png) through a temporary
// file and a rename. Returns an empty string on success, else the error.
std::string write_image(const std::string& path, const Image& image);

}  // namespace phonglab
