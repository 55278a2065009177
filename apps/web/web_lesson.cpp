// A lesson in the web page: the session's LessonPresenter says what to show (a step's scene, its
// view, a compare's source view first for A); this applies it as the desktop's LessonShell does.
#include <cstdio>

#include <nlohmann/json.hpp>

#include "apps/web/web_lesson.h"
#include "io/lesson_io.h"
#include "io/probe_report.h"

namespace phonglab {

std::string WebLesson::open_lesson(const std::string& name) {
  LessonLoad loaded = load_lesson_arg(name);
  if (!loaded.ok()) return loaded.error_text();
  s_.session.lessons().offer(std::move(*loaded.lesson));
  if (const auto show = s_.session.lessons().start()) present(*show);
  return "";
}

bool WebLesson::lesson_next() {
  const auto show = s_.session.lessons().next();
  if (show) present(*show);
  return show.has_value();
}

bool WebLesson::lesson_prev() {
  const auto show = s_.session.lessons().prev();
  if (show) present(*show);
  return show.has_value();
}

bool WebLesson::lesson_show(int step) {
  if (!s_.session.lessons().lesson()) return false;
  present(s_.session.lessons().show({step, false}));
  return true;
}

void WebLesson::close_lesson() {
  s_.session.lessons().close();
  s_.a.clear();
  s_.view = StepView{};
  s_.view_probe.clear();
  if (s_.session.formulas().any()) {
    s_.session.sync_exercise();  // an exercise's formula goes with the lesson
    image_.restart();
  }
}

bool WebLesson::lesson_hint() { return s_.session.show_hint(); }

std::string WebLesson::lesson_state() const {
  const LessonPresenter& presenter = s_.session.lessons();
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
                      {"compare", s_.a.has_image() && s_.view.compare != CompareView::kNone}};
  if (step.exercise) {
    const int shown = std::min<int>(s_.session.hints_shown(), static_cast<int>(step.exercise->hints.size()));
    j["exercise"] = {{"slot", step.exercise->slot},
                     {"task", step.exercise->task},
                     {"hints", std::vector<std::string>(step.exercise->hints.begin(), step.exercise->hints.begin() + shown)},
                     {"hints_left", static_cast<int>(step.exercise->hints.size()) - shown}};
  }
  return j.dump();
}

// What the presenter answers for a place: A cleared, the step's scene adopted when it asks, its
// view applied (a compare's source view first, for A).
void WebLesson::present(const LessonPresenter::Show& show) {
  s_.a.clear();
  if (show.adopt_step) adopt_step(*show.adopt_step);
  apply_view(show.view);
  s_.session.sync_exercise();  // an exercise step's starter in its slot, the formulas cleared elsewhere
  image_.restart();
  if (s_.session.lessons().take_a_now()) s_.a.request(static_cast<std::uint64_t>(s_.generation), true);
}

void WebLesson::adopt_step(int index) {
  const Lesson& lesson = *s_.session.lessons().lesson();
  const LessonStep& step = lesson.steps[static_cast<std::size_t>(index)];
  char source[512];
  std::snprintf(source, sizeof source, "lesson '%s', step %d: %s", lesson.name.c_str(), index + 1, step.scene.c_str());
  s_.session.adopt(step.prepared_scene, source);
  s_.step_scene = step.scene;
}

void WebLesson::apply_view(const StepView& view) {
  s_.view = view;
  s_.view.compare = CompareView::kNone;  // on once A is taken (update_lesson)
  s_.view_probe.clear();
  s_.tree_pixel.reset();
  s_.probe_pixel.reset();
  if (view.probe) {
    const PreparedScene prepared(view_scene(s_.session.scene(), view));
    if (const auto pixel = probe_in(s_.session.scene(), s_.session.scene().camera, view, s_.width, s_.height)) {
      s_.probe_pixel = pixel;  // marked while the question is asked too
      if (view.ray_tree) s_.tree_pixel = pixel;
      const std::optional<Vec3> eye = view_shading_eye(prepared, view, s_.width, s_.height);
      s_.view_probe = probe_to_text(s_.session.scene(), probe_pixel(prepared, s_.width, s_.height, (*pixel)[0], (*pixel)[1], eye), 4);
    }
  }
  image_.restart();
}

// A compare: A is the source view's first full-resolution image; then the step's own view with
// the compare on.
void WebLesson::update_lesson() {
  if (!s_.a.requested() || !s_.a.first_full() || s_.view.small_multiples) return;
  if (!s_.a.take_when_ready(static_cast<std::uint64_t>(s_.generation), s_.shown, image_.finished())) return;
  if (const auto show = s_.session.lessons().a_taken()) {
    if (show->adopt_step) adopt_step(*show->adopt_step);
    apply_view(show->view);
    s_.view.compare = show->view.compare;
  }
}

void WebLesson::edited_by_hand() {
  // Anything changed by hand while a step is shown leaves it as written: exploring; an A under
  // way no longer names the image it was asked of.
  if (!s_.session.lessons().lesson()) return;
  s_.session.lessons().explored();
  if (s_.a.requested() && s_.a.first_full()) {
    s_.a.clear();
    s_.session.lessons().a_dropped();
  }
}

}  // namespace phonglab
