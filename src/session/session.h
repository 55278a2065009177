// The previewer's document and the rules of editing it, without a window: the scene and its
// file (SceneDocument), edits taken as values, undo and redo one gesture at a time, the unsaved
// state, and what each edit invalidates in the last image. The shell (apps/previewer) turns
// input into edits and shows what the session holds; tests/session drives it directly.
// No GLFW, ImGui or GL (the layering test says so).
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "core/render/ray_trees.h"
#include "core/scene/scene.h"
#include "interaction/history.h"
#include "session/document.h"
#include "session/formula_book.h"
#include "session/lesson_presenter.h"
#include "session/recovery_keeper.h"

namespace phonglab {

// An edit as a value: what the panels, the mouse, a lesson step or a script change.
namespace edit {
struct SetMaterial {  // material `index` becomes `value` (a coefficient slider, a preset)
  int index = 0;
  Material value;
};
struct SetLight {  // light `index` becomes `value` (its panel, a drag of its marker, mute)
  int index = 0;
  Light value;
};
struct SetCamera {  // navigation: restarts the image, not an unsaved change
  Camera value;
};
struct SetScene {  // anything else: objects built, materials added or removed, the shading panel
  Scene value;
};
}  // namespace edit

struct Edit {
  std::variant<edit::SetMaterial, edit::SetLight, edit::SetCamera, edit::SetScene> change;
  // Part of a gesture still under way (a slider held, a drag): the gesture's edits become one
  // undo step when it ends (Session::settle).
  bool held = false;
};

// What apply() did.
struct Applied {
  bool changed = false;                   // the scene differs from before
  EditScope scope = EditScope::kNothing;  // what the change invalidates in the last image
  bool unsaved = false;                   // it counts as an unsaved change (navigation does not)
};

class Session {
 public:
  // `recovery_folder`: where unsaved edits are kept (RecoveryKeeper; empty: nowhere).
  explicit Session(std::string recovery_folder = RecoveryKeeper::default_folder())
      : recovery_(std::move(recovery_folder)) {}

  // The document: open (an embedded scene's name or a file), read again, or a scene adopted
  // (a lesson's step). Each success starts the undo history anew; a failure keeps everything.
  bool open(const std::string& scene_arg);
  bool reload(bool keep_view);
  void adopt(const Scene& scene, const std::string& source);

  // An edit. An index out of range changes nothing (changed = false).
  Applied apply(const Edit& edit);
  // Once a UI frame: while no gesture holds them, the pending edits become one undo step.
  void settle(bool gesture_held);
  // The undo history starts anew from the scene as it is (a document replaced from outside).
  void reset_history();

  // The scene before the last undo step (or after the last undone one), keeping the camera:
  // navigation is not an edit. A gesture still under way becomes the step undone. False when
  // there is none.
  bool undo();
  bool redo();
  std::size_t undo_count() const { return history_.undo_count() + formula_undo_.size(); }
  std::size_t redo_count() const { return redo_order_.size(); }
  bool edit_pending() const { return pending_; }  // edits wait for their gesture to end

  const Scene& scene() const { return document_.scene(); }
  SceneDocument& document() { return document_; }
  const SceneDocument& document() const { return document_; }
  bool dirty() const { return document_.dirty(); }
  RecoveryKeeper& recovery() { return recovery_; }
  const RecoveryKeeper& recovery() const { return recovery_; }
  // The student's formulas (docs/formulas.md). A text is an edit with undo, as a scene edit is
  // (one step per finished gesture: `held` while the text box is being typed in). True when what
  // renders changed (the snapshot must follow: formulas().version()).
  bool set_formula(FormulaSlot slot, const std::string& text, bool held = false);
  // Every slot's text at once (a formula file opened): one undo step.
  bool set_formulas(const FormulaBook::Texts& texts);
  const FormulaBook& formulas() const { return formulas_; }
  // A lesson's exercise step (docs/lessons.md), for the desktop and the page alike: once the
  // presenter shows another place, the exercise left keeps its text for a return and the
  // formulas are cleared; the exercise entered gets its starter (or the text left there) in its
  // slot. True when an exercise was entered. The step shown's exercise, its hints shown so far.
  bool sync_exercise();
  const LessonExercise* exercise() const;
  int hints_shown() const { return hints_shown_; }
  bool show_hint();  // one more of the exercise's hints; false when none is left
  // The lesson being presented (its steps' scenes are adopted into the document by the shell).
  LessonPresenter& lessons() { return lessons_; }
  const LessonPresenter& lessons() const { return lessons_; }

 private:
  void edited();  // dirty again, and an undo step pending
  // Which history each undo step is in, oldest first (scene edits and formula texts interleave).
  enum class Step : std::uint8_t { kScene, kFormulas };
  std::vector<Step> undo_order_, redo_order_;
  FormulaBook formulas_;
  FormulaBook::Texts formulas_committed_{};
  std::vector<FormulaBook::Texts> formula_undo_, formula_redo_;
  bool formula_pending_ = false;
  int exercise_step_ = -1;                       // the exercise step whose slot holds the student's text
  int hints_shown_ = 0;
  FormulaSlot exercise_slot_ = FormulaSlot::kAmbient;  // ... and its slot (the lesson may be gone on leaving)
  std::map<int, std::string> exercise_texts_;          // per exercise step: the text left there
  void settle_formulas();

  SceneDocument document_;
  ui::SceneHistory history_;
  bool pending_ = false;
  RecoveryKeeper recovery_;
  LessonPresenter lessons_;
};

}  // namespace phonglab
