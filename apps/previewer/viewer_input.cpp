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
  const Scene& scene = session_.scene();
  const Camera view = view_camera();
  // Where each button went down, from GLFW's event: ImGui 1.86 polls the cursor once a frame, so
  // a press followed by a quick move in the same frame would otherwise start where the pointer
  // already moved to (and miss the light marker it was pressed on).
  const std::vector<MousePress> presses = platform_.take_mouse_presses();
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
  const bool over_viewport = ImGui::IsMousePosValid(&mouse) && mouse.x >= viewport_.x &&
                             mouse.x < viewport_.x + viewport_.width && mouse.y >= viewport_.y &&
                             mouse.y < viewport_.y + viewport_.height;
  const bool mouse_is_ours = over_viewport && !io.WantCaptureMouse && !help_visible_;
  const int view_w = std::max(1, static_cast<int>(std::lround(viewport_.width)));
  const int view_h = std::max(1, static_cast<int>(std::lround(viewport_.height)));

  // The point light whose marker is under the mouse, where it was drawn last frame (an arrow at
  // the edge for a light out of view): what the user sees is what the user grabs.
  hovered_light_ = -1;
  if (drag_.mode == DragMode::kNone && mouse_is_ours) {
    const float grab = ui::light_marker_radius(platform_.ui_scale()) * kMarkerGrabFactor;
    float best = grab * grab;
    for (const ui::LightMarker& marker : markers_) {
      const float dx = marker.pos.x - mouse.x;
      const float dy = marker.pos.y - mouse.y;
      if (dx * dx + dy * dy <= best) {
        best = dx * dx + dy * dy;
        hovered_light_ = marker.index;
      }
    }
  }

  // The wipe's split line, grabbed anywhere along its height.
  const std::optional<float> wipe_x = overlays_.wipe_line_x();
  const float wipe_grab = ui::light_marker_radius(platform_.ui_scale());
  const bool wipe_hovered = mouse_is_ours && hovered_light_ < 0 && wipe_x && std::abs(mouse.x - *wipe_x) <= wipe_grab;
  if (wipe_hovered || drag_.mode == DragMode::kWipe) ImGui::SetMouseCursor(ImGuiMouseCursor_ResizeEW);

  if (drag_.mode == DragMode::kNone) {
    if (mouse_is_ours) {
      for (int button = 0; button < 3; ++button) {
        if (!ImGui::IsMouseClicked(button)) continue;
        drag_ = Drag{};
        drag_.button = button;
        drag_.start = mouse;
        if (button == ImGuiMouseButton_Left && hovered_light_ >= 0 &&
            hovered_light_ < static_cast<int>(scene.lights.size())) {
          drag_.mode = DragMode::kLight;
          drag_.light = hovered_light_;
          drag_.light_depth = ui::view_depth(view, scene.lights[static_cast<std::size_t>(hovered_light_)].position);
          selected_light_ = hovered_light_;
        } else if (button == ImGuiMouseButton_Left && wipe_hovered) {
          drag_.mode = DragMode::kWipe;  // the split line follows the pointer
        } else if (button == ImGuiMouseButton_Left && !io.KeyShift && !io.KeyCtrl &&
                   grab_object(mouse, io.KeyAlt ? object_under(mouse) : std::nullopt)) {
          // The selected object, grabbed by its handle, or by its surface with Alt held: moved
          // over the floor. A plain drag on its surface orbits (a selected room is still the
          // room one orbits in), and Ctrl+click probes it.
        } else if (button == ImGuiMouseButton_Left) {
          drag_.mode = io.KeyShift ? DragMode::kPan : DragMode::kOrbit;
        } else {
          drag_.mode = button == ImGuiMouseButton_Right ? DragMode::kDolly : DragMode::kPan;
        }
        break;
      }
      if (io.MouseWheel != 0) {
        const double factor = std::pow(kDollyPerWheelClick, static_cast<double>(io.MouseWheel));
        Camera camera = scene.camera;
        if (schedule_.snapshot()) ui::dolly_in(*schedule_.snapshot(), camera, factor, dolly_limit_);  // never inside an object
        else ui::dolly(camera, factor, dolly_limit_);
        move_camera(camera);
      }
    }
  } else if (ImGui::IsMouseDown(drag_.button)) {
    if (!drag_.moved && ImGui::IsMouseDragging(drag_.button, kDragThreshold)) drag_.moved = true;
    const ImVec2 d = io.MouseDelta;
    // A grabbed light follows the pointer from the first pixel (an arrow at the edge brings the
    // light into view at once); the camera waits for the drag threshold, so a click stays a click.
    const bool grabbed = drag_.mode == DragMode::kLight || drag_.mode == DragMode::kObject || drag_.mode == DragMode::kWipe;
    const bool moving = (drag_.moved || grabbed) && (d.x != 0 || d.y != 0);
    if (moving) drag_viewport(mouse, d, view, view_w, view_h);
  } else {
    if (drag_.mode == DragMode::kOrbit && !drag_.moved) {
      // Plain click selects a material (as before); Ctrl+click, or any click in probe mode, probes.
      if (instruments_.probe_mode || io.KeyCtrl) tools_.probe_at(drag_.start);
      else pick(drag_.start);
    }
    drag_ = Drag{};
  }
  // Moving the wipe's line changes what is shown of two finished images, not what is rendered.
  interacting_ = drag_.mode != DragMode::kNone && drag_.mode != DragMode::kWipe &&
                 (drag_.moved || drag_.mode == DragMode::kLight || drag_.mode == DragMode::kObject);
  handle_keys();
}

