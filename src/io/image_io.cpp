#include "io/image_io.h"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>

#include <stb_image_write.h>

#include "io/scene/scene_io.h"

namespace phonglab {

Image mean_image(const Accumulator& accum) {
  Image image;
  image.width = accum.width;
  image.height = accum.height;
  image.pixels.resize(accum.sum.size());
  for (int y = 0; y < accum.height; ++y) {
    for (int x = 0; x < accum.width; ++x) image.at(x, y) = glm::vec3(accum.mean(x, y));
  }
  return image;
}


std::string encode_pfm(const Image& image) {
  std::string out = "PF\n" + std::to_string(image.width) + " " + std::to_string(image.height) + "\n-1.0\n";
  const std::size_t row_bytes = static_cast<std::size_t>(image.width) * 3 * sizeof(float);
  std::size_t pos = out.size();
  out.resize(pos + row_bytes * static_cast<std::size_t>(image.height));
  for (int y = image.height - 1; y >= 0; --y) {  // PFM stores the bottom row first
    for (int x = 0; x < image.width; ++x) {
      const glm::vec3& p = image.at(x, y);
      for (int c = 0; c < 3; ++c) {
        std::uint32_t bits;
        std::memcpy(&bits, &p[c], sizeof bits);
        for (int b = 0; b < 4; ++b) out[pos++] = static_cast<char>((bits >> (8 * b)) & 0xFF);  // little-endian
      }
    }
  }
  return out;
}


std::string encode_png_srgb(const Image& image) {
  std::vector<unsigned char> rgb(static_cast<std::size_t>(image.width) * image.height * 3);
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    for (int c = 0; c < 3; ++c) rgb[i * 3 + c] = linear_to_srgb8(image.pixels[i][c]);
  }
  std::string out;
  auto append = [](void* ctx, void* data, int size) {
    static_cast<std::string*>(ctx)->append(static_cast<const char*>(data), static_cast<std::size_t>(size));
  };
  if (!stbi_write_png_to_func(append, &out, image.width, image.height, 3, rgb.data(), image.width * 3)) return {};
  return out;
}

namespace {
bool ends_with(const std::string& s, const std::string& suffix) {
  if (s.size() < suffix.size()) return false;
  for (std::size_t i = 0; i < suffix.size(); ++i) {
    if (std::tolower(static_cast<unsigned char>(s[s.size() - suffix.size() + i])) != suffix[i]) return false;
  }
  return true;
}
}  // namespace

std::string write_image(const std::string& path, const Image& image) {
  std::string bytes;
  if (ends_with(path, ".pfm")) {
    bytes = encode_pfm(image);
  } else if (ends_with(path, ".png")) {
    bytes = encode_png_srgb(image);
    if (bytes.empty()) return "PNG encoding failed";
  } else {
    return "unknown image format for '" + path + "' (use .pfm or .png)";
  }
  return write_file_atomically(path, bytes);
}


}  // namespace phonglab
