// The previewer's input: the mouse over the view (orbit, pan, dolly, light markers, picking,
// probing) and the keyboard shortcuts.
#include "apps/previewer/viewer_app.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/scene/camera.h"
#include "core/geometry/geometry.h"
#include "io/probe_report.h"
#include "interaction/camera_control.h"
#include "interaction/numbers.h"
#include "interaction/scene_objects.h"
#include "ui/widgets.h"

namespace phonglab {

namespace {

constexpr float kDragThreshold = 3;         // pixels a press may move and still be a click
constexpr double kOrbitRadPerPixel = 0.008; // about 1.4 turns across a 1280-pixel drag
constexpr double kDollyPerPixel = 0.01;     // distance factor e^0.01 per pixel dragged
constexpr double kDollyPerWheelClick = 0.85;
constexpr float kMarkerGrabFactor = 1.8f;   // a marker can be grabbed a little outside its disc

const char* object_kind_name(ObjectRef::Kind kind) {
  switch (kind) {
    case ObjectRef::Kind::kSphere: return "sphere";
    case ObjectRef::Kind::kPlane: return "plane";
    case ObjectRef::Kind::kTriangle: return "triangle";
    case ObjectRef::Kind::kMesh: return "mesh";
    case ObjectRef::Kind::kNone: break;
  }
  return "object";
}

}  // namespace

void Viewer::handle_viewport_input() {
  ImGuiIO& io = ImGui::GetIO();
  const Scene& scene = s_.session.scene();
  const Camera view = view_camera(s_);
  // Where each button went down, from GLFW's event: ImGui 1.86 polls the cursor once a frame, so
  // a press followed by a quick move in the same frame would otherwise start where the pointer
  // already moved to (and miss the light marker it was pressed on).
  const std::vector<MousePress> presses = s_.platform.take_mouse_presses();
  const auto pressed_at = [&](int button) {
    ImVec2 at = io.MousePos;
    for (const MousePress& p : presses) {
      if (p.button == button) at = ImVec2(static_cast<float>(p.x), static_cast<float>(p.y));
    }
    return at;
  };
  ImVec2 mouse = io.MousePos;
  for (int button = 0; button < 3; ++button) {
    if (ImGui::IsMouseClicked(button)) mouse = pressed_at(button);
  }
  const bool over_viewport = ImGui::IsMousePosValid(&mouse) && mouse.x >= s_.viewport.x &&
                             mouse.x < s_.viewport.x + s_.viewport.width && mouse.y >= s_.viewport.y &&
                             mouse.y < s_.viewport.y + s_.viewport.height;
  const bool mouse_is_ours = over_viewport && !io.WantCaptureMouse && !s_.help_visible;
  const int view_w = std::max(1, static_cast<int>(std::lround(s_.viewport.width)));
  const int view_h = std::max(1, static_cast<int>(std::lround(s_.viewport.height)));

  // The point light whose marker is under the mouse, where it was drawn last frame (an arrow at
  // the edge for a light out of view): what the user sees is what the user grabs.
  s_.hovered_light = -1;
  if (s_.drag.mode == DragMode::kNone && mouse_is_ours) {
    const float grab = ui::light_marker_radius(s_.platform.ui_scale()) * kMarkerGrabFactor;
    float best = grab * grab;
    for (const ui::LightMarker& marker : s_.markers) {
      const float dx = marker.pos.x - mouse.x;
      const float dy = marker.pos.y - mouse.y;
      if (dx * dx + dy * dy <= best) {
        best = dx * dx + dy * dy;
        s_.hovered_light = marker.index;
      }
    }
  }

  // The wipe's split line, grabbed anywhere along its height.
  const std::optional<float> wipe_x = overlays_.wipe_line_x();
  const float wipe_grab = ui::light_marker_radius(s_.platform.ui_scale());
  const bool wipe_hovered = mouse_is_ours && s_.hovered_light < 0 && wipe_x && std::abs(mouse.x - *wipe_x) <= wipe_grab;
  if (wipe_hovered || s_.drag.mode == DragMode::kWipe) ImGui::SetMouseCursor(ImGuiMouseCursor_ResizeEW);

  if (s_.drag.mode == DragMode::kNone) {
    if (mouse_is_ours) {
      for (int button = 0; button < 3; ++button) {
        if (!ImGui::IsMouseClicked(button)) continue;
        s_.drag = Drag{};
        s_.drag.button = button;
        s_.drag.start = mouse;
        if (button == ImGuiMouseButton_Left && s_.hovered_light >= 0 &&
            s_.hovered_light < static_cast<int>(scene.lights.size())) {
          s_.drag.mode = DragMode::kLight;
          s_.drag.light = s_.hovered_light;
          s_.drag.light_depth = ui::view_depth(view, scene.lights[static_cast<std::size_t>(s_.hovered_light)].position);
          s_.selected_light = s_.hovered_light;
        } else if (button == ImGuiMouseButton_Left && wipe_hovered) {
          s_.drag.mode = DragMode::kWipe;  // the split line follows the pointer
        } else if (button == ImGuiMouseButton_Left && !io.KeyShift && !io.KeyCtrl &&
                   grab_object(mouse, io.KeyAlt ? object_under(mouse) : std::nullopt)) {
          // The selected object, grabbed by its handle, or by its surface with Alt held: moved
          // over the floor. A plain drag on its surface orbits (a selected room is still the
          // room one orbits in), and Ctrl+click probes it.
        } else if (button == ImGuiMouseButton_Left) {
          s_.drag.mode = io.KeyShift ? DragMode::kPan : DragMode::kOrbit;
        } else {
          s_.drag.mode = button == ImGuiMouseButton_Right ? DragMode::kDolly : DragMode::kPan;
        }
        break;
      }
      if (io.MouseWheel != 0) {
        const double factor = std::pow(kDollyPerWheelClick, static_cast<double>(io.MouseWheel));
        Camera camera = scene.camera;
        if (s_.schedule.snapshot()) ui::dolly_in(*s_.schedule.snapshot(), camera, factor, dolly_limit_);  // never inside an object
        else ui::dolly(camera, factor, dolly_limit_);
        move_camera(s_, camera);
      }
    }
  } else if (ImGui::IsMouseDown(s_.drag.button)) {
    if (!s_.drag.moved && ImGui::IsMouseDragging(s_.drag.button, kDragThreshold)) s_.drag.moved = true;
    const ImVec2 d = io.MouseDelta;
    // A grabbed light follows the pointer from the first pixel (an arrow at the edge brings the
    // light into view at once); the camera waits for the drag threshold, so a click stays a click.
    const bool grabbed = s_.drag.mode == DragMode::kLight || s_.drag.mode == DragMode::kObject || s_.drag.mode == DragMode::kWipe;
    const bool moving = (s_.drag.moved || grabbed) && (d.x != 0 || d.y != 0);
    if (moving) drag_viewport(mouse, d, view, view_w, view_h);
  } else {
    if (s_.drag.mode == DragMode::kOrbit && !s_.drag.moved) {
      // Plain click selects a material (as before); Ctrl+click, or any click in probe mode, probes.
      if (s_.instruments.probe_mode || io.KeyCtrl) tools_.probe_at(s_.drag.start);
      else pick(s_.drag.start);
    }
    s_.drag = Drag{};
  }
  // Moving the wipe's line changes what is shown of two finished images, not what is rendered.
  s_.interacting = s_.drag.mode != DragMode::kNone && s_.drag.mode != DragMode::kWipe &&
                 (s_.drag.moved || s_.drag.mode == DragMode::kLight || s_.drag.mode == DragMode::kObject);
  handle_keys();
}

void Viewer::drag_viewport(ImVec2 mouse, ImVec2 delta, const Camera& view, int view_w, int view_h) {
  const Scene& scene = s_.session.scene();
  Camera camera = scene.camera;
  const double per_px = kOrbitRadPerPixel / s_.platform.ui_scale();
  switch (s_.drag.mode) {
    case DragMode::kOrbit:
      // The scene follows the hand: drag right, it turns right; drag down, it is seen from higher up.
      ui::orbit_in(scene, camera, -delta.x * per_px, delta.y * per_px);  // never under the floor
      move_camera(s_, camera);
      break;
    case DragMode::kPan: {
      Camera moved = view;  // the fitted field of view sets how far a pixel goes
      ui::pan(moved, delta.x, delta.y, s_.viewport.height);
      camera.position = moved.position;
      camera.look_at = moved.look_at;
      move_camera(s_, camera);
      break;
    }
    case DragMode::kDolly:
      if (s_.schedule.snapshot()) ui::dolly_in(*s_.schedule.snapshot(), camera, std::exp(delta.y * kDollyPerPixel / s_.platform.ui_scale()), dolly_limit_);
      else ui::dolly(camera, std::exp(delta.y * kDollyPerPixel / s_.platform.ui_scale()), dolly_limit_);
      move_camera(s_, camera);
      break;
    case DragMode::kLight:
      if (s_.drag.light >= 0 && s_.drag.light < static_cast<int>(scene.lights.size()) && s_.drag.light_depth > 0) {
        const ui::ViewportPoint at{mouse.x - s_.viewport.x, mouse.y - s_.viewport.y};
        // Kept to float precision, as every value the panels edit: a saved file reads 1.8074448,
        // not 1.8074447666598992.
        const Vec3 p = ui::unproject(view, at, s_.drag.light_depth, view_w, view_h);
        Light light = scene.lights[static_cast<std::size_t>(s_.drag.light)];
        light.position = Vec3(ui::tidy_float(p.x), ui::tidy_float(p.y), ui::tidy_float(p.z));
        apply_edit(s_, {edit::SetLight{s_.drag.light, light}, true});  // one undo step when the drag ends
      }
      break;
    case DragMode::kObject:
      drag_object_to(mouse, view_w, view_h);
      break;
    case DragMode::kWipe:
      s_.instruments.wipe = std::clamp((mouse.x - s_.viewport.x) / std::max(s_.viewport.width, 1.0f), 0.0f, 1.0f);
      s_.upload_pending = s_.upload_pending || !s_.shown.pixels.empty();
      break;
    case DragMode::kNone:
      break;
  }
}

void Viewer::handle_keys() {
  const ImGuiIO& io = ImGui::GetIO();
  for (const std::string& path : s_.platform.take_drops()) builder_.drop_file(path);
  // Presses come from GLFW's key events, not from the key state once per frame: a tap shorter
  // than a frame still counts. A text field being edited keeps its keys.
  for (const KeyPress& press : s_.platform.take_key_presses()) {
    if (io.WantTextInput) continue;
    const bool ctrl = (press.mods & GLFW_MOD_CONTROL) != 0;
    const bool shift = (press.mods & GLFW_MOD_SHIFT) != 0;
    if (ctrl) {
      // Ctrl+Z is also a text field's own undo: taken only when no field has the keyboard.
      if (press.key == GLFW_KEY_Z) shift ? builder_.redo() : builder_.undo();
      if (press.key == GLFW_KEY_Y) builder_.redo();
      if (press.key == GLFW_KEY_O) files_.browser().open(false, s_.doc.file_path());
      // Ctrl+Q quits as the window's close button does: unsaved edits are asked about first.
      if (press.key == GLFW_KEY_Q) files_.request(FileShell::PendingAction{FileShell::PendingAction::Kind::kQuit, {}});
      if (press.key == GLFW_KEY_S) {
        // Ctrl+S saves the document's file; with none to save to (an embedded scene, an OBJ), or
        // with Shift, it asks where.
        if (shift || !files_.flow().can_save()) files_.browser().open(true, s_.doc.file_path());
        else files_.save_scene(false);
      }
      continue;
    }
    if (press.key == GLFW_KEY_F1 || (press.key == GLFW_KEY_SLASH && shift)) {
      s_.help_visible = !s_.help_visible;
      continue;
    }
    if (press.key == GLFW_KEY_ESCAPE && s_.help_visible) {
      s_.help_visible = false;
      continue;
    }
    if (lesson_shell_.lesson_key(press.key)) continue;  // a presentation remote's keys step through the lesson
    if (io.WantCaptureKeyboard && !s_.help_visible) continue;  // a widget is active
    shortcut(press.key, shift);
  }
}

void Viewer::shortcut(int key, bool shift) {
  const Scene& scene = s_.session.scene();
  if (key >= GLFW_KEY_1 && key <= GLFW_KEY_9) {
    const int digit = key - GLFW_KEY_1;  // 0 for the key 1
    if (shift) {
      // Shift+1..9: solo light L0..L8 (again: end the solo).
      if (digit < static_cast<int>(scene.lights.size())) {
        Scene soloed = scene;
        ui::toggle_solo(soloed.lights, s_.solo, digit);
        s_.selected_light = digit;
        apply_edit(s_, {edit::SetScene{std::move(soloed)}});
      }
    } else if (digit < static_cast<int>(kShortcutTerms.size())) {
      // 1 the full image, 2..6 its terms in the order of the equation. On a lesson's compare
      // step the step is shown again with that term, A too: the difference follows the view.
      const Term term = kShortcutTerms[static_cast<std::size_t>(digit)];
      if (s_.lessons.lesson() && !s_.lessons.awaiting_a() && term != s_.render_settings.term) {
        if (const std::optional<LessonPresenter::Show> show = s_.lessons.show_term(term)) {
          lesson_shell_.present(*show);
          return;
        }
      }
      if (s_.render_settings.term != kShortcutTerms[static_cast<std::size_t>(digit)]) {
        s_.render_settings.term = kShortcutTerms[static_cast<std::size_t>(digit)];
        s_.edits.settings = true;
      }
    }
    return;
  }
  switch (key) {
    case GLFW_KEY_F: s_.edits.frame_requested = true; break;
    case GLFW_KEY_R: s_.edits.reset_requested = true; break;
    case GLFW_KEY_H: s_.sidebar_visible = !s_.sidebar_visible; ++s_.sidebar_toggles; break;
    case GLFW_KEY_L: s_.display.light_markers = !s_.display.light_markers; break;  // the lights' markers
    case GLFW_KEY_M:
      s_.instruments.small_multiples = !s_.instruments.small_multiples;
      s_.edits.settings = true;
      break;
    case GLFW_KEY_I: {  // what ambient stands in for: the next view (Shift: the previous)
      const int n = static_cast<int>(ui::AmbientView::kDifference) + 1;
      const int next = (static_cast<int>(s_.render_settings.ambient_view) + (shift ? n - 1 : 1)) % n;
      s_.render_settings.ambient_view = static_cast<ui::AmbientView>(next);
      if (next >= static_cast<int>(ui::AmbientView::kBeside)) s_.instruments.small_multiples = false;
      s_.edits.settings = true;
      break;
    }
    default: break;
  }
}

std::optional<Hit> Viewer::hit_at(ImVec2 mouse) const {
  if (!s_.schedule.snapshot()) return std::nullopt;
  const int w = std::max(1, static_cast<int>(std::lround(s_.viewport.width)));
  const int h = std::max(1, static_cast<int>(std::lround(s_.viewport.height)));
  const double x = mouse.x - s_.viewport.x;
  const double y = mouse.y - s_.viewport.y;
  const int px = std::clamp(static_cast<int>(std::floor(x)), 0, w - 1);
  const int py = std::clamp(static_cast<int>(std::floor(y)), 0, h - 1);
  // The same camera formula as the renderer, through the clicked point of the pixel.
  const CameraFrame frame = make_camera_frame(view_camera(s_), w, h);
  return intersect(*s_.schedule.snapshot(), camera_ray(frame, px, py, std::clamp(x - px, 0.0, 1.0), std::clamp(y - py, 0.0, 1.0)));
}

std::optional<int> Viewer::object_under(ImVec2 mouse) const {
  const std::optional<Hit> hit = hit_at(mouse);
  if (!hit) return std::nullopt;
  return ui::file_object_of(s_.schedule.snapshot()->scene(), hit->object);
}

void Viewer::pick(ImVec2 mouse) {
  if (!s_.schedule.snapshot()) return;
  const std::optional<Hit> hit = hit_at(mouse);
  if (!hit) {
    s_.picked_text = "the background";
    s_.selected_object = -1;
    return;
  }
  const Scene& scene = s_.schedule.snapshot()->scene();
  s_.selected_material = hit->material;
  s_.selected_object = ui::file_object_of(scene, hit->object);
  s_.open_materials = true;
  std::ostringstream text;
  // The probe's naming: "objects[i]", and a mesh's OBJ face.
  text << object_kind_name(hit->object.kind) << " " << object_name(scene, hit->object);
  if (hit->material >= 0 && hit->material < static_cast<int>(scene.materials.size())) {
    text << ", material '" << scene.materials[static_cast<std::size_t>(hit->material)].name << "'";
  }
  s_.picked_text = text.str();
}

void Viewer::drag_object_to(ImVec2 mouse, int view_w, int view_h) {
  const Camera view = view_camera(s_);
  const Scene& scene = s_.doc.scene();
  const ui::ViewportPoint at{mouse.x - s_.viewport.x, mouse.y - s_.viewport.y};
  const Vec3 start = s_.drag.object_start;
  const Vec3 grab = start - s_.drag.grab_offset;  // the point under the pointer when it was grabbed
  // Over the floor by default (its height kept), up and down with V held; X, Y or Z held: along
  // that world axis only; without a floor, in the view plane. Never under the floor
  // (ui::drag_over_floor).
  const std::optional<ui::Floor> floor = ui::find_floor(scene, view, s_.drag.object);
  int axis = -1;
  for (int a = 0; a < 3 && axis < 0; ++a) {
    if (ImGui::IsKeyDown(GLFW_KEY_X + a)) axis = a;
  }
  Vec3 target = start;
  if (floor && axis < 0) {
    const Vec3 dir = ui::unproject(view, at, 1, view_w, view_h) - view.position;
    const std::optional<Vec3> moved =
        ui::drag_over_floor(scene, s_.drag.object, *floor, start, grab, view.position, dir, ImGui::IsKeyDown(GLFW_KEY_V));
    if (!moved) return;  // the pointer above the horizon: the object stays where it was
    target = *moved;
  } else {
    target = ui::unproject(view, at, s_.drag.object_depth, view_w, view_h) + s_.drag.grab_offset;
    if (axis >= 0) {
      const double along = target[axis] - start[axis];
      target = start;
      target[axis] += along;
    }
    if (floor) target = ui::keep_above_floor(scene, s_.drag.object, *floor, start, target);
  }
  // Kept to float precision where it moved (a saved file reads 1.8074448, not 1.8074447666598992);
  // a coordinate it kept (to rounding: 0, not -3.5e-15), as it was.
  const double noise = 1e-9 * std::max(1.0, glm::length(grab - view.position));
  for (int a = 0; a < 3; ++a) {
    target[a] = std::abs(target[a] - start[a]) <= noise ? start[a] : ui::tidy_float(target[a]);
  }
  const Vec3 delta = target - ui::object_anchor(scene, s_.drag.object);
  if (delta == Vec3(0)) return;
  const bool mesh = ui::object_at(scene, s_.drag.object).kind == ObjectRef::Kind::kMesh;
  builder_.edit_scene([&](Scene& s) { return ui::move_object(s, s_.drag.object, delta); }, mesh);
}

bool Viewer::grab_object(ImVec2 mouse, const std::optional<int>& hit_object) {
  if (s_.selected_object < 0) return false;
  const std::optional<ImVec2> marker = builder_.object_screen_point(s_.selected_object);
  const float grab = ui::light_marker_radius(s_.platform.ui_scale()) * kMarkerGrabFactor;
  const bool on_marker = marker && (marker->x - mouse.x) * (marker->x - mouse.x) + (marker->y - mouse.y) * (marker->y - mouse.y) <= grab * grab;
  if (!on_marker && hit_object != s_.selected_object) return false;
  const Camera view = view_camera(s_);
  const Vec3 anchor = ui::object_anchor(s_.doc.scene(), s_.selected_object);
  const int w = std::max(1, static_cast<int>(std::lround(s_.viewport.width)));
  const int h = std::max(1, static_cast<int>(std::lround(s_.viewport.height)));
  s_.drag.mode = DragMode::kObject;
  s_.drag.object = s_.selected_object;
  s_.drag.object_depth = ui::view_depth(view, anchor);
  if (!(s_.drag.object_depth > 0)) {
    s_.drag.mode = DragMode::kNone;
    return false;
  }
  s_.drag.object_start = anchor;
  s_.drag.grab_offset = anchor - ui::unproject(view, ui::ViewportPoint{mouse.x - s_.viewport.x, mouse.y - s_.viewport.y},
                                             s_.drag.object_depth, w, h);
  return true;
}

}  // namespace phonglab