void Viewer::drag_viewport(ImVec2 mouse, ImVec2 delta, const Camera& view, int view_w, int view_h) {
  const Scene& scene = session_.scene();
  Camera camera = scene.camera;
  const double per_px = kOrbitRadPerPixel / platform_.ui_scale();
  switch (drag_.mode) {
    case DragMode::kOrbit:
      // The scene follows the hand: drag right, it turns right; drag down, it is seen from higher up.
      ui::orbit_in(scene, camera, -delta.x * per_px, delta.y * per_px);  // never under the floor
      move_camera(camera);
      break;
    case DragMode::kPan: {
      Camera moved = view;  // the fitted field of view sets how far a pixel goes
      ui::pan(moved, delta.x, delta.y, viewport_.height);
      camera.position = moved.position;
      camera.look_at = moved.look_at;
      move_camera(camera);
      break;
    }
    case DragMode::kDolly:
      if (schedule_.snapshot()) ui::dolly_in(*schedule_.snapshot(), camera, std::exp(delta.y * kDollyPerPixel / platform_.ui_scale()), dolly_limit_);
      else ui::dolly(camera, std::exp(delta.y * kDollyPerPixel / platform_.ui_scale()), dolly_limit_);
      move_camera(camera);
      break;
    case DragMode::kLight:
      if (drag_.light >= 0 && drag_.light < static_cast<int>(scene.lights.size()) && drag_.light_depth > 0) {
        const ui::ViewportPoint at{mouse.x - viewport_.x, mouse.y - viewport_.y};
        // Kept to float precision, as every value the panels edit: a saved file reads 1.8074448,
        // not 1.8074447666598992.
        const Vec3 p = ui::unproject(view, at, drag_.light_depth, view_w, view_h);
        Light light = scene.lights[static_cast<std::size_t>(drag_.light)];
        light.position = Vec3(ui::tidy_float(p.x), ui::tidy_float(p.y), ui::tidy_float(p.z));
        apply_edit({edit::SetLight{drag_.light, light}, true});  // one undo step when the drag ends
      }
      break;
    case DragMode::kObject:
      drag_object_to(mouse, view_w, view_h);
      break;
    case DragMode::kWipe:
      instruments_.wipe = std::clamp((mouse.x - viewport_.x) / std::max(viewport_.width, 1.0f), 0.0f, 1.0f);
      upload_pending_ = upload_pending_ || !shown_.pixels.empty();
      break;
    case DragMode::kNone:
      break;
  }
}

void Viewer::move_camera(const Camera& camera) {
  session_.apply({edit::SetCamera{camera}});
  edits_.camera = true;
}

void Viewer::handle_keys() {
  const ImGuiIO& io = ImGui::GetIO();
  for (const std::string& path : platform_.take_drops()) builder_.drop_file(path);
  // Presses come from GLFW's key events, not from the key state once per frame: a tap shorter
  // than a frame still counts. A text field being edited keeps its keys.
  for (const KeyPress& press : platform_.take_key_presses()) {
    if (io.WantTextInput) continue;
    const bool ctrl = (press.mods & GLFW_MOD_CONTROL) != 0;
    const bool shift = (press.mods & GLFW_MOD_SHIFT) != 0;
    if (ctrl) {
      // Ctrl+Z is also a text field's own undo: taken only when no field has the keyboard.
      if (press.key == GLFW_KEY_Z) shift ? redo() : undo();
      if (press.key == GLFW_KEY_Y) redo();
      if (press.key == GLFW_KEY_O) files_.browser().open(false, doc_.file_path());
      // Ctrl+Q quits as the window's close button does: unsaved edits are asked about first.
      if (press.key == GLFW_KEY_Q) files_.request(FileShell::PendingAction{FileShell::PendingAction::Kind::kQuit, {}});
      if (press.key == GLFW_KEY_S) {
        // Ctrl+S saves the document's file; with none to save to (an embedded scene, an OBJ), or
        // with Shift, it asks where.
        const bool can_save = !doc_.file_path().empty() && !doc_.opened_mesh();
        if (shift || !can_save) files_.browser().open(true, doc_.file_path());
        else files_.save_scene(false);
      }
      continue;
    }
    if (press.key == GLFW_KEY_F1 || (press.key == GLFW_KEY_SLASH && shift)) {
      help_visible_ = !help_visible_;
      continue;
    }
    if (press.key == GLFW_KEY_ESCAPE && help_visible_) {
      help_visible_ = false;
      continue;
    }
    if (lesson_shell_.lesson_key(press.key)) continue;  // a presentation remote's keys step through the lesson
    if (io.WantCaptureKeyboard && !help_visible_) continue;  // a widget is active
    shortcut(press.key, shift);
  }
}

