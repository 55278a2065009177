#include "session/session.h"

#include <type_traits>
#include <utility>

namespace phonglab {

namespace {

template <class T>
bool in_range(int index, const std::vector<T>& v) {
  return index >= 0 && static_cast<std::size_t>(index) < v.size();
}

}  // namespace

bool Session::open(const std::string& scene_arg) {
  if (!document_.open(scene_arg)) return false;
  reset_history();
  return true;
}

bool Session::reload(bool keep_view) {
  if (!document_.reload(keep_view)) return false;
  reset_history();
  return true;
}

void Session::adopt(const Scene& scene, const std::string& source) {
  document_.adopt(scene, source);
  reset_history();
}

Applied Session::apply(const Edit& e) {
  Scene& scene = document_.scene();
  const Scene before = scene;
  bool valid = true, navigation = false;
  std::visit(
      [&](const auto& change) {
        using T = std::decay_t<decltype(change)>;
        if constexpr (std::is_same_v<T, edit::SetMaterial>) {
          valid = in_range(change.index, scene.materials);
          if (valid) scene.materials[static_cast<std::size_t>(change.index)] = change.value;
        } else if constexpr (std::is_same_v<T, edit::SetLight>) {
          valid = in_range(change.index, scene.lights);
          if (valid) scene.lights[static_cast<std::size_t>(change.index)] = change.value;
        } else if constexpr (std::is_same_v<T, edit::SetCamera>) {
          scene.camera = change.value;
          navigation = true;
        } else {
          scene = change.value;
        }
      },
      e.change);
  if (!valid) return {};
  Applied applied;
  applied.scope = edit_scope(before, scene);
  // A rename changes no pixel but the file; navigation changes pixels but not the file.
  const std::string content = navigation ? std::string() : scene_content(scene);
  applied.unsaved = !navigation && scene_content(before) != content;
  applied.changed = applied.scope != EditScope::kNothing || applied.unsaved;
  if (!applied.unsaved) return applied;  // navigation, or nothing: no undo step, none settled
  document_.update_dirty(content);
  pending_ = true;
  if (!e.held) settle(false);
  return applied;
}

void Session::edited_in_place() { edited(); }

void Session::edited() {
  document_.update_dirty();
  pending_ = true;
}

void Session::settle(bool gesture_held) {
  if (!pending_ || gesture_held) return;
  history_.commit(document_.scene());
  pending_ = false;
}

void Session::reset_history() {
  history_.reset(document_.scene());
  pending_ = false;
}

bool Session::undo() {
  settle(false);  // a gesture still under way becomes the step undone
  std::optional<Scene> step = history_.undo(document_.scene());
  if (!step) return false;
  document_.scene() = std::move(*step);
  document_.update_dirty();
  return true;
}

bool Session::redo() {
  std::optional<Scene> step = history_.redo(document_.scene());
  if (!step) return false;
  document_.scene() = std::move(*step);
  document_.update_dirty();
  return true;
}

}  // namespace phonglab
