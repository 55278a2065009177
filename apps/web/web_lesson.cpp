// A lesson in the web page: the session's LessonPresenter says what to show (a step's scene, its
// view, a compare's source view first for A); this applies it as the desktop's LessonShell does.
#include <cstdio>

#include <nlohmann/json.hpp>

#include "apps/web/web_view.h"
#include "io/lesson_io.h"
#include "io/probe_report.h"

namespace phonglab {

std::string WebView::open_lesson(const std::string& name) {
  LessonLoad loaded = load_lesson_arg(name);
  if (!loaded.ok()) return loaded.error_text();
  session_.lessons().offer(std::move(*loaded.lesson));
  if (const auto show = session_.lessons().start()) present(*show);
  return "";
}

bool WebView::lesson_next() {
  const auto show = session_.lessons().next();
  if (show) present(*show);
  return show.has_value();
}

bool WebView::lesson_prev() {
  const auto show = session_.lessons().prev();
  if (show) present(*show);
  return show.has_value();
}

bool WebView::lesson_show(int step) {
  if (!session_.lessons().lesson()) return false;
  present(session_.lessons().show({step, false}));
  return true;
}

void WebView::close_lesson() {
  session_.lessons().close();
  a_.clear();
  view_ = StepView{};
  view_probe_.clear();
  if (session_.formulas().any()) {
    session_.sync_exercise();  // an exercise's formula goes with the lesson
    restart();
  }
}

bool WebView::lesson_hint() { return session_.show_hint(); }

std::string WebView::lesson_state() const {
  const LessonPresenter& presenter = session_.lessons();
  const Lesson* lesson = presenter.lesson();
  if (!lesson) return "{}";
  const LessonPlace place = presenter.place();
  const LessonStep& step = lesson->steps[static_cast<std::size_t>(place.step)];
  nlohmann::json j = {{"lesson", lesson->name},
                      {"title", lesson->title},
                      {"step", place.step},
                      {"steps", lesson->steps.size()},
                      {"step_title", step.title},
                      {"caption", caption_at(step, place.revealed)},
                      {"question", step.question},
                      {"revealed", place.revealed},
                      {"exploring", presenter.exploring()},
                      {"compare", a_.has_image() && view_.compare != CompareView::kNone}};
  if (step.exercise) {
    const int shown = std::min<int>(session_.hints_shown(), static_cast<int>(step.exercise->hints.size()));
    j["exercise"] = {{"slot", step.exercise->slot},
                     {"task", step.exercise->task},
                     {"hints", std::vector<std::string>(step.exercise->hints.begin(), step.exercise->hints.begin() + shown)},
                     {"hints_left", static_cast<int>(step.exercise->hints.size()) - shown}};
  }
  return j.dump();
}

// What the presenter answers for a place: A cleared, the step's scene adopted when it asks, its
// view applied (a compare's source view first, for A).
void WebView::present(const LessonPresenter::Show& show) {
  a_.clear();
  if (show.adopt_step) adopt_step(*show.adopt_step);
  apply_view(show.view);
  session_.sync_exercise();  // an exercise step's starter in its slot, the formulas cleared elsewhere
  restart();
  if (session_.lessons().take_a_now()) a_.request(static_cast<std::uint64_t>(generation_), true);
}

void WebView::adopt_step(int index) {
  const Lesson& lesson = *session_.lessons().lesson();
  const LessonStep& step = lesson.steps[static_cast<std::size_t>(index)];
  char source[512];
  std::snprintf(source, sizeof source, "lesson '%s', step %d: %s", lesson.name.c_str(), index + 1, step.scene.c_str());
  session_.adopt(step.prepared_scene, source);
  step_scene_ = step.scene;
}

void WebView::apply_view(const StepView& view) {
  view_ = view;
  view_.compare = CompareView::kNone;  // on once A is taken (update_lesson)
  view_probe_.clear();
  tree_pixel_.reset();
  probe_pixel_.reset();
  if (view.probe) {
    const PreparedScene prepared(view_scene(session_.scene(), view));
    if (const auto pixel = probe_in(session_.scene(), session_.scene().camera, view, width_, height_)) {
      probe_pixel_ = pixel;  // marked while the question is asked too
      if (view.ray_tree) tree_pixel_ = pixel;
      const std::optional<Vec3> eye = view_shading_eye(prepared, view, width_, height_);
      view_probe_ = probe_to_text(session_.scene(), probe_pixel(prepared, width_, height_, (*pixel)[0], (*pixel)[1], eye), 4);
    }
  }
  restart();
}

// A compare: A is the source view's first full-resolution image; then the step's own view with
// the compare on.
void WebView::update_lesson() {
  if (!a_.requested() || !a_.first_full() || view_.small_multiples) return;
  if (!a_.take_when_ready(static_cast<std::uint64_t>(generation_), shown_, finished())) return;
  if (const auto show = session_.lessons().a_taken()) {
    if (show->adopt_step) adopt_step(*show->adopt_step);
    apply_view(show->view);
    view_.compare = show->view.compare;
  }
}

void WebView::edited_by_hand() {
  // Anything changed by hand while a step is shown leaves it as written: exploring; an A under
  // way no longer names the image it was asked of.
  if (!session_.lessons().lesson()) return;
  session_.lessons().explored();
  if (a_.requested() && a_.first_full()) {
    a_.clear();
    session_.lessons().a_dropped();
  }
}

}  // namespace phonglab
