// A lesson in the web page: the session's LessonPresenter says what to show (a step's scene, its
// view, a compare's source view first for A); this applies it as the desktop's LessonShell does.
#pragma once

#include <string>

#include "apps/web/page_state.h"

namespace phonglab {

class WebLesson {
 public:
  WebLesson(PageState& state, PageImage& image) : s_(state), image_(image) {}
  WebLesson(const WebLesson&) = delete;
  WebLesson& operator=(const WebLesson&) = delete;

  // An embedded lesson's name: "" or its errors; the presenter's keys; where it stands as JSON
  // (title, step, steps, caption, question, revealed, exploring).
  std::string open_lesson(const std::string& name);
  bool lesson_next();
  bool lesson_prev();
  bool lesson_show(int step);
  void close_lesson();
  std::string lesson_state() const;
  bool lesson_hint();  // the exercise's next hint (lesson_state's "hints"); false when none is left
  std::string view_probe() const { return s_.view_probe; }  // the step's probed pixel's numbers
  // Anything changed by hand while a step is shown leaves it as written (exploring).
  void edited_by_hand();
  // After each image: a compare step's A taken from its source view's first full image, then
  // the step's own view.
  void update_lesson();

 private:
  void present(const LessonPresenter::Show& show);
  void adopt_step(int index);  // the document takes a lesson step's scene
  void apply_view(const StepView& view);

  PageState& s_;
  PageImage& image_;
};

}  // namespace phonglab
