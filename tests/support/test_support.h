// Helpers shared by the test suites.
#pragma once

#include <string>
#include <string_view>
#include <utility>

#include <gtest/gtest.h>

#include "core/accel/prepared_scene.h"
#include "core/shading/shading.h"
#include "io/scene/scene_io.h"

namespace phonglab {

// An embedded scene (or a scene file), loaded as plain data; a failed load fails the test.
inline Scene load_scene_or_fail(std::string_view name) {
  LoadResult result = load_scene_arg(std::string(name));
  EXPECT_TRUE(result.ok()) << result.error_text();
  return result.ok() ? std::move(*result.scene) : Scene{};
}

// The same scene, prepared for rendering.
inline PreparedScene load_prepared(std::string_view name) { return PreparedScene(load_scene_or_fail(name)); }

}  // namespace phonglab
