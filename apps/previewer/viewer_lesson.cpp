// Lessons in the previewer: a lesson's steps shown as written (scene, term, instruments, probe,
// head, depth cut, compare against A), next and previous from the keys a presentation remote
// sends, presenter mode, exploring and the way back, the caption over the image, and the
// lesson script commands.
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

std::string Viewer::open_lesson(const std::string& lesson_arg) {
  LessonLoad load = load_lesson_arg(lesson_arg);
  if (!load.ok()) {
    lesson_.error = load.error_text();
    std::cerr << "phonglab: " << lesson_.error << "\n";
    return lesson_.error;
  }
  lesson_.error.clear();
  lessons_.offer(std::move(*load.lesson));
  // A lesson replaces the scene: unsaved edits of a file are asked about first; a lesson's own
  // explorations are not (they were never anyone's file).
  const PendingAction action{PendingAction::Kind::kLesson, lessons_.waiting()->name};
  if (lessons_.lesson()) perform(action);
  else request(action);
  return "";
}

void Viewer::start_lesson() {
  const std::optional<LessonPresenter::Show> show = lessons_.start();
  if (!show) return;
  lesson_.unfold_panel = true;
  present(*show);
}

void Viewer::close_lesson() {
  lessons_.close();
  set_presenting(false);
  if (recovery_.after_lesson) {
    recovery_.after_lesson = false;
    find_recovery();
  }
}

void Viewer::adopt_step_scene(int step) {
  const Lesson& lesson = *lessons_.lesson();
  char source[512];
  std::snprintf(source, sizeof source, "lesson '%s', step %d: %s", lesson.name.c_str(), step + 1,
                lesson.steps[static_cast<std::size_t>(step)].scene.c_str());
  doc_.adopt(lesson.steps[static_cast<std::size_t>(step)].prepared_scene, source);
  document_replaced();  // the probe and A are the step view's (apply_step_view, the compare stages)
}

void Viewer::apply_step_view(const StepView& view) {
  render_settings_.term = view.term;
  render_settings_.ambient_view = view.ambient == Ambient::kIndirect ? ui::AmbientView::kIndirect : ui::AmbientView::kConstant;
  rays_.heat_map = false;
  instruments_.small_multiples = view.small_multiples;
  instruments_.move_head = view.head_angle_deg.has_value();
  instruments_.head_angle_deg = static_cast<float>(view.head_angle_deg.value_or(0));
  instruments_.wipe = static_cast<float>(view.wipe);
  instruments_.difference_gain = static_cast<float>(view.difference_gain);
  rays_.overlay = view.ray_tree;
  rays_.depth_cut = view.depth_cut.has_value();
  rays_.cut_depth = view.depth_cut.value_or(rays_.cut_depth);
  instruments_.probe_mode = view.probe.has_value();
  probed_.tree.reset();
  lesson_.probe_pending = view.probe.has_value();
  edits_.settings = true;
  edits_.view = true;
}

void Viewer::show_place(LessonPlace place) {
  if (lessons_.lesson()) present(lessons_.show(place));
}

// What the session's presenter answers for a place: A and the compare view cleared, the step's
// scene adopted when it asks, its view applied (a compare's source view first, for A).
void Viewer::present(const LessonPresenter::Show& show) {
  compare_.image = ProgressiveFrame{};
  compare_.requested = compare_.dropped = false;
  instruments_.compare = 0;
  if (show.adopt_step) adopt_step_scene(*show.adopt_step);
  apply_step_view(show.view);
  lesson_.applied = true;
  lesson_.shown_size = {0, 0};
}

