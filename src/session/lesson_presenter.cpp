#include "session/lesson_presenter.h"

#include <algorithm>

namespace phonglab {

std::optional<LessonPresenter::Show> LessonPresenter::start() {
  if (!waiting_) return std::nullopt;
  lesson_ = std::move(waiting_);
  waiting_.reset();
  scene_step_ = -1;
  exploring_ = false;
  return show({0, false});
}

void LessonPresenter::close() {
  lesson_.reset();
  scene_step_ = -1;
  stage_ = Stage::kNone;
  exploring_ = false;
}

LessonPresenter::Show LessonPresenter::show(LessonPlace place) { return show_place(place, std::nullopt); }

StepView LessonPresenter::with_term(StepView view) const {
  if (term_) view.term = *term_;
  return view;
}

std::optional<LessonPresenter::Show> LessonPresenter::show_term(Term term) {
  if (!lesson_) return std::nullopt;
  const StepView& view = view_at(lesson_->steps[static_cast<std::size_t>(place_.step)], place_.revealed);
  if (view.compare == CompareView::kNone || view.small_multiples) return std::nullopt;
  Show out = show_place(place_, term);
  exploring_ = true;
  return out;
}

LessonPresenter::Show LessonPresenter::show_place(LessonPlace place, std::optional<Term> term) {
  term_ = term;
  Show out;
  if (!lesson_) return out;
  const Lesson& lesson = *lesson_;
  place.step = std::clamp(place.step, 0, static_cast<int>(lesson.steps.size()) - 1);
  place.revealed = place.revealed && lesson.steps[static_cast<std::size_t>(place.step)].has_question();
  place_ = place;
  const StepView& view = view_at(lesson.steps[static_cast<std::size_t>(place.step)], place.revealed);
  const CompareSource source = compare_source(lesson, place.step, view);
  const bool compare = view.compare != CompareView::kNone && !view.small_multiples;
  const int scene_step = compare ? source.step : place.step;
  // Revealing an answer keeps the scene (its trees re-shade a view change at once), unless
  // exploring changed it; a compare shows its source first, for A.
  if (scene_step != scene_step_ || exploring_ || compare) {
    out.adopt_step = scene_step;
    scene_step_ = scene_step;
  }
  out.view = view_ = with_term(compare ? source.view : view);
  stage_ = compare ? Stage::kRequestA : Stage::kNone;
  exploring_ = false;
  return out;
}

std::optional<LessonPresenter::Show> LessonPresenter::next() {
  if (!lesson_) return std::nullopt;
  const LessonPlace next = lesson_next(*lesson_, place_);
  if (next == place_ && !exploring_) return std::nullopt;
  return show(next);
}

std::optional<LessonPresenter::Show> LessonPresenter::prev() {
  if (!lesson_) return std::nullopt;
  const LessonPlace prev = lesson_prev(*lesson_, place_);
  if (prev == place_ && !exploring_) return std::nullopt;
  return show(prev);
}

bool LessonPresenter::take_a_now() {
  if (stage_ != Stage::kRequestA) return false;
  stage_ = Stage::kTakingA;
  return true;
}

std::optional<LessonPresenter::Show> LessonPresenter::a_taken() {
  if (stage_ != Stage::kTakingA || !lesson_) return std::nullopt;
  stage_ = Stage::kNone;
  Show out;
  if (scene_step_ != place_.step) {
    out.adopt_step = place_.step;
    scene_step_ = place_.step;
  }
  out.view = view_ = with_term(view_at(lesson_->steps[static_cast<std::size_t>(place_.step)], place_.revealed));
  out.compare = true;
  return out;
}

}  // namespace phonglab
