// Scenes and lessons compiled into the binaries, so the previewer and CLI need no files on disk.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace phonglab {

struct EmbeddedScene {
  std::string_view name;         // what `phonglab-cli scenes` lists and SCENE accepts
  std::string_view description;  // one line: what the scene teaches
  std::string_view json;         // scene file text (docs/scene-format.md)
};

// A mesh file of an embedded scene, as string chunks to concatenate.
struct EmbeddedFile {
  std::string_view path;                  // relative to assets/scenes, '/'-separated
  std::span<const std::string_view> chunks;
};

// All embedded scenes; the first is the default (`lecture`).
std::span<const EmbeddedScene> embedded_scenes();

// The embedded scene of that name, or nullptr.
const EmbeddedScene* find_embedded_scene(std::string_view name);

// Every embedded mesh file.
std::span<const EmbeddedFile> embedded_files();

// A lesson compiled in (assets/lessons/<name>.json, docs/lessons.md).
struct EmbeddedLesson {
  std::string_view name;  // what `phonglab-cli lessons` lists and LESSON accepts
  std::string_view json;  // lesson file text
};
std::span<const EmbeddedLesson> embedded_lessons();
const EmbeddedLesson* find_embedded_lesson(std::string_view name);

// A file compiled in beside the embedded scenes (their meshes), by its path relative to
// assets/scenes ("cornell/CornellBox-Original.obj"); nullopt when there is none.
std::optional<std::string> embedded_file(std::string_view path);

}  // namespace phonglab
