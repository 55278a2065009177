#include "session/dropped_file.h"

#include <filesystem>
#include <system_error>

#include "io/lesson_io.h"
#include "io/scene/scene_io.h"

namespace phonglab {

DroppedFile classify_drop(const std::string& path) {
  using Kind = DroppedFile::Kind;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return {Kind::kRefused, "dropped '" + path + "': not a file"};
  if (is_obj_path(path)) return {Kind::kMesh, {}};
  const std::string ext = std::filesystem::path(path).extension().string();
  if (ext == ".json" || ext == ".JSON") return {is_lesson_file(path) ? Kind::kLesson : Kind::kScene, {}};
  if (ext == ".png" || ext == ".PNG" || ext == ".ppm" || ext == ".PPM" || ext == ".pfm" || ext == ".PFM") {
    return {Kind::kImage, {}};
  }
  return {Kind::kRefused, "dropped '" + path +
                              "': not a scene or a lesson (.json), a mesh (.obj), nor an image to check (.png, .ppm, .pfm)"};
}

}  // namespace phonglab
