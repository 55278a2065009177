// The previewer's file actions: open, reload, save (with the unsaved-changes guard and the check for changes made on disk), and screenshots.
#include "apps/previewer/file_shell.h"

#include "apps/previewer/viewer_app.h"
#include "interaction/recovery.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
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
#include "io/scene/scene_io.h"
#include "core/teaching/ray_tree_view.h"
#include "core/shading/shading.h"
#include "interaction/camera_control.h"


namespace phonglab {

FileShell::FileShell(ShellState& shell, LessonShell& lesson_shell, Instruments& tools)
    : s_(shell), lesson_shell_(lesson_shell), tools_(tools), flow_(shell.doc) {}

void FileShell::request(FileShell::PendingAction action) { carry_out(flow_.request(std::move(action))); }

void FileShell::perform(const FileShell::PendingAction& action) {
  switch (action.kind) {
    case FileShell::PendingAction::Kind::kQuit: s_.quit = true; break;
    case FileShell::PendingAction::Kind::kOpen: open_scene(action.arg); break;
    case FileShell::PendingAction::Kind::kReload: reload_scene(false); break;
    case FileShell::PendingAction::Kind::kLesson: lesson_shell_.start_lesson(); break;
    case FileShell::PendingAction::Kind::kNone: break;
  }
}

void FileShell::carry_out(FileFlow::Outcome outcome) {
  if (outcome.reload) reload_scene(false);  // the edits go, the file's version comes
  if (outcome.saved) report_save(*outcome.saved);
  perform(outcome.run);
}

namespace {

FileFlow::Answer flow_answer(ui::GuardChoice choice) {
  switch (choice) {
    case ui::GuardChoice::kSave: return FileFlow::Answer::kSave;
    case ui::GuardChoice::kSaveAs: return FileFlow::Answer::kSaveAs;
    case ui::GuardChoice::kDiscard: return FileFlow::Answer::kDiscard;
    case ui::GuardChoice::kOverwrite: return FileFlow::Answer::kOverwrite;
    case ui::GuardChoice::kReload: return FileFlow::Answer::kReload;
    case ui::GuardChoice::kCancel:
    case ui::GuardChoice::kNone: break;
  }
  return FileFlow::Answer::kCancel;
}

}  // namespace

void FileShell::handle_guard_modal() {
  using Kind = FileShell::PendingAction::Kind;
  const FileShell::PendingAction& waiting = flow_.waiting();
  ui::GuardView view;
  view.action = "quit";
  if (waiting.kind == Kind::kOpen) view.action = "open " + waiting.arg;
  if (waiting.kind == Kind::kReload) view.action = "reload the file";
  if (waiting.kind == Kind::kLesson) view.action = "open the lesson " + waiting.arg;
  view.can_save = flow_.can_save();
  view.changed_on_disk = flow_.file_changed();
  const bool open_now = flow_.question() == FileFlow::Question::kUnsavedChanges && !guard_visible();
  const ui::GuardChoice choice = ui::unsaved_changes_modal(open_now, view, file_state_.path_field);
  if (open_now) shown_ = FileFlow::Question::kUnsavedChanges;
  if (choice != ui::GuardChoice::kNone) {
    shown_ = FileFlow::Question::kNone;
    // A save that meets an outside change asks first; the action waits for that answer.
    carry_out(flow_.answer(flow_answer(choice), file_state_.path_field));
  }
  handle_conflict_modal();
  handle_file_browser();
}

void FileShell::handle_conflict_modal() {
  const bool open_now = flow_.question() == FileFlow::Question::kChangedOnDisk && !conflict_visible();
  const ui::GuardChoice choice = ui::changed_on_disk_modal(open_now, s_.doc.file_path());
  if (open_now) shown_ = FileFlow::Question::kChangedOnDisk;
  if (choice == ui::GuardChoice::kNone) return;
  shown_ = FileFlow::Question::kNone;
  carry_out(flow_.answer(flow_answer(choice), file_state_.path_field));
}

void FileShell::poll_file() {
  switch (flow_.poll(file_state_.auto_reload)) {
    case FileFlow::OnDisk::kNothing: file_state_.changed_on_disk = false; break;
    case FileFlow::OnDisk::kKeepEdits: file_state_.changed_on_disk = true; break;  // never throw away edits silently
    case FileFlow::OnDisk::kReload: reload_scene(true); break;
  }
}

void FileShell::open_scene(const std::string& scene_arg) {
  if (scene_arg.empty()) {
    file_state_.error_text = "Open: type a scene file path or an embedded scene name into the path field";
    return;
  }
  if (!s_.doc.open(scene_arg)) {
    file_state_.error_text = s_.doc.error_text();  // the old scene stays
    return;
  }
  document_replaced();
  if (!s_.doc.file_path().empty()) browser_.remember(s_.doc.file_path());
  file_state_.path_field = s_.doc.file_path().empty() ? scene_arg : s_.doc.file_path();
  tools_.probe().tree.reset();
  // A belongs to the scene it was taken of (a reload of the same file keeps it: before and after).
  tools_.compare().clear();
  s_.instruments.compare = 0;
}

void FileShell::document_replaced() {
  s_.session.recovery().remove();  // the guard was passed: the last document's edits were saved or discarded
  file_state_.error_text.clear();
  file_state_.status = s_.doc.status();
  file_state_.changed_on_disk = false;
  s_.selected_object = -1;
  s_.selected_material = 0;
  s_.selected_light = s_.doc.scene().lights.empty() ? -1 : 0;
  s_.picked_text.clear();
  s_.drag = Drag{};
  s_.edits.replaced = true;
}

void FileShell::reload_scene(bool keep_view) {
  if (!s_.doc.reload(keep_view)) {
    file_state_.error_text = s_.doc.error_text();
    return;
  }
  s_.session.recovery().remove();  // reloading discarded the edits (the guard asked first)
  file_state_.error_text.clear();
  file_state_.status = s_.doc.status();
  file_state_.changed_on_disk = false;
  s_.selected_object = -1;
  const int materials = static_cast<int>(s_.doc.scene().materials.size());
  s_.selected_material = std::clamp(s_.selected_material, 0, std::max(materials - 1, 0));
  if (s_.selected_light >= static_cast<int>(s_.doc.scene().lights.size())) s_.selected_light = -1;
  s_.drag = Drag{};
  s_.edits.replaced = true;
}

void FileShell::save_scene(bool as) { carry_out(flow_.save(as, file_state_.path_field)); }

void FileShell::report_save(bool wrote) {
  if (!wrote) {
    file_state_.error_text = s_.doc.error_text();
    return;
  }
  browser_.remember(s_.doc.file_path());
  file_state_.error_text.clear();
  file_state_.status = s_.doc.status();
  file_state_.changed_on_disk = false;
}

bool FileShell::begin_screenshot(Image& image) {
  if (s_.shown.pixels.empty()) {
    screenshot_state_.status = "no image yet";
    return false;
  }
  image.width = s_.shown.width;
  image.height = s_.shown.height;
  return true;
}

void FileShell::save_png(const std::string& path) {
  Image image;
  if (!begin_screenshot(image)) return;
  image.pixels.reserve(s_.shown.pixels.size());
  // The heat map is written as shown: its colours, without exposure.
  const bool heat = tools_.heat_shown();
  const std::vector<glm::vec3> source = heat ? tools_.display_pixels() : s_.shown.pixels;
  const float exposure = heat ? 1.0f : std::exp2(s_.display.exposure_ev);
  for (const glm::vec3& p : source) {
    glm::vec3 v = glm::clamp(p * exposure, 0.0f, 1.0f);
    // Linear display shows the values themselves as 8-bit codes: pre-decode them so the
    // sRGB encoder of write_image gives those codes back.
    if (!s_.display.srgb) {
      for (int c = 0; c < 3; ++c) v[c] = static_cast<float>(srgb_to_linear(v[c]));
    }
    image.pixels.push_back(v);
  }
  write_screenshot(path, image, "");
}

void FileShell::save_pfm(const std::string& path) {
  Image image;
  if (!begin_screenshot(image)) return;
  image.pixels = s_.shown.pixels;
  write_screenshot(path, image, "linear, ");
}

void FileShell::write_screenshot(const std::string& path, const Image& image, const char* kind) {
  const std::string error = write_image(path, image);
  std::ostringstream status;
  if (error.empty()) {
    status << "saved " << path << " (" << kind << image.width << "x" << image.height << ", " << s_.shown.spp << " spp)";
  } else {
    status << error;
  }
  screenshot_state_.status = status.str();
}

bool FileShell::save_window_screenshot(const std::string& path, const std::vector<unsigned char>& rgb, int fb_width,
                                       int fb_height) {
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
    s_.quit = true;
    return false;
  }
  return true;
}

void FileShell::handle_file_browser() {
  const FileBrowser::Choice choice = browser_.draw();
  using Kind = FileBrowser::Choice::Kind;
  if (choice.kind == Kind::kOpen) {
    request(FileShell::PendingAction{FileShell::PendingAction::Kind::kOpen, choice.path});  // through the unsaved-changes guard
  } else if (choice.kind == Kind::kSaveAs) {
    file_state_.path_field = choice.path;
    save_scene(true);
  }
}

}  // namespace phonglab
