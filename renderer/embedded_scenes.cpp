#include "renderer/embedded_scenes.h"

namespace phonglab {

const EmbeddedScene* find_embedded_scene(std::string_view name) {
  for (const EmbeddedScene& s : embedded_scenes()) {
    if (s.name == name) return &s;
  }
  return nullptr;
}

}  // namespace phonglab
