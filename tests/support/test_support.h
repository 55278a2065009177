// Helpers shared by the test suites.
#pragma once

#include <string>
#include <string_view>
#include <utility>

#include <gtest/gtest.h>

#include <limits>
#include <optional>

#include "core/geometry/geometry.h"

#include "core/accel/prepared_scene.h"
#include "core/shading/shading.h"
#include "io/scene/scene_io.h"

namespace phonglab {

// The production sphere and triangle tests one ray at a time, as the tests call them.
inline std::optional<double> intersect_sphere(const Sphere& s, const Ray& ray, double t_min = 0) {
  const double t = sphere_root(s, ray.origin, ray.dir, t_min, std::numeric_limits<double>::infinity());
  if (t > 0) return t;
  return std::nullopt;
}
inline std::optional<double> intersect_triangle(const Triangle& tri, const Ray& ray, double* b1 = nullptr,
                                                double* b2 = nullptr, double t_min = 0) {
  return intersect_triangle(tri, ray, make_shear(ray.dir), b1, b2, t_min);
}

// An embedded scene (or a scene file), loaded as plain data; a failed load fails the test.
inline Scene load_scene_or_fail(std::string_view name) {
  LoadResult result = load_scene_arg(std::string(name));
  EXPECT_TRUE(result.ok()) << result.error_text();
  return result.ok() ? std::move(*result.scene) : Scene{};
}

// The same scene, prepared for rendering.
inline PreparedScene load_prepared(std::string_view name) { return PreparedScene(load_scene_or_fail(name)); }

}  // namespace phonglab
