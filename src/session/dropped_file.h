// What a file dropped on the previewer's window is taken as: a mesh added to the scene, a lesson
// opened, a scene opened (through the unsaved-changes question), a student's image checked, or
// refused with the reason. No GLFW, ImGui or GL.
#pragma once

#include <cstdint>
#include <string>

namespace phonglab {

struct DroppedFile {
  enum class Kind : std::uint8_t { kRefused, kMesh, kLesson, kScene, kImage };
  Kind kind = Kind::kRefused;
  std::string refusal;  // kRefused: why, naming the file
};

// By the file's ending (and, for .json, whether it is a lesson file, docs/lessons.md).
DroppedFile classify_drop(const std::string& path);

}  // namespace phonglab
