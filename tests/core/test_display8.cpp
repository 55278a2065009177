// The display's 8-bit codes (src/core/scene/display8.h): the fast encoder gives exactly the
// codes of linear_to_srgb8 / linear_to_unorm8 (the PNG writer's rule) for every float checked:
// a stride through all floats in [0, 1], every float between the two stride points around each
// step of the code, and the special values.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include "core/scene/display8.h"

using namespace phonglab;

namespace {

float float_of(std::uint32_t bits) {
  float f;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}

void check_curve(const Display8Encoder& encoder, unsigned char (*reference)(double)) {
  constexpr std::uint32_t kOne = 0x3F800000u;
  constexpr std::uint32_t kStride = 97;
  int steps = 0;
  unsigned char previous = reference(0.0);
  for (std::uint32_t bits = 0; bits <= kOne; bits += kStride) {
    const float v = float_of(bits);
    const unsigned char expected = reference(v);
    ASSERT_EQ(encoder(v), expected) << "v = " << v;
    if (expected != previous) {
      ++steps;
      for (std::uint32_t b = bits - kStride; b <= bits; ++b) {  // every float across the step
        ASSERT_EQ(encoder(float_of(b)), reference(float_of(b))) << "bits " << b;
      }
    }
    previous = expected;
  }
  EXPECT_GE(steps, 250);  // almost every code is met within the stride
}

}  // namespace

TEST(Display8, SrgbCodesAreThePngWritersForEveryFloat) { check_curve(Display8Encoder::srgb(), &linear_to_srgb8); }

TEST(Display8, LinearCodesAreRoundedForEveryFloat) { check_curve(Display8Encoder::linear(), &linear_to_unorm8); }

TEST(Display8, OutOfRangeAndSpecialValues) {
  for (const Display8Encoder* e : {&Display8Encoder::srgb(), &Display8Encoder::linear()}) {
    EXPECT_EQ((*e)(std::numeric_limits<float>::quiet_NaN()), 0);
    EXPECT_EQ((*e)(-std::numeric_limits<float>::quiet_NaN()), 0);
    EXPECT_EQ((*e)(-0.0f), 0);
    EXPECT_EQ((*e)(-1.0f), 0);
    EXPECT_EQ((*e)(std::numeric_limits<float>::denorm_min()), 0);
    EXPECT_EQ((*e)(1.0f), 255);
    EXPECT_EQ((*e)(std::nextafter(1.0f, 0.0f)), 255);
    EXPECT_EQ((*e)(7.5f), 255);
    EXPECT_EQ((*e)(std::numeric_limits<float>::infinity()), 255);
    EXPECT_EQ((*e)(-std::numeric_limits<float>::infinity()), 0);
  }
  EXPECT_EQ(linear_to_srgb8(0.5), 188);
  EXPECT_EQ(Display8Encoder::srgb()(0.5f), 188);
  EXPECT_EQ(Display8Encoder::linear()(0.5f), 128);
}

TEST(Display8, PixelsAreScaledThenWrittenBlueFirst) {
  const std::vector<glm::vec3> pixels = {{0.25f, 0.5f, 1.0f}, {0.0f, 2.0f, 0.125f}};
  std::vector<unsigned char> bgra(8);
  Display8Encoder::srgb().encode_bgra(pixels.data(), pixels.size(), 2.0f, bgra.data());
  const std::vector<unsigned char> expected = {linear_to_srgb8(2.0), linear_to_srgb8(1.0), linear_to_srgb8(0.5), 255,
                                               linear_to_srgb8(0.25), linear_to_srgb8(4.0), 0, 255};
  EXPECT_EQ(bgra, expected);
}

// A coarse level widened into its blocks: every screen pixel holds the code of the image pixel
// whose block covers it (the last blocks cut at the view's edges), rows from the top or from the
// bottom, and a size that does not fit the view is refused.
TEST(Display8, BlocksRepeatEachPixelOverItsBlock) {
  const Display8Encoder& encoder = Display8Encoder::srgb();
  for (const DisplayBlocks blocks : {DisplayBlocks{1, 5, 3}, DisplayBlocks{2, 7, 5}, DisplayBlocks{4, 13, 9}, DisplayBlocks{8, 16, 8}}) {
    const int width = (blocks.width + blocks.block - 1) / blocks.block;
    const int height = (blocks.height + blocks.block - 1) / blocks.block;
    std::vector<glm::vec3> image(static_cast<std::size_t>(width * height));
    for (std::size_t i = 0; i < image.size(); ++i) image[i] = glm::vec3(0.01f * static_cast<float>(i), 0.5f, 1.0f - 0.013f * static_cast<float>(i));
    for (const bool bottom_up : {false, true}) {
      std::vector<unsigned char> out(static_cast<std::size_t>(blocks.width * blocks.height * 4), 7);
      ASSERT_TRUE(encoder.encode_bgra_blocks(image.data(), width, height, 2.0f, blocks, bottom_up, out.data()));
      for (int y = 0; y < blocks.height; ++y) {
        const int row = bottom_up ? blocks.height - 1 - y : y;
        for (int x = 0; x < blocks.width; ++x) {
          const glm::vec3 c = image[static_cast<std::size_t>((y / blocks.block) * width + x / blocks.block)] * 2.0f;
          const unsigned char* p = &out[static_cast<std::size_t>((row * blocks.width + x) * 4)];
          ASSERT_EQ(p[0], encoder(c.z)) << "block " << blocks.block << " x " << x << " y " << y << " bottom_up " << bottom_up;
          ASSERT_EQ(p[1], encoder(c.y));
          ASSERT_EQ(p[2], encoder(c.x)) << "block " << blocks.block << " x " << x << " y " << y;
          ASSERT_EQ(p[3], 255);
        }
      }
    }
    std::vector<unsigned char> out(static_cast<std::size_t>(blocks.width * blocks.height * 4));
    EXPECT_FALSE(encoder.encode_bgra_blocks(image.data(), width + 1, height, 1.0f, blocks, false, out.data()));
    EXPECT_FALSE(encoder.encode_bgra_blocks(image.data(), width, height + 1, 1.0f, blocks, false, out.data()));
  }
}
