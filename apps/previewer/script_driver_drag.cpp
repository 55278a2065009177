// The drag commands of test scripts (docs/previewer.md lists them): a mouse drag, a light's
// marker grabbed where it is drawn, an object grabbed by its marker, each injected as real input
// frame by frame.
#include <algorithm>
#include <optional>

#include "apps/previewer/script_step.h"
#include "apps/previewer/script_words.h"
#include "apps/previewer/viewer_app.h"
#include "interaction/scene_objects.h"

namespace phonglab {

using script::parse_double;
using script::parse_int;

namespace {

int mouse_button(const std::string& name) {
  if (name == "left") return 0;
  if (name == "right") return 1;
  if (name == "middle") return 2;
  return -1;
}

}  // namespace

std::optional<bool> ScriptDriver::script_drag_command(ScriptStep& step) {
  const std::vector<std::string>& w = step.w;
  const std::string& name = w[0];
  if (name == "drag") {
    // drag BUTTON X0 Y0 X1 Y1 [STEPS] [shift]
    int button = w.size() >= 6 ? mouse_button(w[1]) : -1;
    double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    int steps = 10;
    if (button < 0 || !parse_double(w[2], x0) || !parse_double(w[3], y0) || !parse_double(w[4], x1) ||
        !parse_double(w[5], y1) || (w.size() > 6 && !parse_int(w[6], steps)) || steps < 1) {
      return step.fail("usage: drag left|right|middle X0 Y0 X1 Y1 [STEPS] [shift]");
    }
    const bool shift = w.size() > 7 && w[7] == "shift";
    push_drag(button, ImVec2(static_cast<float>(x0), static_cast<float>(y0)),
              ImVec2(static_cast<float>(x1), static_cast<float>(y1)), steps, shift);
    return step.wait_for(ScriptWait::kInput, 99);
  }
  if (name == "drag_light") {
    // drag_light I DX DY [STEPS]: grabs light I's marker where it is drawn and drags it by
    // (DX, DY), in STEPS frames (10).
    int index = -1;
    double dx = 0, dy = 0;
    int steps = 10;
    const std::vector<Light>& lights = s_.doc.scene().lights;
    if ((w.size() != 4 && w.size() != 5) || !parse_int(w[1], index) || !parse_double(w[2], dx) ||
        !parse_double(w[3], dy) || index < 0 || index >= static_cast<int>(lights.size()) ||
        (w.size() == 5 && (!parse_int(w[4], steps) || steps < 1))) {
      return step.fail("usage: drag_light I DX DY [STEPS]");
    }
    // Where its marker (or its arrow at the edge) was drawn last frame: what a user would grab.
    const auto marker = std::find_if(s_.markers.begin(), s_.markers.end(),
                                     [&](const ui::LightMarker& m) { return m.index == index; });
    if (marker == s_.markers.end()) return step.fail("light " + w[1] + " has no marker (behind the camera, or not a point light)");
    const ImVec2 from = marker->pos;
    push_drag(0, from, ImVec2(from.x + static_cast<float>(dx), from.y + static_cast<float>(dy)), steps, false);
    return step.wait_for(ScriptWait::kInput, 99);
  }
  if (name == "drag_object") {
    // drag_object I DX DY [x|y|z|v]: selects object I, grabs it by its marker (where it is drawn)
    // and drags by DX, DY pixels, the axis key (or V, up and down) held for a constrained move.
    int index = -1, axis_key = -1;
    double dx = 0, dy = 0;
    if ((w.size() != 4 && w.size() != 5) || !parse_int(w[1], index) || !parse_double(w[2], dx) || !parse_double(w[3], dy)) {
      return step.fail("usage: drag_object I DX DY [x|y|z|v]");
    }
    if (w.size() == 5) {
      if (w[4] != "x" && w[4] != "y" && w[4] != "z" && w[4] != "v") return step.fail("usage: drag_object I DX DY [x|y|z|v]");
      axis_key = w[4] == "v" ? GLFW_KEY_V : GLFW_KEY_X + (w[4][0] - 'x');
    }
    // No such object, or none to grab on screen: the program says so, as for a refused edit.
    if (index < 0 || index >= ui::object_count(s_.doc.scene())) {
      builder_.refuse("no objects[" + w[1] + "]");
      return true;
    }
    builder_.select_object(index);
    const std::optional<ImVec2> from = builder_.object_screen_point(index);
    if (!from) {
      builder_.refuse("objects[" + w[1] + "] is behind the camera: nothing to grab");
      return true;
    }
    push_drag(0, *from, ImVec2(from->x + static_cast<float>(dx), from->y + static_cast<float>(dy)), 12, false, axis_key);
    return step.wait_for(ScriptWait::kInput, 99);
  }
  return std::nullopt;
}

}  // namespace phonglab
