// Scenes compiled into the binaries, so the previewer and CLI need no files on disk.
#pragma once

#include <span>
#include <string_view>

namespace phonglab {

struct EmbeddedScene {
  std::string_view name;         // what `phonglab-cli scenes` lists and SCENE accepts
  std::string_view description;  // one line: what the scene teaches
  std::string_view json;         // scene file text (SPEC §3)
};

// All embedded scenes; the first is the default (`lecture`).
std::span<const EmbeddedScene> embedded_scenes();

// The embedded scene of that name, or nullptr.
const EmbeddedScene* find_embedded_scene(std::string_view name);

}  // namespace phonglab