void Viewer::shortcut(int key, bool shift) {
  const Scene& scene = session_.scene();
  if (key >= GLFW_KEY_1 && key <= GLFW_KEY_9) {
    const int digit = key - GLFW_KEY_1;  // 0 for the key 1
    if (shift) {
      // Shift+1..9: solo light L0..L8 (again: end the solo).
      if (digit < static_cast<int>(scene.lights.size())) {
        Scene soloed = scene;
        ui::toggle_solo(soloed.lights, solo_, digit);
        selected_light_ = digit;
        apply_edit({edit::SetScene{std::move(soloed)}});
      }
    } else if (digit < static_cast<int>(kShortcutTerms.size())) {
      // 1 the full image, 2..6 its terms in the order of the equation. On a lesson's compare
      // step the step is shown again with that term, A too: the difference follows the view.
      const Term term = kShortcutTerms[static_cast<std::size_t>(digit)];
      if (lessons_.lesson() && !lessons_.awaiting_a() && term != render_settings_.term) {
        if (const std::optional<LessonPresenter::Show> show = lessons_.show_term(term)) {
          lesson_shell_.present(*show);
          return;
        }
      }
      if (render_settings_.term != kShortcutTerms[static_cast<std::size_t>(digit)]) {
        render_settings_.term = kShortcutTerms[static_cast<std::size_t>(digit)];
        edits_.settings = true;
      }
    }
    return;
  }
  switch (key) {
    case GLFW_KEY_F: edits_.frame_requested = true; break;
    case GLFW_KEY_R: edits_.reset_requested = true; break;
    case GLFW_KEY_H: sidebar_visible_ = !sidebar_visible_; ++sidebar_toggles_; break;
    case GLFW_KEY_L: display_.light_markers = !display_.light_markers; break;  // the lights' markers
    case GLFW_KEY_M:
      instruments_.small_multiples = !instruments_.small_multiples;
      edits_.settings = true;
      break;
    case GLFW_KEY_I: {  // what ambient stands in for: the next view (Shift: the previous)
      const int n = static_cast<int>(ui::AmbientView::kDifference) + 1;
      const int next = (static_cast<int>(render_settings_.ambient_view) + (shift ? n - 1 : 1)) % n;
      render_settings_.ambient_view = static_cast<ui::AmbientView>(next);
      if (next >= static_cast<int>(ui::AmbientView::kBeside)) instruments_.small_multiples = false;
      edits_.settings = true;
      break;
    }
    default: break;
  }
}

std::optional<Hit> Viewer::hit_at(ImVec2 mouse) const {
  if (!schedule_.snapshot()) return std::nullopt;
  const int w = std::max(1, static_cast<int>(std::lround(viewport_.width)));
  const int h = std::max(1, static_cast<int>(std::lround(viewport_.height)));
  const double x = mouse.x - viewport_.x;
  const double y = mouse.y - viewport_.y;
  const int px = std::clamp(static_cast<int>(std::floor(x)), 0, w - 1);
  const int py = std::clamp(static_cast<int>(std::floor(y)), 0, h - 1);
  // The same camera formula as the renderer, through the clicked point of the pixel.
  const CameraFrame frame = make_camera_frame(view_camera(), w, h);
  return intersect(*schedule_.snapshot(), camera_ray(frame, px, py, std::clamp(x - px, 0.0, 1.0), std::clamp(y - py, 0.0, 1.0)));
}

std::optional<int> Viewer::object_under(ImVec2 mouse) const {
  const std::optional<Hit> hit = hit_at(mouse);
  if (!hit) return std::nullopt;
  return ui::file_object_of(schedule_.snapshot()->scene(), hit->object);
}

