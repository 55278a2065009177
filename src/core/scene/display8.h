// What the screen and the PNG files show: a linear colour as 8-bit codes, through the sRGB
// transfer curve (IEC 61966-2-1) or linearly. One rule for both: the previewer's screen shows
// the codes the CLI's PNG holds, bit for bit, at exposure 0.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include <glm/glm.hpp>

namespace phonglab {

// Linear value to an 8-bit code: clamped to [0, 1] (NaN to 0), through the sRGB curve or not,
// rounded to the nearest of 0..255.
unsigned char linear_to_srgb8(double linear);
unsigned char linear_to_unorm8(double linear);

// The same codes for float values, fast enough for a whole image every frame (about 2 ns a
// channel): the floats in [0, 1] are split into buckets of 2^13 consecutive values, each of
// which holds at most one of the 255 thresholds where the code steps up (checked when built);
// a code is its bucket's code, plus one past that threshold.
// A coarse image's pixel stands for a block of block x block pixels of a view of
// width x height (the last blocks cut at the view's edges); block 1: the image as it is.
struct DisplayBlocks {
  int block = 1;
  int width = 0;
  int height = 0;
  // Whether an image of width x height is this view's coarse level: ceil(view / block) each way.
  bool fit(int image_width, int image_height) const {
    return block >= 1 && (width + block - 1) / block == image_width && (height + block - 1) / block == image_height;
  }
};

class Display8Encoder {
 public:
  explicit Display8Encoder(bool srgb);
  // linear_to_srgb8(v) or linear_to_unorm8(v), exactly.
  unsigned char operator()(float v) const {
    if (!(v > 0.0f)) return 0;  // also NaN
    if (v >= 1.0f) return 255;
    std::uint32_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    unsigned code = bucket_code_[bits >> kShift];
    if (code < 255 && bits >= first_bits_[code + 1]) ++code;
    return static_cast<unsigned char>(code);
  }
  // n pixels times `scale` (a float product, the display's exposure) into n x 4 bytes of
  // B, G, R, A (255) each: the order software GL copies to an X window without converting.
  void encode_bgra(const glm::vec3* pixels, std::size_t n, float scale, unsigned char* bgra) const;

  // A width x height image (rows from the top) times `scale` into the B, G, R, A codes of the
  // view `blocks` describes, each pixel repeated over its block; rows from the top, or from
  // the bottom (GL's order) when `bottom_up`. `out` holds blocks.width x blocks.height x 4
  // bytes, and the image must have ceil(blocks.width / block) x ceil(blocks.height / block)
  // pixels (returns false, writing nothing, otherwise).
  bool encode_bgra_blocks(const glm::vec3* pixels, int width, int height, float scale, const DisplayBlocks& blocks,
                          bool bottom_up, unsigned char* out) const;

  static const Display8Encoder& srgb();
  static const Display8Encoder& linear();

 private:
  static constexpr int kShift = 13;
  std::array<std::uint32_t, 256> first_bits_{};  // bit pattern of the smallest float with code k
  std::vector<unsigned char> bucket_code_;       // the code of each bucket's first float
};

}  // namespace phonglab