void Viewer::update_lesson() {
  if (!lessons_.lesson()) return;
  // A new view size (presenter mode, the panels hidden, the window resized) shows the step
  // again: its probed pixel and its A belong to the size they were made at.
  const std::array<int, 2> size{render_width_, render_height_};
  if (lesson_.shown_size == std::array<int, 2>{0, 0}) {
    lesson_.shown_size = size;
  } else if (size != lesson_.shown_size && size[0] > 0 && !lessons_.exploring()) {
    show_place(lessons_.place());
    return;
  }
  if (lesson_.probe_pending && snapshot_ && render_width_ > 0 && render_height_ > 0) {
    if (const auto pixel = probe_in(doc_.scene(), snapshot_->scene().camera, lessons_.view(), render_width_, render_height_)) {
      probed_.x = (*pixel)[0];
      probed_.y = (*pixel)[1];
      refresh_probe();
    }
    lesson_.probe_pending = false;
  }
  // A compare: A of the source's view first, then the step's own view with the compare on.
  if (lessons_.take_a_now()) {
    snapshot_a(true);
  } else if (lessons_.awaiting_a()) {
    if (compare_.dropped) {
      lessons_.a_dropped();  // something changed first: the user is exploring
    } else if (!compare_.requested && !compare_.image.pixels.empty()) {
      if (const std::optional<LessonPresenter::Show> show = lessons_.a_taken()) {
        if (show->adopt_step) adopt_step_scene(*show->adopt_step);
        apply_step_view(show->view);
        instruments_.compare = show->view.compare == CompareView::kWipe ? 1 : 2;
        lesson_.applied = true;
      }
    }
  }
}

void Viewer::set_presenting(bool on) {
  if (on == lesson_.presenting) return;
  lesson_.presenting = on;
  if (on) {
    lesson_.sidebar_before = sidebar_visible_;
    sidebar_visible_ = false;
  } else {
    sidebar_visible_ = lesson_.sidebar_before;
  }
  platform_.set_fullscreen(on);
}

bool Viewer::lesson_key(int key) {
  if (key == GLFW_KEY_F11) {
    if (lessons_.lesson() || lesson_.presenting) set_presenting(!lesson_.presenting);
    return lessons_.lesson() != nullptr;
  }
  if (!lessons_.lesson()) return false;
  if (key == GLFW_KEY_ESCAPE && lesson_.presenting) {
    set_presenting(false);
    return true;
  }
  if (key == GLFW_KEY_RIGHT || key == GLFW_KEY_PAGE_DOWN || key == GLFW_KEY_SPACE) {
    if (const std::optional<LessonPresenter::Show> show = lessons_.next()) present(*show);
    return true;
  }
  if (key == GLFW_KEY_LEFT || key == GLFW_KEY_PAGE_UP) {
    if (const std::optional<LessonPresenter::Show> show = lessons_.prev()) present(*show);
    return true;
  }
  return false;
}

void Viewer::sidebar_lessons() {
  ui::LessonPanelView view;
  view.lesson = lessons_.lesson();
  view.place = lessons_.place();
  view.exploring = lessons_.exploring();
  view.presenting = lesson_.presenting;
  view.error = lesson_.error;  // every diagnostic, each with its suggestion
  ui::LessonActions actions;
  ui::lessons_panel(view, lesson_.path_field, actions);
  if (!actions.open.empty()) open_lesson(actions.open);
  if (!lessons_.lesson()) return;
  if (actions.go_to >= 0) show_place({actions.go_to, false});
  if (actions.next) lesson_key(GLFW_KEY_RIGHT);
  if (actions.prev) lesson_key(GLFW_KEY_LEFT);
  if (actions.back) show_place(lessons_.place());
  if (actions.present) set_presenting(!lesson_.presenting);
  if (actions.close) close_lesson();
}