void Viewer::pick(ImVec2 mouse) {
  if (!schedule_.snapshot()) return;
  const std::optional<Hit> hit = hit_at(mouse);
  if (!hit) {
    picked_text_ = "the background";
    selected_object_ = -1;
    return;
  }
  const Scene& scene = schedule_.snapshot()->scene();
  selected_material_ = hit->material;
  selected_object_ = ui::file_object_of(scene, hit->object);
  open_materials_ = true;
  std::ostringstream text;
  // The probe's naming: "objects[i]", and a mesh's OBJ face.
  text << object_kind_name(hit->object.kind) << " " << object_name(scene, hit->object);
  if (hit->material >= 0 && hit->material < static_cast<int>(scene.materials.size())) {
    text << ", material '" << scene.materials[static_cast<std::size_t>(hit->material)].name << "'";
  }
  picked_text_ = text.str();
}

void Viewer::drag_object_to(ImVec2 mouse, int view_w, int view_h) {
  const Camera view = view_camera();
  const Scene& scene = doc_.scene();
  const ui::ViewportPoint at{mouse.x - viewport_.x, mouse.y - viewport_.y};
  const Vec3 start = drag_.object_start;
  const Vec3 grab = start - drag_.grab_offset;  // the point under the pointer when it was grabbed
  // Over the floor by default (its height kept), up and down with V held; X, Y or Z held: along
  // that world axis only; without a floor, in the view plane. Never under the floor
  // (ui::drag_over_floor).
  const std::optional<ui::Floor> floor = ui::find_floor(scene, view, drag_.object);
  int axis = -1;
  for (int a = 0; a < 3 && axis < 0; ++a) {
    if (ImGui::IsKeyDown(GLFW_KEY_X + a)) axis = a;
  }
  Vec3 target = start;
  if (floor && axis < 0) {
    const Vec3 dir = ui::unproject(view, at, 1, view_w, view_h) - view.position;
    const std::optional<Vec3> moved =
        ui::drag_over_floor(scene, drag_.object, *floor, start, grab, view.position, dir, ImGui::IsKeyDown(GLFW_KEY_V));
    if (!moved) return;  // the pointer above the horizon: the object stays where it was
    target = *moved;
  } else {
    target = ui::unproject(view, at, drag_.object_depth, view_w, view_h) + drag_.grab_offset;
    if (axis >= 0) {
      const double along = target[axis] - start[axis];
      target = start;
      target[axis] += along;
    }
    if (floor) target = ui::keep_above_floor(scene, drag_.object, *floor, start, target);
  }
  // Kept to float precision where it moved (a saved file reads 1.8074448, not 1.8074447666598992);
  // a coordinate it kept (to rounding: 0, not -3.5e-15), as it was.
  const double noise = 1e-9 * std::max(1.0, glm::length(grab - view.position));
  for (int a = 0; a < 3; ++a) {
    target[a] = std::abs(target[a] - start[a]) <= noise ? start[a] : ui::tidy_float(target[a]);
  }
  const Vec3 delta = target - ui::object_anchor(scene, drag_.object);
  if (delta == Vec3(0)) return;
  const bool mesh = ui::object_at(scene, drag_.object).kind == ObjectRef::Kind::kMesh;
  builder_.edit_scene([&](Scene& s) { return ui::move_object(s, drag_.object, delta); }, mesh);
}

bool Viewer::grab_object(ImVec2 mouse, const std::optional<int>& hit_object) {
  if (selected_object_ < 0) return false;
  const std::optional<ImVec2> marker = builder_.object_screen_point(selected_object_);
  const float grab = ui::light_marker_radius(platform_.ui_scale()) * kMarkerGrabFactor;
  const bool on_marker = marker && (marker->x - mouse.x) * (marker->x - mouse.x) + (marker->y - mouse.y) * (marker->y - mouse.y) <= grab * grab;
  if (!on_marker && hit_object != selected_object_) return false;
  const Camera view = view_camera();
  const Vec3 anchor = ui::object_anchor(doc_.scene(), selected_object_);
  const int w = std::max(1, static_cast<int>(std::lround(viewport_.width)));
  const int h = std::max(1, static_cast<int>(std::lround(viewport_.height)));
  drag_.mode = DragMode::kObject;
  drag_.object = selected_object_;
  drag_.object_depth = ui::view_depth(view, anchor);
  if (!(drag_.object_depth > 0)) {
    drag_.mode = DragMode::kNone;
    return false;
  }
  drag_.object_start = anchor;
  drag_.grab_offset = anchor - ui::unproject(view, ui::ViewportPoint{mouse.x - viewport_.x, mouse.y - viewport_.y},
                                             drag_.object_depth, w, h);
  return true;
}

}  // namespace phonglab
