// Lessons in the previewer: a lesson's steps shown as written (scene, term, instruments, probe,
// head, depth cut, compare against A), next and previous from the keys a presentation remote
// sends, presenter mode, exploring and the way back, the caption over the image, and the
// lesson script commands.
#include "apps/previewer/lesson_shell.h"

#include "apps/previewer/viewer_app.h"

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <ostream>

#include "apps/previewer/script_words.h"
#include "io/lesson_io.h"
#include "ui/overlay.h"
#include "ui/widgets.h"

namespace phonglab {

std::string LessonShell::open_lesson(const std::string& lesson_arg) {
  LessonLoad load = load_lesson_arg(lesson_arg);
  if (!load.ok()) {
    state_.error = load.error_text();
    std::cerr << "phonglab: " << state_.error << "\n";
    return state_.error;
  }
  state_.error.clear();
  s_.lessons.offer(std::move(*load.lesson));
  // A lesson replaces the scene: unsaved edits of a file are asked about first; a lesson's own
  // explorations are not (they were never anyone's file).
  const FileShell::PendingAction action{FileShell::PendingAction::Kind::kLesson, s_.lessons.waiting()->name};
  if (s_.lessons.lesson()) files_.perform(action);
  else files_.request(action);
  return "";
}

void LessonShell::start_lesson() {
  const std::optional<LessonPresenter::Show> show = s_.lessons.start();
  if (!show) return;
  state_.unfold_panel = true;
  present(*show);
}

void LessonShell::close_lesson() {
  s_.lessons.close();
  sync_exercise();
  set_presenting(false);
  if (files_.recovery().after_lesson) {
    files_.recovery().after_lesson = false;
    files_.find_recovery();
  }
}

void LessonShell::adopt_step_scene(int step) {
  const Lesson& lesson = *s_.lessons.lesson();
  char source[512];
  std::snprintf(source, sizeof source, "lesson '%s', step %d: %s", lesson.name.c_str(), step + 1,
                lesson.steps[static_cast<std::size_t>(step)].scene.c_str());
  s_.doc.adopt(lesson.steps[static_cast<std::size_t>(step)].prepared_scene, source);
  files_.document_replaced();  // the probe and A are the step view's (apply_step_view, the compare stages)
}

void LessonShell::apply_step_view(const StepView& view) {
  s_.render_settings.term = view.term;
  s_.render_settings.ambient_view = view.ambient != Ambient::kIndirect                 ? ui::AmbientView::kConstant
                                     : view.ambient_shown == AmbientShown::kBeside     ? ui::AmbientView::kBeside
                                     : view.ambient_shown == AmbientShown::kDifference ? ui::AmbientView::kDifference
                                                                                       : ui::AmbientView::kIndirect;
  s_.rays.heat_map = false;
  s_.instruments.small_multiples = view.small_multiples;
  s_.instruments.move_head = view.head_angle_deg.has_value();
  s_.instruments.head_angle_deg = static_cast<float>(view.head_angle_deg.value_or(0));
  s_.instruments.wipe = static_cast<float>(view.wipe);
  s_.instruments.difference_gain = static_cast<float>(view.difference_gain);
  s_.rays.overlay = view.ray_tree;
  s_.rays.depth_cut = view.depth_cut.has_value();
  s_.rays.cut_depth = view.depth_cut.value_or(s_.rays.cut_depth);
  s_.instruments.probe_mode = view.probe.has_value();
  tools_.probe().tree.reset();
  state_.probe_pending = view.probe.has_value();
  s_.edits.settings = true;
  s_.edits.view = true;
}

void LessonShell::show_place(LessonPlace place) {
  if (s_.lessons.lesson()) present(s_.lessons.show(place));
}

// What the session's presenter answers for a place: A and the compare view cleared, the step's
// scene adopted when it asks, its view applied (a compare's source view first, for A).
void LessonShell::present(const LessonPresenter::Show& show) {
  tools_.compare().clear();
  s_.instruments.compare = 0;
  if (show.adopt_step) adopt_step_scene(*show.adopt_step);
  apply_step_view(show.view);
  state_.applied = true;
  state_.shown_size = {0, 0};
  sync_exercise();
}

const LessonExercise* LessonShell::exercise() const { return s_.session.exercise(); }

int LessonShell::hints_left() const {
  const LessonExercise* e = exercise();
  return e ? static_cast<int>(e->hints.size()) - s_.session.hints_shown() : 0;
}

void LessonShell::show_hint() { s_.session.show_hint(); }

void LessonShell::sync_exercise() {
  if (s_.session.sync_exercise()) formulas_.unfold();
}

void LessonShell::update_lesson() {
  if (!s_.lessons.lesson()) return;
  // A new view size (presenter mode, the panels hidden, the window resized) shows the step
  // again: its probed pixel and its A belong to the size they were made at.
  const std::array<int, 2> size{s_.schedule.width(), s_.schedule.height()};
  if (state_.shown_size == std::array<int, 2>{0, 0}) {
    state_.shown_size = size;
  } else if (size != state_.shown_size && size[0] > 0 && !s_.lessons.exploring()) {
    show_place(s_.lessons.place());
    return;
  }
  if (state_.probe_pending && s_.schedule.snapshot() && s_.schedule.width() > 0 && s_.schedule.height() > 0) {
    if (const auto pixel = probe_in(s_.doc.scene(), s_.schedule.snapshot()->scene().camera, s_.lessons.view(), s_.schedule.width(), s_.schedule.height())) {
      tools_.probe().x = (*pixel)[0];
      tools_.probe().y = (*pixel)[1];
      tools_.refresh_probe();
    }
    state_.probe_pending = false;
  }
  // A compare: A of the source's view first, then the step's own view with the compare on.
  if (s_.lessons.take_a_now()) {
    tools_.snapshot_a(true);
  } else if (s_.lessons.awaiting_a()) {
    if (tools_.compare().dropped()) {
      s_.lessons.a_dropped();  // something changed first: the user is exploring
    } else if (!tools_.compare().requested() && tools_.compare().has_image()) {
      if (const std::optional<LessonPresenter::Show> show = s_.lessons.a_taken()) {
        if (show->adopt_step) adopt_step_scene(*show->adopt_step);
        apply_step_view(show->view);
        s_.instruments.compare = show->view.compare == CompareView::kWipe ? 1 : 2;
        state_.applied = true;
      }
    }
  }
}

void LessonShell::set_presenting(bool on) {
  if (on == state_.presenting) return;
  state_.presenting = on;
  if (on) {
    state_.sidebar_before = s_.sidebar_visible;
    s_.sidebar_visible = false;
  } else {
    s_.sidebar_visible = state_.sidebar_before;
  }
  s_.platform.set_fullscreen(on);
}

bool LessonShell::lesson_key(int key) {
  if (key == GLFW_KEY_F11) {
    if (s_.lessons.lesson() || state_.presenting) set_presenting(!state_.presenting);
    return s_.lessons.lesson() != nullptr;
  }
  if (!s_.lessons.lesson()) return false;
  if (key == GLFW_KEY_ESCAPE && state_.presenting) {
    set_presenting(false);
    return true;
  }
  if (key == GLFW_KEY_RIGHT || key == GLFW_KEY_PAGE_DOWN || key == GLFW_KEY_SPACE) {
    if (const std::optional<LessonPresenter::Show> show = s_.lessons.next()) present(*show);
    return true;
  }
  if (key == GLFW_KEY_LEFT || key == GLFW_KEY_PAGE_UP) {
    if (const std::optional<LessonPresenter::Show> show = s_.lessons.prev()) present(*show);
    return true;
  }
  return false;
}

void LessonShell::sidebar_lessons() {
  ui::LessonPanelView view;
  view.lesson = s_.lessons.lesson();
  view.place = s_.lessons.place();
  view.exploring = s_.lessons.exploring();
  view.presenting = state_.presenting;
  view.error = state_.error;  // every diagnostic, each with its suggestion
  ui::LessonActions actions;
  ui::lessons_panel(view, state_.path_field, actions);
  if (!actions.open.empty()) open_lesson(actions.open);
  if (!s_.lessons.lesson()) return;
  if (actions.go_to >= 0) show_place({actions.go_to, false});
  if (actions.next) lesson_key(GLFW_KEY_RIGHT);
  if (actions.prev) lesson_key(GLFW_KEY_LEFT);
  if (actions.back) show_place(s_.lessons.place());
  if (actions.present) set_presenting(!state_.presenting);
  if (actions.close) close_lesson();
}

float LessonShell::caption_pad() const { return 10 * s_.platform.ui_scale(); }

std::vector<LessonShell::CaptionLine> LessonShell::caption_lines(int step_index, bool revealed) const {
  const Lesson& lesson = *s_.lessons.lesson();
  const LessonStep& step = lesson.steps[static_cast<std::size_t>(step_index)];
  const ImFont* font = s_.platform.caption_font();
  if (font == nullptr) font = ImGui::GetFont();
  // Large in presenter mode (read from the back of a hall), the panel's size beside the panels.
  const float size = state_.presenting ? font->FontSize : font->FontSize * 0.6f;
  const float small = size * 0.7f;
  char head[512];
  std::snprintf(head, sizeof head, "%d/%zu  %s%s", step_index + 1, lesson.steps.size(), step.title.c_str(),
                s_.lessons.exploring() ? "   (exploring)" : "");
  std::vector<CaptionLine> lines = {{head, size, IM_COL32(255, 255, 255, 255)},
                                    {step.caption, small, IM_COL32(225, 225, 225, 255)}};
  if (step.has_question()) lines.push_back({"Q: " + step.question, small, IM_COL32(255, 200, 70, 255)});
  if (step.has_question() && revealed) lines.push_back({"A: " + step.answer, small, IM_COL32(140, 235, 140, 255)});
  if (step.exercise) {
    // `revealed` measures the strip: the task and a long verdict; hints asked for grow the
    // caption up over the image's bottom (no new render).
    const LessonExercise& e = *step.exercise;
    lines.push_back({"Your turn (the " + e.slot + " term, in the Formula panel): " + e.task, small, IM_COL32(255, 200, 70, 255)});
    const int shown = revealed ? 0 : s_.session.hints_shown();
    for (int h = 0; h < shown && h < static_cast<int>(e.hints.size()); ++h) {
      lines.push_back({"Hint " + std::to_string(h + 1) + ": " + e.hints[static_cast<std::size_t>(h)], small,
                       IM_COL32(190, 210, 255, 255)});
    }
    const std::optional<CheckResult>& check = formulas_.last_check();
    if (revealed) {
      lines.push_back({std::string(200, 'x'), small, IM_COL32(0, 0, 0, 0)});
    } else if (!s_.session.formulas().any()) {
      lines.push_back({"Type the formula: the image shows yours.", small, IM_COL32(200, 200, 200, 255)});
    } else if (!check || !formulas_.check_settled()) {
      lines.push_back({"Checking against the reference...", small, IM_COL32(200, 200, 200, 255)});
    } else if (check->match) {
      lines.push_back({"Done: your formula matches the reference at every pixel.", small, IM_COL32(140, 235, 140, 255)});
    } else {
      lines.push_back({"Not yet: " + check_summary(*check), small, IM_COL32(255, 150, 110, 255)});
    }
  }
  const bool posed = step.has_question() && !revealed;
  const LessonPlace place{step_index, revealed};
  const bool last = lesson_next(lesson, place) == place;
  const char* hint = posed ? "\xE2\x86\x92 / space: the answer"
                     : last ? "the end of the lesson   \xE2\x86\x90: back"
                            : "\xE2\x86\x92 / space: next   \xE2\x86\x90: back";
  lines.push_back({std::string(hint) + (state_.presenting ? "   F11 / Esc: leave presenter mode" : "   F11: presenter mode"),
                   small * 0.75f, IM_COL32(170, 170, 170, 255)});
  return lines;
}

float LessonShell::caption_lines_height(const std::vector<CaptionLine>& lines, float width) const {
  const ImFont* font = s_.platform.caption_font();
  if (font == nullptr) font = ImGui::GetFont();
  const float pad = caption_pad();
  const float wrap = std::max(width - 4 * pad, 50.0f);
  float height = pad;
  for (const CaptionLine& l : lines) {
    height += font->CalcTextSizeA(l.size, FLT_MAX, wrap, l.text.c_str()).y + pad * 0.4f;
  }
  return height + pad * 0.6f;
}

float LessonShell::caption_strip_height(float width, float window_height) {
  const Lesson* lesson = s_.lessons.lesson();
  if (lesson == nullptr || width < 1) return 0;
  const StripKey key{lesson->name + '\n' + lesson->title, width, window_height, s_.platform.ui_scale(),
                       state_.presenting, s_.lessons.exploring()};
  if (key == strip_key_) return strip_height_;
  float tallest = 0;
  for (int i = 0; i < static_cast<int>(lesson->steps.size()); ++i) {
    const LessonStep& s = lesson->steps[static_cast<std::size_t>(i)];
    tallest = std::max(tallest, caption_lines_height(caption_lines(i, s.has_question() || s.exercise), width));
  }
  strip_key_ = key;
  strip_height_ = std::min(tallest, kCaptionShare * window_height);
  return strip_height_;
}

void LessonShell::draw_lesson_caption() {
  if (!s_.lessons.lesson() || s_.viewport.width < 1) return;
  const LessonPlace place = s_.lessons.place();
  ImFont* font = s_.platform.caption_font();
  if (font == nullptr) font = ImGui::GetFont();
  const float pad = caption_pad();
  const float wrap = std::max(s_.viewport.width - 4 * pad, 50.0f);
  const std::vector<CaptionLine> lines = caption_lines(place.step, place.revealed);
  // Below the image, in the strip the layout left for it (Viewer::layout); a caption taller
  // than the strip's cap grows up over the image's bottom.
  const float bottom = ImGui::GetIO().DisplaySize.y;
  const float top = std::min(s_.viewport.y + s_.viewport.height, bottom - caption_lines_height(lines, s_.viewport.width));
  ImDrawList* draw = ImGui::GetBackgroundDrawList();
  draw->AddRectFilled(ImVec2(s_.viewport.x, top), ImVec2(s_.viewport.x + s_.viewport.width, bottom), IM_COL32(0, 0, 0, 190));
  float y = top + pad;
  for (const CaptionLine& l : lines) {
    draw->AddText(font, l.size, ImVec2(s_.viewport.x + 2 * pad, y), l.colour, l.text.c_str(), nullptr, wrap);
    y += font->CalcTextSizeA(l.size, FLT_MAX, wrap, l.text.c_str()).y + pad * 0.4f;
  }
  s_.overlay_rects["##lesson_caption"] = ui::ScreenRect{ImVec2(s_.viewport.x, top), ImVec2(s_.viewport.x + s_.viewport.width, bottom)};
}

std::optional<std::string> LessonShell::script_lesson_command(const std::vector<std::string>& w) {
  const std::string& name = w[0];
  if (name == "lesson_open") {
    if (w.size() != 2) return "usage: lesson_open NAME|FILE";
    open_lesson(w[1]);  // a lesson that does not load is reported (stderr, lesson_error) and changes nothing
    return "";
  }
  if (name == "lesson_hint") {
    if (hints_left() <= 0) return "no hint left (or no exercise shown)";
    show_hint();
    return "";
  }
  if (name != "lesson_next" && name != "lesson_prev" && name != "lesson_goto") return std::nullopt;
  if (!s_.lessons.lesson()) return "no lesson is open (lesson_open NAME|FILE)";
  if (name == "lesson_next" || name == "lesson_prev") {
    if (w.size() != 1) return "usage: " + name;
    lesson_key(name == "lesson_next" ? GLFW_KEY_RIGHT : GLFW_KEY_LEFT);
    return "";
  }
  int n = 0;
  const int steps = static_cast<int>(s_.lessons.lesson()->steps.size());
  if (w.size() != 2 || !script::parse_int(w[1], n) || n < 1 || n > steps) {
    return "usage: lesson_goto N, N in 1.." + std::to_string(steps);
  }
  show_place({n - 1, false});
  return "";
}

void LessonShell::write_lesson_state(std::ostream& out) const {
  const Lesson* lesson = s_.lessons.lesson();
  const LessonPlace place = s_.lessons.place();
  out << "lesson=" << (lesson ? lesson->name : "") << "\n"
      << "lesson_step=" << (lesson ? place.step + 1 : 0) << "\n"
      << "lesson_steps=" << (lesson ? lesson->steps.size() : 0) << "\n"
      << "lesson_revealed=" << (place.revealed ? 1 : 0) << "\n"
      << "lesson_title=" << (lesson ? lesson->steps[static_cast<std::size_t>(place.step)].title : "") << "\n"
      << "lesson_exploring=" << (s_.lessons.exploring() ? 1 : 0) << "\n"
      << "lesson_presenting=" << (state_.presenting ? 1 : 0) << "\n"
      << "lesson_comparing=" << (s_.lessons.awaiting_a() ? 1 : 0) << "\n"
      << "lesson_error=" << state_.error.substr(0, state_.error.find('\n')) << "\n"
      << "lesson_exercise=" << (exercise() ? exercise()->slot : "") << "\n"
      << "lesson_hints_shown=" << s_.session.hints_shown() << "\n";
}

}  // namespace phonglab
