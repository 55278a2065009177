// The lesson being presented: where it stands (step, answer revealed, exploring), which step's
// scene the document holds, the view shown, and the order of a compare (A is taken of the
// compare's source first, then the step itself is shown). The rules of showing a step live here
// once; the shell applies what they answer (adopts the scene, sets the instruments, takes A).
#pragma once

#include <cstdint>
#include <optional>

#include "core/teaching/lesson.h"

namespace phonglab {

class LessonPresenter {
 public:
  // What the shell does to show a place.
  struct Show {
    std::optional<int> adopt_step;  // the document takes this step's prepared scene
    StepView view;                  // the view to apply now (a compare's source view while A is taken)
    bool compare = false;           // the view's compare against A is on (A has been taken)
  };

  // A lesson opened: it waits until the shell has asked about unsaved edits.
  void offer(Lesson lesson) { waiting_ = std::move(lesson); }
  const Lesson* waiting() const { return waiting_ ? &*waiting_ : nullptr; }
  // The waiting lesson becomes the lesson, at its first step; nothing without one.
  std::optional<Show> start();
  void close();

  const Lesson* lesson() const { return lesson_ ? &*lesson_ : nullptr; }
  LessonPlace place() const { return place_; }
  const StepView& view() const { return view_; }  // the view shown
  int scene_step() const { return scene_step_; }  // the step whose scene the document holds (-1: none)
  bool exploring() const { return exploring_; }

  // Shows a place (clamped to the lesson): the step's scene unless the document holds it
  // already (an answer re-shades its view), or, for a compare, its source's scene and view first.
  Show show(LessonPlace place);
  // The presenter's keys: the answer, then the next step; back. Nothing when the place does not
  // change and nothing was explored.
  std::optional<Show> next();
  std::optional<Show> prev();
  // Anything changed by hand while a step is shown (not by the lesson itself).
  void explored() { exploring_ = true; }
  // A term key on a step whose view compares against A: the step shown again with that term in
  // its view and its compare's source (A taken anew of the same term), so the difference follows
  // what is shown; the step counts as explored. Nothing when the step shows no compare.
  std::optional<Show> show_term(Term term);

  // A compare's A: wanted once a compare's source is shown (take_a_now() answers true once),
  // then taken (a_taken(): the step's own view with the compare on) or dropped (something
  // changed first: the user is exploring).
  bool take_a_now();
  bool awaiting_a() const { return stage_ != Stage::kNone; }
  std::optional<Show> a_taken();
  void a_dropped() { stage_ = Stage::kNone; }

 private:
  enum class Stage : std::uint8_t { kNone, kRequestA, kTakingA };
  Show show_place(LessonPlace place, std::optional<Term> term);
  StepView with_term(StepView view) const;
  std::optional<Lesson> lesson_, waiting_;
  LessonPlace place_;
  StepView view_;
  int scene_step_ = -1;
  bool exploring_ = false;
  Stage stage_ = Stage::kNone;
  std::optional<Term> term_;  // show_term's term, in the views shown until the next show()
};

}  // namespace phonglab
