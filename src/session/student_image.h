// A student's own image of the view, opened to be checked against the reference
// (docs/checking.md): one rule for the previewer and the page.
// No GLFW, ImGui or GL.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "check/check.h"
#include "core/render/progressive.h"

namespace phonglab {

struct OpenedStudentImage {
  std::optional<StudentImage> image;  // nothing when refused
  std::string name;                   // the file's name, as the compare's caption names it
  std::string error;                  // why not: unreadable, or not the view's size (both sizes said)
};

// Reads the image at `path` for the view of `view_width` x `view_height`. A refusal for its size
// ends with `hint` in brackets when given (where the client's user finds the view's size).
OpenedStudentImage open_student_image(const std::string& path, int view_width, int view_height,
                                      std::string_view hint = {});

// The image as A of the compare: linear values, as the screen shows a render (8-bit codes decoded
// through the sRGB curve), one sample.
ProgressiveFrame compare_frame(const StudentImage& image);

}  // namespace phonglab
