// The previewer's file actions: open, reload, save (with the unsaved-changes guard and the check for changes made on disk), and screenshots.
#include "apps/previewer/viewer_app.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <thread>

#include <backends/imgui_impl_opengl3.h>

#include "core/scene/camera.h"
#include "io/figure.h"
#include "core/geometry/geometry.h"
#include "core/teaching/heat_map.h"
#include "io/image_io.h"
#include "io/probe_report.h"
#include "core/teaching/ray_tree_view.h"
#include "core/shading/shading.h"
#include "interaction/camera_control.h"


namespace phonglab {

void Viewer::request(PendingAction action) {
  doc_.update_dirty();  // edits made earlier in this frame count
  if (!doc_.dirty()) {
    perform(action);
    return;
  }
  pending_ = std::move(action);
  open_guard_ = true;
}

void Viewer::perform(const PendingAction& action) {
  switch (action.kind) {
    case PendingAction::Kind::kQuit: quit_ = true; break;
    case PendingAction::Kind::kOpen: open_scene(action.arg); break;
    case PendingAction::Kind::kReload: reload_scene(false); break;
    case PendingAction::Kind::kNone: break;
  }
}

void Viewer::handle_guard_modal() {
  ui::GuardView view;
  view.action = "quit";
  if (pending_.kind == PendingAction::Kind::kOpen) view.action = "open " + pending_.arg;
  if (pending_.kind == PendingAction::Kind::kReload) view.action = "reload the file";
  view.can_save = !doc_.file_path().empty() && !doc_.opened_mesh();
  view.changed_on_disk = !doc_.file_path().empty() && doc_.changed_on_disk();
  const ui::GuardChoice choice = ui::unsaved_changes_modal(open_guard_, view, file_state_.path_field, scripted_choice_);
  if (open_guard_) guard_visible_ = true;
  open_guard_ = false;
  if (guard_visible_) scripted_choice_ = ui::GuardChoice::kNone;
  if (choice != ui::GuardChoice::kNone) {
    guard_visible_ = false;
    PendingAction pending = std::move(pending_);
    pending_ = PendingAction{};
    if (choice == ui::GuardChoice::kSave || choice == ui::GuardChoice::kSaveAs) {
      // A save that meets an outside change asks first; the action waits for that answer.
      after_save_ = std::move(pending);
      save_scene(choice == ui::GuardChoice::kSaveAs);
    } else if (choice == ui::GuardChoice::kDiscard) {
      perform(pending);
    }
  }
  handle_conflict_modal();
}

void Viewer::handle_conflict_modal() {
  const ui::GuardChoice choice = ui::changed_on_disk_modal(open_conflict_, doc_.file_path(), scripted_choice_);
  if (open_conflict_) conflict_visible_ = true;
  open_conflict_ = false;
  if (conflict_visible_) scripted_choice_ = ui::GuardChoice::kNone;
  if (choice == ui::GuardChoice::kNone) return;
  conflict_visible_ = false;
  PendingAction after = std::move(after_save_);
  after_save_ = PendingAction{};
  if (choice == ui::GuardChoice::kOverwrite) {
    if (finish_save(doc_.save(true))) perform(after);
  } else if (choice == ui::GuardChoice::kReload) {
    reload_scene(false);  // the edits go, the file's version comes
    if (after.kind != PendingAction::Kind::kReload) perform(after);
  }
}

void Viewer::open_scene(const std::string& scene_arg) {
  if (scene_arg.empty()) {
    file_state_.error_text = "Open: type a scene file path or an embedded scene name into the path field";
    return;
  }
  if (!doc_.open(scene_arg)) {
    file_state_.error_text = doc_.error_text();  // the old scene stays
    return;
  }
  file_state_.error_text.clear();
  file_state_.status = doc_.status();
  file_state_.changed_on_disk = false;
  file_state_.path_field = doc_.file_path().empty() ? scene_arg : doc_.file_path();
  selected_material_ = 0;
  selected_light_ = doc_.scene().lights.empty() ? -1 : 0;
  picked_text_.clear();
  probe_.reset();
  // A belongs to the scene it was taken of (a reload of the same file keeps it: before and after).
  image_a_ = ProgressiveFrame{};
  a_requested_ = a_dropped_ = false;
  instruments_.compare = 0;
  drag_ = Drag{};
  scene_replaced_ = true;
}

void Viewer::reload_scene(bool keep_view) {
  if (!doc_.reload(keep_view)) {
    file_state_.error_text = doc_.error_text();
    return;
  }
  file_state_.error_text.clear();
  file_state_.status = doc_.status();
  file_state_.changed_on_disk = false;
  const int materials = static_cast<int>(doc_.scene().materials.size());
  selected_material_ = std::clamp(selected_material_, 0, std::max(materials - 1, 0));
  if (selected_light_ >= static_cast<int>(doc_.scene().lights.size())) selected_light_ = -1;
  drag_ = Drag{};
  scene_replaced_ = true;
}

void Viewer::save_scene(bool as) {
  if (as) {
    const bool ok = doc_.save_as(file_state_.path_field);
    if (finish_save(ok ? SceneDocument::SaveResult::kSaved : SceneDocument::SaveResult::kFailed)) {
      perform(after_save_);
    }
    after_save_ = PendingAction{};
    return;
  }
  const SceneDocument::SaveResult result = doc_.save();
  if (result == SceneDocument::SaveResult::kChangedOnDisk) {
    open_conflict_ = true;  // the answer decides; after_save_ waits for it
    return;
  }
  if (finish_save(result)) perform(after_save_);
  after_save_ = PendingAction{};
}

bool Viewer::finish_save(SceneDocument::SaveResult result) {
  if (result != SceneDocument::SaveResult::kSaved) {
    file_state_.error_text = doc_.error_text();
    return false;
  }
  file_state_.error_text.clear();
  file_state_.status = doc_.status();
  file_state_.changed_on_disk = false;
  return true;
}

bool Viewer::begin_screenshot(Image& image) {
  if (shown_.pixels.empty()) {
    screenshot_state_.status = "no image yet";
    return false;
  }
  image.width = shown_.width;
  image.height = shown_.height;
  return true;
}

void Viewer::save_png(const std::string& path) {
  Image image;
  if (!begin_screenshot(image)) return;
  image.pixels.reserve(shown_.pixels.size());
  // The heat map is written as shown: its colours, without exposure.
  const bool heat = heat_shown();
  const std::vector<glm::vec3> source = heat ? display_pixels() : shown_.pixels;
  const float exposure = heat ? 1.0f : std::exp2(display_.exposure_ev);
  for (const glm::vec3& p : source) {
    glm::vec3 v = glm::clamp(p * exposure, 0.0f, 1.0f);
    // Linear display shows the values themselves as 8-bit codes: pre-decode them so the
    // sRGB encoder of write_image gives those codes back.
    if (!display_.srgb) {
      for (int c = 0; c < 3; ++c) v[c] = static_cast<float>(srgb_to_linear(v[c]));
    }
    image.pixels.push_back(v);
  }
  write_screenshot(path, image, "");
}

void Viewer::save_pfm(const std::string& path) {
  Image image;
  if (!begin_screenshot(image)) return;
  image.pixels = shown_.pixels;
  write_screenshot(path, image, "linear, ");
}

void Viewer::write_screenshot(const std::string& path, const Image& image, const char* kind) {
  const std::string error = write_image(path, image);
  std::ostringstream status;
  if (error.empty()) {
    status << "saved " << path << " (" << kind << image.width << "x" << image.height << ", " << shown_.spp << " spp)";
  } else {
    status << error;
  }
  screenshot_state_.status = status.str();
}

void Viewer::save_window_screenshot(const std::string& path, int fb_width, int fb_height) {
  const std::vector<unsigned char> rgb = read_framebuffer_rgb8(fb_width, fb_height);
  Image image;
  image.width = fb_width;
  image.height = fb_height;
  image.pixels.resize(static_cast<std::size_t>(fb_width) * static_cast<std::size_t>(fb_height));
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      image.pixels[i][c] = static_cast<float>(srgb_to_linear(rgb[i * 3 + static_cast<std::size_t>(c)] / 255.0));
    }
  }
  const std::string error = write_image(path, image);
  if (!error.empty()) {
    std::cerr << "phonglab: screenshot: " << error << "\n";
    script_failed_ = true;
    quit_ = true;
  }
}

}  // namespace phonglab
