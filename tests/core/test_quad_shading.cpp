// The quad-shaded live rung (core/render/quad_shading.h): the pixels it shades are the
// exact image's bit for bit, every pixel is within a few display codes of it, its error is under a
// third of the half-resolution level's (the target of the camera-drag design), and it is the same
// image for any thread count, traced in packets or by the scalar tracer.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "core/scene/display8.h"
#include "core/render/quad_shading.h"
#include "io/scene/scene_io.h"
#include "tests/support/simd_targets.h"

namespace phonglab {
namespace {

Accumulator image(const PreparedScene& scene, int w, int h, bool quads, int threads, bool packets = true) {
  Accumulator a;
  a.reset(w, h);
  RenderOptions options;
  options.threads = threads;
  options.packets = packets;
  if (quads) render_quad_shaded(scene, options, a);
  else render_pass(scene, options, a);
  return a;
}

// RMSE in display sRGB codes (0..1) of `a` shown over a w x h view (a coarse level widened into
// its blocks) against `exact`.
double rmse(const Accumulator& a, const Accumulator& exact) {
  const int d = exact.width / a.width;
  double sq = 0;
  for (int y = 0; y < exact.height; ++y) {
    for (int x = 0; x < exact.width; ++x) {
      const Color c = a.sum[static_cast<std::size_t>(y / d) * a.width + x / d];
      const Color e = exact.sum[static_cast<std::size_t>(y) * exact.width + x];
      for (int k = 0; k < 3; ++k) {
        const double diff = (linear_to_srgb8(c[k]) - linear_to_srgb8(e[k])) / 255.0;
        sq += diff * diff;
      }
    }
  }
  return std::sqrt(sq / (3.0 * exact.width * exact.height));
}

TEST(QuadShading, ShadedPixelsAreExactAndTheErrorIsUnderAThirdOfTheHalfLevels) {
  test::for_each_simd_target([&] {
    for (const char* name : {"lecture", "cornell", "shininess"}) {
      LoadResult loaded = load_scene_arg(name);
      ASSERT_TRUE(loaded.ok()) << name;
      const PreparedScene scene(*loaded.scene);
      constexpr int kW = 320, kH = 180;
      const Accumulator exact = image(scene, kW, kH, false, 2);
      const Accumulator quads = image(scene, kW, kH, true, 2);
      const Accumulator half = image(scene, kW / 2, kH / 2, false, 2);
      std::size_t same = 0, far = 0;
      for (std::size_t i = 0; i < exact.sum.size(); ++i) {
        if (std::memcmp(&exact.sum[i], &quads.sum[i], sizeof(Color)) == 0) ++same;
        for (int k = 0; k < 3; ++k) {
          if (std::abs(linear_to_srgb8(exact.sum[i][k]) - linear_to_srgb8(quads.sum[i][k])) > 3) ++far;
        }
      }
      EXPECT_GT(same, exact.sum.size() / 4) << name << ": at least the shaded quarter is exact";
      EXPECT_LT(far, exact.sum.size() / 1000) << name << ": hardly a channel more than 3 codes off";
      EXPECT_LT(rmse(quads, exact), rmse(half, exact) / 3) << name;
      const Accumulator one = image(scene, kW, kH, true, 1);
      EXPECT_EQ(std::memcmp(one.sum.data(), quads.sum.data(), one.sum.size() * sizeof(Color)), 0) << name;
      const Accumulator scalar = image(scene, kW, kH, true, 2, false);
      EXPECT_EQ(std::memcmp(scalar.sum.data(), quads.sum.data(), scalar.sum.size() * sizeof(Color)), 0)
          << name << ": the scalar tracer's rung is the packet tracer's";
    }
  });
}

}  // namespace
}  // namespace phonglab
