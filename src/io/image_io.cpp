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

unsigned char linear_to_srgb8(double linear) {
  const double c = linear > 0 ? (linear < 1 ? linear : 1) : 0;  // also maps NaN to 0
  const double s = c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1 / 2.4) - 0.055;
  return static_cast<unsigned char>(std::lround(s * 255));
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

Image decode_pfm(const std::string& bytes, std::string* error) {
  std::istringstream in(bytes);
  std::string magic;
  int w = 0, h = 0;
  double scale = 0;
  in >> magic >> w >> h >> scale;
  if (!in || magic != "PF" || w <= 0 || h <= 0 || scale == 0) {
    if (error) *error = "not a colour PFM file";
    return {};
  }
  in.get();  // the single whitespace character after the scale
  const std::size_t offset = static_cast<std::size_t>(in.tellg());
  const std::size_t count = static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 3;
  if (bytes.size() < offset + count * 4) {
    if (error) *error = "PFM file is truncated";
    return {};
  }
  Image img;
  img.width = w;
  img.height = h;
  img.pixels.resize(static_cast<std::size_t>(w) * h);
  const bool little = scale < 0;
  std::size_t pos = offset;
  for (int y = h - 1; y >= 0; --y) {
    for (int x = 0; x < w; ++x) {
      for (int c = 0; c < 3; ++c) {
        std::uint32_t bits = 0;
        for (int b = 0; b < 4; ++b) {
          const auto byte = static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[pos + (little ? b : 3 - b)]));
          bits |= byte << (8 * b);
        }
        pos += 4;
        float f;
        std::memcpy(&f, &bits, sizeof f);
        img.at(x, y)[c] = f;
      }
    }
  }
  return img;
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

Image read_pfm(const std::string& path, std::string* error) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    if (error) *error = "cannot open " + path;
    return {};
  }
  std::ostringstream ss;
  ss << in.rdbuf();
  return decode_pfm(ss.str(), error);
}

}  // namespace phonglab
