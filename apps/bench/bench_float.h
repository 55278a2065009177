// The float brute-force loop (float_loop.h) over a phonglab Scene, for the bench's comparisons.
#pragma once

#include <cstdint>
#include <vector>

#include "apps/bench/float_loop.h"
#include "core/scene/scene.h"

namespace phonglab::bench {

class FloatLoop {
 public:
  // The scene's spheres, planes, loose triangles and meshes' triangles in float; its camera at
  // width x height.
  FloatLoop(const Scene& scene, int width, int height);
  FloatLoop(const FloatLoop&) = delete;
  FloatLoop& operator=(const FloatLoop&) = delete;

  struct Frame {
    double ms = 0;
    std::uint64_t rays = 0;
    std::vector<float> rgb;  // width * height * 3
  };
  // One frame on `threads` threads (rows interleaved).
  Frame frame(int threads) const;

  static bool available() { return float_loop::cpu_supported(); }

 private:
  std::vector<float_loop::Sphere> spheres_;
  std::vector<float_loop::Plane> planes_;
  std::vector<float_loop::Triangle> triangles_;
  std::vector<float_loop::Light> lights_;
  std::vector<float_loop::Material> materials_;
  float_loop::Scene scene_{};
};

}  // namespace phonglab::bench