void Viewer::draw_lesson_caption() {
  if (!lessons_.lesson() || viewport_.width < 1) return;
  const Lesson& lesson = *lessons_.lesson();
  const LessonPlace place = lessons_.place();
  const LessonStep& step = lesson.steps[static_cast<std::size_t>(place.step)];
  ImFont* font = platform_.caption_font();
  if (font == nullptr) font = ImGui::GetFont();
  const float scale = platform_.ui_scale();
  // Large in presenter mode (read from the back of a hall), the panel's size beside the panels.
  const float size = lesson_.presenting ? font->FontSize : font->FontSize * 0.6f;
  const float small = size * 0.7f;
  const float pad = 10 * scale;
  const float wrap = std::max(viewport_.width - 4 * pad, 50.0f);
  char head[512];
  std::snprintf(head, sizeof head, "%d/%zu  %s%s", place.step + 1, lesson.steps.size(), step.title.c_str(),
                lessons_.exploring() ? "   (exploring)" : "");
  struct Line {
    std::string text;
    float size;
    ImU32 colour;
  };
  std::vector<Line> lines = {{head, size, IM_COL32(255, 255, 255, 255)}, {step.caption, small, IM_COL32(225, 225, 225, 255)}};
  if (step.has_question()) lines.push_back({"Q: " + step.question, small, IM_COL32(255, 200, 70, 255)});
  if (step.has_question() && place.revealed) lines.push_back({"A: " + step.answer, small, IM_COL32(140, 235, 140, 255)});
  const bool posed = step.has_question() && !place.revealed;
  const bool last = lesson_next(lesson, place) == place;
  const char* hint = posed ? "\xE2\x86\x92 / space: the answer"
                     : last ? "the end of the lesson   \xE2\x86\x90: back"
                            : "\xE2\x86\x92 / space: next   \xE2\x86\x90: back";
  lines.push_back({std::string(hint) + (lesson_.presenting ? "   F11 / Esc: leave presenter mode" : "   F11: presenter mode"),
                   small * 0.75f, IM_COL32(170, 170, 170, 255)});
  float height = pad;
  for (const Line& l : lines) height += font->CalcTextSizeA(l.size, FLT_MAX, wrap, l.text.c_str()).y + pad * 0.4f;
  height += pad * 0.6f;
  const float top = viewport_.y + viewport_.height - height;  // the bottom boxes move above it (draw_overlays)
  ImDrawList* draw = ImGui::GetBackgroundDrawList();
  draw->AddRectFilled(ImVec2(viewport_.x, top), ImVec2(viewport_.x + viewport_.width, viewport_.y + viewport_.height),
                      IM_COL32(0, 0, 0, 190));
  float y = top + pad;
  for (const Line& l : lines) {
    draw->AddText(font, l.size, ImVec2(viewport_.x + 2 * pad, y), l.colour, l.text.c_str(), nullptr, wrap);
    y += font->CalcTextSizeA(l.size, FLT_MAX, wrap, l.text.c_str()).y + pad * 0.4f;
  }
  overlay_rects_["##lesson_caption"] = ui::ScreenRect{ImVec2(viewport_.x, top), ImVec2(viewport_.x + viewport_.width, viewport_.y + viewport_.height)};
}

std::optional<std::string> Viewer::script_lesson_command(const std::vector<std::string>& w) {
  const std::string& name = w[0];
  if (name == "lesson_open") {
    if (w.size() != 2) return "usage: lesson_open NAME|FILE";
    open_lesson(w[1]);  // a lesson that does not load is reported (stderr, lesson_error) and changes nothing
    return "";
  }
  if (name != "lesson_next" && name != "lesson_prev" && name != "lesson_goto") return std::nullopt;
  if (!lessons_.lesson()) return "no lesson is open (lesson_open NAME|FILE)";
  if (name == "lesson_next" || name == "lesson_prev") {
    if (w.size() != 1) return "usage: " + name;
    lesson_key(name == "lesson_next" ? GLFW_KEY_RIGHT : GLFW_KEY_LEFT);
    return "";
  }
  int n = 0;
  const int steps = static_cast<int>(lessons_.lesson()->steps.size());
  if (w.size() != 2 || !script::parse_int(w[1], n) || n < 1 || n > steps) {
    return "usage: lesson_goto N, N in 1.." + std::to_string(steps);
  }
  show_place({n - 1, false});
  return "";
}

void Viewer::write_lesson_state(std::ostream& out) const {
  const Lesson* lesson = lessons_.lesson();
  const LessonPlace place = lessons_.place();
  out << "lesson=" << (lesson ? lesson->name : "") << "\n"
      << "lesson_step=" << (lesson ? place.step + 1 : 0) << "\n"
      << "lesson_steps=" << (lesson ? lesson->steps.size() : 0) << "\n"
      << "lesson_revealed=" << (place.revealed ? 1 : 0) << "\n"
      << "lesson_title=" << (lesson ? lesson->steps[static_cast<std::size_t>(place.step)].title : "") << "\n"
      << "lesson_exploring=" << (lessons_.exploring() ? 1 : 0) << "\n"
      << "lesson_presenting=" << (lesson_.presenting ? 1 : 0) << "\n"
      << "lesson_comparing=" << (lessons_.awaiting_a() ? 1 : 0) << "\n"
      << "lesson_error=" << lesson_.error.substr(0, lesson_.error.find('\n')) << "\n";
}

}  // namespace phonglab
