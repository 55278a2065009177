#include "session/session.h"

#include "interaction/scene_objects.h"

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
  Scene& scene = document_.edited_scene();
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
  ui::own_edited_mtl_materials(before, scene);  // an MTL material's edit is saved like any other
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


void Session::edited() {
  document_.update_dirty();
  pending_ = true;
}

void Session::settle(bool gesture_held) {
  if (gesture_held) return;
  settle_formulas();
  if (!pending_) return;
  history_.commit(document_.scene());
  undo_order_.push_back(Step::kScene);
  redo_order_.clear();
  pending_ = false;
}

void Session::reset_history() {
  history_.reset(document_.scene());
  pending_ = false;
  // The formulas stay with a new scene (a student tries theirs on several); their undo steps
  // stay, the scene's are gone.
  std::erase(undo_order_, Step::kScene);
  std::erase(redo_order_, Step::kScene);
}

bool Session::set_formula(FormulaSlot slot, const std::string& text, bool held) {
  const bool changed = formulas_.set(slot, text);
  if (formulas_.texts() != formulas_committed_) formula_pending_ = true;
  if (!held) settle_formulas();
  return changed;
}

bool Session::set_formulas(const FormulaBook::Texts& texts) {
  settle_formulas();
  const bool changed = formulas_.set_all(texts);
  if (formulas_.texts() != formulas_committed_) formula_pending_ = true;
  settle_formulas();
  return changed;
}

void Session::settle_formulas() {
  if (!formula_pending_) return;
  formula_pending_ = false;
  const FormulaBook::Texts now = formulas_.texts();
  if (now == formulas_committed_) return;
  formula_undo_.push_back(formulas_committed_);
  formula_redo_.clear();
  formulas_committed_ = now;
  undo_order_.push_back(Step::kFormulas);
  redo_order_.clear();
}

const LessonExercise* Session::exercise() const {
  const Lesson* lesson = lessons_.lesson();
  if (lesson == nullptr) return nullptr;
  const LessonStep& step = lesson->steps[static_cast<std::size_t>(lessons_.place().step)];
  return step.exercise ? &*step.exercise : nullptr;
}

bool Session::show_hint() {
  const LessonExercise* e = exercise();
  if (e == nullptr || hints_shown_ >= static_cast<int>(e->hints.size())) return false;
  ++hints_shown_;
  return true;
}

bool Session::sync_exercise() {
  const LessonExercise* e = exercise();
  const int step = e ? lessons_.place().step : -1;
  if (step == exercise_step_) return false;
  if (exercise_step_ >= 0) exercise_texts_[exercise_step_] = formulas_.slot(exercise_slot_).text;
  if (exercise_step_ >= 0 || e) {
    for (int s = 0; s < kFormulaSlots; ++s) set_formula(static_cast<FormulaSlot>(s), "");
  }
  hints_shown_ = 0;
  const std::optional<FormulaSlot> slot = e ? formula_slot_from_name(e->slot) : std::nullopt;
  exercise_step_ = slot ? step : -1;  // the reader refuses any other slot's name
  if (!slot) return false;
  exercise_slot_ = *slot;
  const auto kept = exercise_texts_.find(step);
  set_formula(*slot, kept != exercise_texts_.end() ? kept->second : e->starter);
  return true;
}

bool Session::undo() {
  settle(false);  // a gesture still under way becomes the step undone
  while (!undo_order_.empty()) {
    const Step step = undo_order_.back();
    undo_order_.pop_back();
    if (step == Step::kFormulas) {
      if (formula_undo_.empty()) continue;
      formula_redo_.push_back(formulas_committed_);
      formulas_committed_ = formula_undo_.back();
      formula_undo_.pop_back();
      formulas_.set_all(formulas_committed_);
      redo_order_.push_back(step);
      return true;
    }
    std::optional<Scene> scene = history_.undo(document_.scene());
    if (!scene) continue;  // beyond the scene history's bound
    document_.edited_scene() = std::move(*scene);
    document_.update_dirty();
    redo_order_.push_back(step);
    return true;
  }
  return false;
}

bool Session::redo() {
  while (!redo_order_.empty()) {
    const Step step = redo_order_.back();
    redo_order_.pop_back();
    if (step == Step::kFormulas) {
      if (formula_redo_.empty()) continue;
      formula_undo_.push_back(formulas_committed_);
      formulas_committed_ = formula_redo_.back();
      formula_redo_.pop_back();
      formulas_.set_all(formulas_committed_);
      undo_order_.push_back(step);
      return true;
    }
    std::optional<Scene> scene = history_.redo(document_.scene());
    if (!scene) continue;
    document_.edited_scene() = std::move(*scene);
    document_.update_dirty();
    undo_order_.push_back(step);
    return true;
  }
  return false;
}

}  // namespace phonglab
