// Lesson files (docs/lessons.md): JSON text -> Lesson, with positioned diagnostics like scene
// files (file:line:col, the JSON path, what was expected). Each step's scene is loaded (an
// embedded scene's name, or a file relative to the lesson's folder) and its changes applied.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/teaching/lesson.h"
#include "io/diagnostic.h"

namespace phonglab {

struct LessonLoad {
  std::optional<Lesson> lesson;    // set when there are no errors
  std::vector<Diagnostic> errors;
  bool ok() const { return lesson.has_value(); }
  std::string error_text() const;  // all errors, one per line
};

// Parses lesson JSON. `file_name` names it in diagnostics and gives the lesson its name (the
// stem); scene files are read relative to `base_dir`.
LessonLoad load_lesson_text(const std::string& text, const std::string& file_name, const std::string& base_dir = ".");

// LESSON as the CLI and the previewer take it: an embedded lesson's name, else a file path.
LessonLoad load_lesson_arg(const std::string& lesson_arg);

// Whether a file's text is a lesson rather than a scene: a JSON object with "steps" (what only
// a lesson has). A file that does not parse is not one (it is then reported as a scene).
bool looks_like_lesson(const std::string& text);
bool is_lesson_file(const std::string& path);

}  // namespace phonglab
