// Undo and redo of scene edits, and per-light solo. Plain data, no ImGui, no GL: header-only
// so the tests use it without linking the UI.
#pragma once

#include <cstddef>
#include <deque>
#include <optional>
#include <vector>

#include "core/scene/scene.h"

namespace phonglab::ui {

// A bounded history of committed scene states. The app commits once per finished edit (a
// slider released, a light drag ended, a checkbox clicked), so one Ctrl+Z undoes one gesture.
// Undo and redo keep the current camera: navigation is not an edit (docs/previewer.md, Files).
class SceneHistory {
 public:
  static constexpr std::size_t kMaxStates = 100;  // oldest states drop off beyond this

  // Forgets everything; `scene` is the state edits start from (after open or reload).
  void reset(const Scene& scene) {
    undo_.clear();
    redo_.clear();
    committed_ = scene;
  }
  // Records `scene` as the result of one edit: the previous state becomes undoable.
  void commit(const Scene& scene) {
    undo_.push_back(committed_);
    if (undo_.size() > kMaxStates) undo_.pop_front();
    redo_.clear();
    committed_ = scene;
  }
  // The state before the last commit, with `current`'s camera; nullopt when there is none.
  std::optional<Scene> undo(const Scene& current) {
    if (undo_.empty()) return std::nullopt;
    redo_.push_back(committed_);
    committed_ = undo_.back();
    undo_.pop_back();
    committed_.camera = current.camera;
    return committed_;
  }
  // The state the last undo left, with `current`'s camera; nullopt when there is none.
  std::optional<Scene> redo(const Scene& current) {
    if (redo_.empty()) return std::nullopt;
    undo_.push_back(committed_);
    committed_ = redo_.back();
    redo_.pop_back();
    committed_.camera = current.camera;
    return committed_;
  }
  std::size_t undo_count() const { return undo_.size(); }
  std::size_t redo_count() const { return redo_.size(); }

 private:
  std::deque<Scene> undo_;  // oldest first
  std::deque<Scene> redo_;  // most recently undone last
  Scene committed_;         // the state after the last commit, undo or redo
};

// Solo: one light on, the others off, and their previous enabled flags kept to restore.
struct LightSolo {
  int soloed = -1;             // index of the soloed light, -1 when none
  std::vector<bool> saved;     // each light's enabled flag before the solo
};

// Solos light `index`, or ends the solo when it is the soloed one (restoring every flag).
// Soloing another light while one is soloed moves the solo and keeps the original flags.
inline void toggle_solo(std::vector<Light>& lights, LightSolo& solo, int index) {
  if (index < 0 || index >= static_cast<int>(lights.size())) return;
  if (solo.soloed == index) {
    for (std::size_t i = 0; i < lights.size() && i < solo.saved.size(); ++i) lights[i].enabled = solo.saved[i];
    solo = LightSolo{};
    return;
  }
  if (solo.soloed < 0) {
    solo.saved.clear();
    for (const Light& light : lights) solo.saved.push_back(light.enabled);
  }
  solo.soloed = index;
  for (std::size_t i = 0; i < lights.size(); ++i) lights[i].enabled = static_cast<int>(i) == index;
}

}  // namespace phonglab::ui
