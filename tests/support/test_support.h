// Helpers shared by the test suites.
#pragma once

#include <string>
#include <string_view>
#include <utility>

#include <gtest/gtest.h>

#include "io/scene/scene_io.h"
#include "core/shading/shading.h"

namespace phonglab {

// An embedded scene (or a scene file), loaded and prepared; a failed load fails the test.
inline Scene load_prepared(std::string_view name) {
  LoadResult result = load_scene_arg(std::string(name));
  EXPECT_TRUE(result.ok()) << result.error_text();
  Scene scene = result.ok() ? std::move(*result.scene) : Scene{};
  prepare_scene(scene);
  return scene;
}

}  // namespace phonglab
