#include "core/scene/display8.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

namespace phonglab {

namespace {

double clamp01(double v) { return v > 0 ? (v < 1 ? v : 1) : 0; }  // NaN to 0

float float_of(std::uint32_t bits) {
  float f;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}

constexpr std::uint32_t kOneBits = 0x3F800000u;  // 1.0f

}  // namespace

unsigned char linear_to_srgb8(double linear) {
  const double c = clamp01(linear);
  const double s = c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1 / 2.4) - 0.055;
  return static_cast<unsigned char>(std::lround(s * 255));
}

unsigned char linear_to_unorm8(double linear) { return static_cast<unsigned char>(std::lround(clamp01(linear) * 255)); }

Display8Encoder::Display8Encoder(bool srgb) {
  const auto code = [srgb](std::uint32_t bits) {
    const double v = float_of(bits);
    return srgb ? linear_to_srgb8(v) : linear_to_unorm8(v);
  };
  // Positive floats order as their bit patterns: each threshold by bisection over them.
  first_bits_[0] = 0;
  for (unsigned k = 1; k < 256; ++k) {
    std::uint32_t lo = 0, hi = kOneBits;  // code(lo) < k <= code(hi)
    while (hi - lo > 1) {
      const std::uint32_t mid = lo + (hi - lo) / 2;
      (code(mid) >= k ? hi : lo) = mid;
    }
    first_bits_[k] = hi;
  }
  const std::size_t buckets = kOneBits >> kShift;
  bucket_code_.resize(buckets);
  unsigned k = 0;
  for (std::size_t b = 0; b < buckets; ++b) {
    const auto first = static_cast<std::uint32_t>(b << kShift);
    const std::uint32_t last = first + ((1u << kShift) - 1);
    while (k < 255 && first_bits_[k + 1] <= first) ++k;
    bucket_code_[b] = static_cast<unsigned char>(k);
    if (k + 2 < 256 && first_bits_[k + 2] <= last) {
      throw std::logic_error("Display8Encoder: two thresholds in one bucket");  // cannot happen for these curves
    }
  }
}

void Display8Encoder::encode_bgra(const glm::vec3* pixels, std::size_t n, float scale, unsigned char* bgra) const {
  for (std::size_t i = 0; i < n; ++i, bgra += 4) {
    const glm::vec3 c = pixels[i] * scale;
    bgra[0] = (*this)(c.z);
    bgra[1] = (*this)(c.y);
    bgra[2] = (*this)(c.x);
    bgra[3] = 255;
  }
}

bool Display8Encoder::encode_bgra_blocks(const glm::vec3* pixels, int width, int height, float scale,
                                         const DisplayBlocks& blocks, bool bottom_up, unsigned char* out) const {
  const int block = blocks.block;
  if (width < 1 || height < 1 || !blocks.fit(width, height)) return false;
  const auto out_row = static_cast<std::size_t>(blocks.width) * 4;
  const auto row_of = [&](int y) { return out + out_row * static_cast<std::size_t>(bottom_up ? blocks.height - 1 - y : y); };
  const auto image_row = [&](int y) { return pixels + static_cast<std::size_t>(y) * static_cast<std::size_t>(width); };
  if (block == 1) {  // the image as it is: each row straight into its place
    for (int y = 0; y < height; ++y) encode_bgra(image_row(y), static_cast<std::size_t>(width), scale, row_of(y));
    return true;
  }
  std::vector<unsigned char> codes(static_cast<std::size_t>(width) * 4);
  for (int y = 0; y < height; ++y) {
    encode_bgra(image_row(y), static_cast<std::size_t>(width), scale, codes.data());
    const int first = y * block;
    unsigned char* const target = row_of(first);
    for (int x = 0; x < width; ++x) {
      const int end = std::min((x + 1) * block, blocks.width);
      for (int wide = x * block; wide < end; ++wide) std::memcpy(target + static_cast<std::size_t>(wide) * 4, &codes[static_cast<std::size_t>(x) * 4], 4);
    }
    for (int copy = first + 1; copy < std::min(first + block, blocks.height); ++copy) std::memcpy(row_of(copy), target, out_row);
  }
  return true;
}

const Display8Encoder& Display8Encoder::srgb() {
  static const Display8Encoder encoder(true);
  return encoder;
}

const Display8Encoder& Display8Encoder::linear() {
  static const Display8Encoder encoder(false);
  return encoder;
}

}  // namespace phonglab
