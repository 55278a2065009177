#include "io/embedded_scenes.h"

namespace phonglab {

const EmbeddedScene* find_embedded_scene(std::string_view name) {
  for (const EmbeddedScene& s : embedded_scenes()) {
    if (s.name == name) return &s;
  }
  return nullptr;
}

const EmbeddedLesson* find_embedded_lesson(std::string_view name) {
  for (const EmbeddedLesson& l : embedded_lessons()) {
    if (l.name == name) return &l;
  }
  return nullptr;
}

std::optional<std::string> embedded_file(std::string_view path) {
  for (const EmbeddedFile& f : embedded_files()) {
    if (f.path != path) continue;
    std::string text;
    for (const std::string_view chunk : f.chunks) text += chunk;
    return text;
  }
  return std::nullopt;
}

}  // namespace phonglab
